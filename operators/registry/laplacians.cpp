// operators/registry/laplacians.cpp — the named Laplacian registry.
#include "polydec/operators/registry/laplacians.h"

#include <fmt/format.h>

#include <stdexcept>

#include "polydec/operators/comparison/aw11.h"
#include "polydec/operators/comparison/cotan.h"
#include "polydec/operators/comparison/degoes20.h"
#include "polydec/operators/comparison/diamond.h"
#include "polydec/operators/surface/gradient.h"
#include "polydec/operators/surface/split_laplacian.h"
#include "polydec/operators/comparison/intrinsic_delaunay.h"
#include "polydec/operators/comparison/triangulation.h"

namespace polydec {

namespace {

struct MethodInfo {
  const char* name;
  bool needs_parameter;
};

const MethodInfo kMethods[] = {
    {"ours", false},
    {"centroid", false},
    {"abs-area", false},
    {"convex", false},
    {"trace-min", false},
    {"split", false},
    {"triangulated-minarea", false},
    {"triangulated-maxminangle", false},
    {"refined", false},
    {"intrinsic-delaunay", false},
    {"aw11", true},
    {"degoes20", true},
    {"diamond", false},
};

const MethodInfo* find_method(const std::string& name) {
  for (const auto& m : kMethods)
    if (name == m.name) return &m;
  return nullptr;
}

}  // namespace

std::string LaplacianChoice::canonical_name() const {
  return has_parameter ? fmt::format("{}:{:g}", method, parameter) : method;
}

std::vector<std::string> laplacian_names() {
  std::vector<std::string> names;
  for (const auto& m : kMethods)
    names.push_back(m.needs_parameter ? std::string(m.name) + ":LAMBDA" : m.name);
  return names;
}

LaplacianChoice parse_laplacian(const std::string& spec) {
  LaplacianChoice c;
  const auto colon = spec.find(':');
  c.method = spec.substr(0, colon);
  if (colon != std::string::npos) {
    try {
      size_t used = 0;
      c.parameter = std::stod(spec.substr(colon + 1), &used);
      if (used != spec.size() - colon - 1) throw std::invalid_argument("trailing characters");
    } catch (const std::exception&) {
      throw std::invalid_argument("bad parameter in Laplacian '" + spec + "'");
    }
    if (!std::isfinite(c.parameter))
      throw std::invalid_argument("non-finite parameter in Laplacian '" + spec + "'");
    c.has_parameter = true;
  }
  const MethodInfo* m = find_method(c.method);
  if (!m)
    throw std::invalid_argument(
        fmt::format("unknown Laplacian '{}' (known: {})", c.method, fmt::join(laplacian_names(), ", ")));
  if (m->needs_parameter && !c.has_parameter)
    throw std::invalid_argument(
        fmt::format("Laplacian '{}' needs a parameter, e.g. '{}:0.5'", c.method, c.method));
  if (!m->needs_parameter && c.has_parameter)
    throw std::invalid_argument(fmt::format("Laplacian '{}' takes no parameter", c.method));
  if (m->needs_parameter && c.parameter < 0)
    throw std::invalid_argument(fmt::format("Laplacian '{}': parameter must be >= 0", spec));
  return c;
}

namespace {

OperatorSet virtual_vertex_operators(const Mesh& mesh, VirtualVertexRule rule,
                                     const OperatorOptions& options) {
  OperatorSet ops;
  ops.domain = mesh;
  ops.n_input_vertices = mesh.n_vertices();
  RefinementOptions ro;
  ro.rule = rule;
  ro.lift = options.lift;
  Refinement r = refine(mesh, ro);
  AssemblyOptions aopt;
  aopt.threads = options.threads;
  Laplacian L = assemble_laplacian(mesh, r, {}, nullptr, aopt);
  ops.S.swap(L.S);  // swap, not move: std::move copies an Eigen 3.4 SparseMatrix
  ops.M.swap(L.M);
  ops.M_lumped = std::move(L.M_lumped);
  ops.quality = r.quality;
  if (options.with_gradient && options.gradient_with_refinement) {
    SparseMatrix G = gradient(mesh, r), D = divergence(mesh, r);
    ops.G.swap(G);
    ops.D.swap(D);
  }
  ops.refinement = std::move(r);
  return ops;
}

// Several virtual vertices per non-convex face (operators/surface/split_laplacian.h); the paper's
// operators, bit for bit, when no face is split.
OperatorSet split_operators(const Mesh& mesh, const OperatorOptions& options) {
  if (split_refine(mesh).n_faces_split == 0) return virtual_vertex_operators(mesh, VirtualVertexRule::SquaredArea, options);
  OperatorSet ops;
  ops.domain = mesh;
  ops.n_input_vertices = mesh.n_vertices();
  SplitLaplacian L = split_laplacian(mesh, options.with_gradient);
  ops.S.swap(L.S);
  ops.M.swap(L.M);
  ops.M_lumped = std::move(L.M_lumped);
  ops.G.swap(L.G);
  ops.D.swap(L.D);
  ops.quality = L.split.after;
  return ops;
}

void take(OperatorSet& ops, TriangleOperators&& T) {
  ops.S = std::move(T.S);
  ops.M = std::move(T.M);
  ops.M_lumped = std::move(T.M_lumped);
  ops.G = std::move(T.G);
  ops.D = std::move(T.D);
  ops.n_degenerate_triangles = T.n_degenerate;
}

// Triangles of `tri` (the triangulation of `mesh`, in face order) oriented against the
// vector-area normal of the polygon they come from.
int count_folded(const Mesh& mesh, const std::vector<Eigen::Vector3i>& tri) {
  int folded = 0, t = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const PolygonPositions X = face_positions(mesh, f);
    const int n = int(X.rows());
    const Eigen::RowVector3d c = X.colwise().mean();
    Eigen::RowVector3d normal = Eigen::RowVector3d::Zero();
    for (int k = 0; k < n; ++k) normal += (X.row(k) - c).cross(X.row((k + 1) % n) - c);
    for (int k = 0; k < n - 2; ++k, ++t) {
      const Eigen::Vector3d a = mesh.position(tri[t][0]), b = mesh.position(tri[t][1]),
                            d = mesh.position(tri[t][2]);
      if ((b - a).cross(d - a).dot(normal.transpose()) < 0) ++folded;
    }
  }
  return folded;
}

OperatorSet triangulated_operators(const Mesh& mesh, TriangulationRule rule, bool with_gradient) {
  OperatorSet ops;
  ops.domain = mesh;  // same vertices; the triangles need not form a valid mesh (fold-overs)
  ops.n_input_vertices = mesh.n_vertices();
  const auto tris = triangulate(mesh, rule);
  take(ops, cotan_operators(mesh.positions(), tris, with_gradient));
  // Mixed Voronoi lumped mass, as pmp-library and libigl lump the cotangent Laplacian (and as the
  // paper's [Lie03] numbers of Tables 2-3 were made; area/3 gives 6x their curvature error).
  ops.M_lumped = voronoi_areas(length_triangles(mesh.positions(), tris));
  ops.mean_edge_length = mean_edge_length(mesh.positions(), tris);
  ops.n_folded_triangles = count_folded(mesh, tris);
  return ops;
}

OperatorSet refined_operators(const Mesh& mesh, const VirtualLift& lift, bool with_gradient) {
  OperatorSet ops;
  RefinementOptions ro;
  ro.lift = lift;
  const Refinement r = refine(mesh, ro);
  ops.domain = refined_mesh(mesh, r);
  ops.n_input_vertices = mesh.n_vertices();
  ops.quality = r.quality;
  take(ops, cotan_operators(ops.domain, with_gradient));
  std::vector<Eigen::Vector3i> tris(ops.domain.n_faces());
  for (int f = 0; f < ops.domain.n_faces(); ++f) {
    const auto face = ops.domain.face(f);
    tris[f] = Eigen::Vector3i(face[0], face[1], face[2]);
  }
  ops.M_lumped = voronoi_areas(length_triangles(ops.domain.positions(), tris));  // as for the triangulations
  ops.mean_edge_length = ops.domain.mean_edge_length();
  return ops;
}

OperatorSet intrinsic_delaunay_operators(const Mesh& mesh, bool with_gradient) {
  OperatorSet ops;
  ops.domain = mesh;
  ops.n_input_vertices = mesh.n_vertices();
  const auto tris = triangulate(mesh, TriangulationRule::MinSquaredArea);
  ops.n_folded_triangles = count_folded(mesh, tris);
  const IntrinsicTriangulation T = intrinsic_delaunay(mesh.positions(), tris);
  take(ops, cotan_operators(T.triangles, with_gradient));
  ops.M_lumped = voronoi_areas(T.triangles);  // libigl's default for the intrinsic Laplacian (see header)
  ops.n_flips = T.n_flips;
  ops.mean_edge_length = mean_edge_length(mesh.positions(), tris);
  return ops;
}

// Methods built on a Refinement, whose virtual vertices OperatorOptions::lift can move.
bool takes_virtual_lift(const std::string& m) {
  return m == "ours" || m == "centroid" || m == "abs-area" || m == "convex" || m == "trace-min" || m == "refined";
}

// Returns each method's set as a prvalue: `ops = f(...)` would deep-copy S, M, G and D (Eigen
// 3.4's SparseMatrix has no move assignment; ~10 s of the 1.5M-quad heat-method set-up).
OperatorSet operators_by_name(const Mesh& mesh, const LaplacianChoice& choice,
                              const OperatorOptions& options) {
  const bool with_gradient = options.with_gradient;
  const std::string& m = choice.method;
  if (m == "ours") return virtual_vertex_operators(mesh, VirtualVertexRule::SquaredArea, options);
  if (m == "centroid") return virtual_vertex_operators(mesh, VirtualVertexRule::Centroid, options);
  if (m == "abs-area") return virtual_vertex_operators(mesh, VirtualVertexRule::AbsArea, options);
  if (m == "convex") return virtual_vertex_operators(mesh, VirtualVertexRule::Convex, options);
  if (m == "trace-min") return virtual_vertex_operators(mesh, VirtualVertexRule::TraceMin, options);
  if (m == "split") return split_operators(mesh, options);
  if (m == "triangulated-minarea")
    return triangulated_operators(mesh, TriangulationRule::MinSquaredArea, with_gradient);
  if (m == "triangulated-maxminangle")
    return triangulated_operators(mesh, TriangulationRule::MaxMinAngle, with_gradient);
  if (m == "refined") return refined_operators(mesh, options.lift, with_gradient);
  if (m == "intrinsic-delaunay") return intrinsic_delaunay_operators(mesh, with_gradient);
  if (m == "aw11") return aw11_operators(mesh, choice.parameter, with_gradient);
  if (m == "degoes20") return degoes20_operators(mesh, choice.parameter, with_gradient);
  if (m == "diamond") return diamond_operators(mesh, with_gradient);
  throw std::invalid_argument("unknown Laplacian '" + m + "'");
}

}  // namespace

OperatorSet build_operators(const Mesh& mesh, const LaplacianChoice& choice, const OperatorOptions& options) {
  const bool lifted = options.lift.kind != VirtualLiftKind::None;
  if (lifted && !takes_virtual_lift(choice.method))
    throw std::invalid_argument("Laplacian '" + choice.canonical_name() +
                                "' has no virtual vertices to lift (ours, centroid, abs-area, convex, trace-min, refined)");
  OperatorSet ops = operators_by_name(mesh, choice, options);
  ops.name = choice.canonical_name();
  if (lifted) ops.name += "+lift:" + to_string(options.lift);
  if (ops.mean_edge_length == 0.0) ops.mean_edge_length = mesh.mean_edge_length();
  return ops;
}

OperatorSet build_operators(const Mesh& mesh, const LaplacianChoice& choice, bool with_gradient) {
  OperatorOptions options;
  options.with_gradient = with_gradient;
  return build_operators(mesh, choice, options);
}

OperatorSet take_operators(OperatorSet& ops) {
  SparseMatrix S, M, G, D;
  S.swap(ops.S);
  M.swap(ops.M);
  G.swap(ops.G);
  D.swap(ops.D);
  OperatorSet dst = std::move(ops);  // the other members move; the matrices are empty here
  dst.S.swap(S);
  dst.M.swap(M);
  dst.G.swap(G);
  dst.D.swap(D);
  return dst;
}

}  // namespace polydec
