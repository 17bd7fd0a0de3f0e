// apps/applications/form_spectrum.cpp — Hodge Laplacian eigenpairs of Whitney 1- and 2-forms:
// Spectra's generalized shift-invert solver on a quasi-definite LDL^T of the mixed system.
#include "polydec/apps/applications/form_spectrum.h"

#include <fmt/format.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "polydec/apps/applications/detail/form_pencil.h"
#include "polydec/apps/applications/hodge_decomposition.h"
#include "polydec/apps/applications/spectrum.h"
#include "polydec/dec/surface/complex.h"
#include "polydec/dec/surface/form_span.h"
#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/solvers/span_solver.h"

namespace polydec {
namespace form_spectrum_detail {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

SpMat diagonal_matrix(const Eigen::VectorXd& d) {
  SpMat D(d.size(), d.size());
  D.reserve(Eigen::VectorXi::Constant(d.size(), 1));
  for (Eigen::Index i = 0; i < d.size(); ++i) D.insert(i, i) = d[i];
  return D;
}

double star_norm(const SpMat& star, const Eigen::VectorXd& x) {
  return std::sqrt(std::max(0.0, x.dot(star * x)));
}

}  // namespace
}  // namespace form_spectrum_detail

const char* form_kind_name(FormKind kind) {
  switch (kind) {
    case FormKind::Exact:
      return "exact";
    case FormKind::Coexact:
      return "co-exact";
    case FormKind::Harmonic:
      return "harmonic";
  }
  return "?";
}

FormSpectrum form_spectrum(const Mesh& mesh, const FormSpectrumOptions& options) {
  using namespace form_spectrum_detail;
  if (options.degree != 1 && options.degree != 2)
    throw std::invalid_argument(fmt::format("form spectrum: degree {} must be 1 or 2", options.degree));
  if (mesh.n_faces() == 0) throw InvalidMeshError("mesh", -1, "form spectrum: the mesh has no faces");
  const Refinement ref = refine(mesh, options.refinement);
  const bool on_mesh = options.complex == DecComplex::Mesh;
  const CoarseComplex cx = on_mesh ? CoarseComplex() : CoarseComplex(mesh);
  HodgeStars H;
  SpMat d0, d1;
  FormSpan span1;
  if (on_mesh) {
    // The mesh complex: positive definite stars, so the reduced bases are the identity.
    HodgeStarParts parts;
    parts.star1 = parts.star2 = false;
    H = hodge_stars(mesh, ref, cx, parts);  // star0 and its lumped version
    MeshComplexForms F = mesh_complex_forms(mesh, ref, SpokeRule::AreaConsistent, {.star1 = true, .star2 = true});
    H.star1.swap(F.star1);
    H.star2 = SpMat(F.star2.asDiagonal());
    d0 = mesh_d0(mesh);
    d1 = mesh_d1(mesh);
    span1.R = SpMat(mesh.n_edges(), mesh.n_edges());
    span1.R.setIdentity();
  } else {
    H = hodge_stars(mesh, ref, cx);
    d0 = cx.d0();
    d1 = cx.d1();
    span1 = form_span(mesh, ref, cx, 1);
  }
  const SpMat& R1 = span1.R;
  const SpMat B1 = R1.transpose() * H.star1 * R1;
  const double area = H.star0_lumped.sum();
  if (!(area > 0)) throw SolverError("form spectrum: the mesh has zero area");

  FormSpectrum out;
  out.quality = ref.quality;
  out.degree = options.degree;
  out.shift = -options.shift_factor / area;
  SpMat A, B, C, D, R;
  std::string name;
  if (options.degree == 1) {
    // Unreferenced vertices (zero mass, no pair) are left out of the vertex block.
    std::vector<int> index(size_t(mesh.n_vertices()), -1);
    int n0 = 0;
    for (int v = 0; v < mesh.n_vertices(); ++v)
      if (H.star0_lumped[v] > 0) index[size_t(v)] = n0++;
    const SpMat M0full = options.lumped_mass ? diagonal_matrix(H.star0_lumped) : H.star0;
    D = principal_submatrix(M0full, index);
    SpMat keep(mesh.n_vertices(), n0);  // selection of the kept vertices
    keep.reserve(Eigen::VectorXi::Constant(n0, 1));
    for (int v = 0; v < mesh.n_vertices(); ++v)
      if (index[size_t(v)] >= 0) keep.insert(v, index[size_t(v)]) = 1;
    A = R1.transpose() * d1.transpose() * H.star2 * d1 * R1;
    B = B1;
    C = R1.transpose() * H.star1 * d0 * keep;
    R = R1;
    name = "[d1^T star2 d1 - sigma star1, star1 d0; d0^T star1, -M0]";
  } else {
    if (on_mesh) {
      R = SpMat(mesh.n_faces(), mesh.n_faces());
      R.setIdentity();
    } else {
      R = form_span(mesh, ref, cx, 2).R;
    }
    B = R.transpose() * H.star2 * R;
    A = SpMat(B.rows(), B.cols());
    C = R.transpose() * H.star2 * d1 * R1;
    D = B1;
    name = "[-sigma star2, star2 d1; d1^T star2, -star1]";
  }
  form_pencil_detail::solve(A, B, C, D, R, name, options, "form spectrum", out);
  if (!options.decompose) return out;

  const int k = options.k;
  // Eigenvalues below this (relative to the first nonzero scale 1 / area) count as zero.
  const double zero = 1e-8 / area;
  if (options.degree == 1) {
    const HodgeDecomposer hd(mesh, options.refinement, options.complex);
    for (int i = 0; i < k; ++i) {
      const HodgeParts p = hd.decompose(out.eigenvectors.col(i));
      out.exact.col(i) = p.exact;
      out.coexact.col(i) = p.coexact;
      out.harmonic.col(i) = p.harmonic;
      out.norm_exact[i] = p.norm_exact;
      out.norm_coexact[i] = p.norm_coexact;
      out.norm_harmonic[i] = p.norm_harmonic;
    }
  } else {
    // u = d1 (delta u) / lambda with delta u = star1^+ d1^T star2 u, when lambda != 0 (star1^-1 on
    // the mesh complex).
    std::unique_ptr<SpanSolver> S1span;
    std::unique_ptr<SparseCholesky> S1mesh;
    if (on_mesh)
      S1mesh = std::make_unique<SparseCholesky>(H.star1, "star1");
    else
      S1span = std::make_unique<SpanSolver>(H.star1, span1, "star1");
    for (int i = 0; i < k; ++i) {
      const Eigen::VectorXd u = out.eigenvectors.col(i);
      if (std::abs(out.eigenvalues[i]) > zero) {
        const Eigen::VectorXd rhs = d1.transpose() * (H.star2 * u);
        const Eigen::VectorXd delta = on_mesh ? S1mesh->solve(rhs) : S1span->solve(rhs);
        out.exact.col(i) = d1 * delta / out.eigenvalues[i];
      }
      out.harmonic.col(i) = u - out.exact.col(i);
      out.norm_exact[i] = star_norm(H.star2, out.exact.col(i));
      out.norm_coexact[i] = 0;
      out.norm_harmonic[i] = star_norm(H.star2, out.harmonic.col(i));
    }
  }
  form_pencil_detail::classify(out);
  return out;
}

Eigen::MatrixX3d whitney_vectors_at_virtual_vertices(const Mesh& mesh, const Refinement& refinement,
                                                     const Eigen::VectorXd& cochain, DecComplex complex) {
  check_refinement(mesh, refinement, "whitney_vectors_at_virtual_vertices");
  const bool on_mesh = complex == DecComplex::Mesh;
  const CoarseComplex cx = on_mesh ? CoarseComplex() : CoarseComplex(mesh);
  const long n1 = on_mesh ? mesh.n_edges() : cx.n_pairs();
  if (cochain.size() != n1)
    throw std::invalid_argument(fmt::format("whitney vectors: the cochain has {} values, the mesh {} {}",
                                            cochain.size(), n1, on_mesh ? "edges" : "pairs"));
  const Eigen::VectorXd c =
      (on_mesh ? mesh_prolongation1(mesh, refinement) : prolongation1(mesh, refinement, cx)) * cochain;
  const int ne = mesh.n_edges();
  Eigen::MatrixX3d U = Eigen::MatrixX3d::Zero(mesh.n_faces(), 3);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const Eigen::Vector3d xv = refinement.virtual_points.row(f).transpose();
    int used = 0;
    for (int h = mesh.face_offsets()[f]; h < mesh.face_offsets()[f + 1]; ++h) {
      const int hn = mesh.halfedge_next(h);
      const Eigen::Vector3d ea = mesh.position(mesh.halfedge_source(h)) - xv;
      const Eigen::Vector3d eb = mesh.position(mesh.halfedge_target(h)) - xv;
      // u = alpha ea + beta eb with u . ea = -c_av, u . eb = -c_bv (2 x 2 Gram system).
      const double g11 = ea.dot(ea), g12 = ea.dot(eb), g22 = eb.dot(eb), det = g11 * g22 - g12 * g12;
      if (!(det > 1e-24 * g11 * g22)) continue;  // degenerate fan triangle: no Whitney form
      const double ra = -c[ne + h], rb = -c[ne + hn];
      const double alpha = (g22 * ra - g12 * rb) / det, beta = (g11 * rb - g12 * ra) / det;
      U.row(f) += (alpha * ea + beta * eb).transpose();
      ++used;
    }
    if (used > 0) U.row(f) /= double(used);
  }
  return U;
}

Eigen::VectorXd whitney2_face_densities(const Mesh& mesh, const Refinement& refinement,
                                        const Eigen::VectorXd& cochain, DecComplex complex) {
  check_refinement(mesh, refinement, "whitney2_face_densities");
  const bool on_mesh = complex == DecComplex::Mesh;
  const CoarseComplex cx = on_mesh ? CoarseComplex() : CoarseComplex(mesh);
  const long n2 = on_mesh ? mesh.n_faces() : cx.n_triples();
  if (cochain.size() != n2)
    throw std::invalid_argument(fmt::format("whitney 2-form densities: the cochain has {} values, the mesh {} {}",
                                            cochain.size(), n2, on_mesh ? "faces" : "triples"));
  const Eigen::VectorXd t =
      (on_mesh ? mesh_prolongation2(mesh, refinement) : prolongation2(mesh, refinement, cx)) * cochain;
  Eigen::VectorXd integral = Eigen::VectorXd::Zero(mesh.n_faces()), area = integral;
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    const int f = mesh.halfedge_face(h);
    const Eigen::Vector3d a = mesh.position(mesh.halfedge_source(h)),
                          b = mesh.position(mesh.halfedge_target(h));
    const Eigen::Vector3d x = refinement.virtual_points.row(f).transpose();
    integral[f] += refined_triangle_sign(mesh, h) * t[h];
    area[f] += 0.5 * (b - a).cross(x - a).norm();
  }
  for (int f = 0; f < mesh.n_faces(); ++f) integral[f] = area[f] > 0 ? integral[f] / area[f] : 0;
  return integral;
}

}  // namespace polydec
