// python/src/operators.cpp — bindings of the assembled operators (operators/surface/laplacian.h,
// operators/surface/gradient.h, operators/registry/laplacians.h) and of the DEC pieces (dec/surface/complex.h,
// dec/surface/hodge_star.h, dec/surface/prolongation.h). Sparse results are Eigen column-major matrices, which
// pybind11 hands over as scipy.sparse.csc_matrix.
#include <set>

#include "bindings.h"
#include "polydec/dec/surface/complex.h"
#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/operators/surface/gradient.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec::python {
namespace {

using Parts = std::set<std::string>;

// What `operators` returns, filled with the GIL released, converted to Python afterwards.
struct Assembled {
  std::string name;
  int n_input_vertices = 0, n_domain_vertices = 0;
  SparseMatrix S, M, G, D;
  Eigen::VectorXd M_lumped;
  bool has_M = false, has_G = false;
};

Assembled assemble(const MeshHandle& h, const std::string& spec, const Parts& parts, int threads,
                   double planarity) {
  const LaplacianChoice choice = parse_laplacian(spec);
  const Mesh& mesh = h.mesh();
  const bool want_G = parts.count("G") || parts.count("D");
  Assembled a;
  a.name = choice.canonical_name();
  if (choice.method == "ours") {
    // The paper's operator, assembled only in the parts asked for (the CLI's `operators` route),
    // on the mesh's cached refinement.
    const std::shared_ptr<const Refinement> ref = h.refinement(VirtualVertexRule::SquaredArea, planarity, threads);
    const Refinement& r = *ref;
    LaplacianParts lp{parts.count("S") > 0, parts.count("M") > 0, parts.count("M_lumped") > 0};
    AssemblyOptions aopt;
    aopt.threads = threads;
    if (lp.stiffness || lp.mass || lp.lumped_mass) {
      Laplacian L = assemble_laplacian(mesh, r, lp, nullptr, aopt);
      a.S.swap(L.S);
      a.M.swap(L.M);
      a.M_lumped.swap(L.M_lumped);
    }
    if (parts.count("G")) a.G = gradient(mesh, r);
    if (parts.count("D")) a.D = divergence(mesh, r);
    a.has_M = a.has_G = true;
    a.n_input_vertices = a.n_domain_vertices = mesh.n_vertices();
    return a;
  }
  OperatorSet ops = build_operators(h.with_planarity(planarity), choice, want_G);
  a.S.swap(ops.S);
  a.M.swap(ops.M);
  a.M_lumped.swap(ops.M_lumped);
  a.G.swap(ops.G);
  a.D.swap(ops.D);
  a.has_M = a.M.rows() > 0;
  a.has_G = a.G.rows() > 0;
  a.n_input_vertices = ops.n_input_vertices;
  a.n_domain_vertices = ops.domain.n_vertices();
  return a;
}

}  // namespace

void register_operators(py::module_& m) {
  m.def("laplacian_names", &laplacian_names);
  m.def("canonical_laplacian",
        [](const std::string& spec) { return parse_laplacian(spec).canonical_name(); });

  m.def("operators", [](const MeshHandle& h, const std::string& spec, const Parts& parts, int threads,
                        double planarity) {
    if (threads < 0) throw std::invalid_argument("threads must be at least 0 (0: all hardware threads)");
    Assembled a = without_gil([&] { return assemble(h, spec, parts, threads, planarity); });
    py::dict d;
    d["name"] = a.name;
    d["n_input_vertices"] = a.n_input_vertices;
    d["n_domain_vertices"] = a.n_domain_vertices;
    d["has_M"] = a.has_M;
    d["has_G"] = a.has_G;
    if (parts.count("S")) d["S"] = to_scipy(a.S);
    if (parts.count("M") && a.has_M) d["M"] = to_scipy(a.M);
    if (parts.count("M_lumped")) d["M_lumped"] = to_numpy(a.M_lumped);
    if (parts.count("G") && a.has_G) d["G"] = to_scipy(a.G);
    if (parts.count("D") && a.has_G) d["D"] = to_scipy(a.D);
    return d;
  });

  m.def("dec", [](const MeshHandle& h, const Parts& parts, const std::string& rule, double planarity) {
    const Mesh& mesh = h.mesh();
    const VirtualVertexRule vrule = parse_virtual_vertex_rule(rule);
    std::map<std::string, SparseMatrix> mats;
    Eigen::VectorXd star0_lumped;
    CoarseComplex K;
    {
      py::gil_scoped_release release;
      const std::shared_ptr<const Refinement> ref = h.refinement(vrule, planarity);
      const Refinement& r = *ref;
      K = CoarseComplex(mesh);
      auto keep = [&](const char* name, SparseMatrix A) { mats[name].swap(A); };  // no copy
      if (parts.count("d0")) keep("d0", K.d0());
      if (parts.count("d1")) keep("d1", K.d1());
      if (parts.count("P0")) keep("P0", prolongation(mesh, r));
      if (parts.count("P1")) keep("P1", prolongation1(mesh, r, K));
      if (parts.count("P2")) keep("P2", prolongation2(mesh, r, K));
      HodgeStarParts hp{parts.count("star0") > 0, parts.count("star0_lumped") > 0, parts.count("star1") > 0,
                        parts.count("star2") > 0};
      if (hp.star0 || hp.star0_lumped || hp.star1 || hp.star2) {
        HodgeStars H = hodge_stars(mesh, r, K, hp);
        if (hp.star0) mats["star0"].swap(H.star0);
        if (hp.star1) mats["star1"].swap(H.star1);
        if (hp.star2) mats["star2"].swap(H.star2);
        star0_lumped.swap(H.star0_lumped);
      }
    }
    py::dict d;
    for (auto& [name, A] : mats) d[py::str(name)] = to_scipy(A);
    if (parts.count("star0_lumped")) d["star0_lumped"] = star0_lumped;
    if (parts.count("pairs")) d["pairs"] = Eigen::MatrixX2i(K.pairs());
    if (parts.count("triples")) d["triples"] = Eigen::MatrixX3i(K.triples());
    if (parts.count("is_edge")) {
      py::array_t<bool> e(K.n_pairs());
      for (int p = 0; p < K.n_pairs(); ++p) e.mutable_data()[p] = K.is_edge(p);
      d["is_edge"] = e;
    }
    return d;
  });

  m.def("surface_dec", [](const MeshHandle& h, const std::string& complex, int max_degree,
                          const std::string& spoke_rule, const std::string& rule, double planarity) {
    const Mesh& mesh = h.mesh();
    SurfaceDecOptions options;
    options.complex = parse_dec_complex(complex);
    options.spoke_rule = parse_spoke_rule(spoke_rule);
    options.max_degree = max_degree;
    const VirtualVertexRule vrule = parse_virtual_vertex_rule(rule);
    SurfaceDec D = without_gil([&] { return surface_dec(mesh, *h.refinement(vrule, planarity), options); });
    py::list d, P, star;
    for (int k = 0; k < D.max_degree; ++k) d.append(to_scipy(D.d[k]));
    for (int k = 0; k <= D.max_degree; ++k) {
      P.append(to_scipy(D.P[k]));
      star.append(to_scipy(D.star[k]));
    }
    py::dict out;
    out["d"] = d;
    out["P"] = P;
    out["star"] = star;
    out["complex"] = to_string(D.complex);
    out["max_degree"] = D.max_degree;
    if (D.complex == DecComplex::Mesh) {
      out["edges"] = Eigen::MatrixX2i(mesh.edges());
      out["face_offsets"] = Eigen::VectorXi(Eigen::Map<const Eigen::VectorXi>(mesh.face_offsets().data(),
                                                                              long(mesh.face_offsets().size())));
      out["face_indices"] = Eigen::VectorXi(Eigen::Map<const Eigen::VectorXi>(mesh.face_indices().data(),
                                                                              long(mesh.face_indices().size())));
      out["faces"] = true;
    } else {
      out["pairs"] = Eigen::MatrixX2i(D.coarse.pairs());
      out["triples"] = Eigen::MatrixX3i(D.coarse.triples());
    }
    return out;
  });
}

}  // namespace polydec::python
