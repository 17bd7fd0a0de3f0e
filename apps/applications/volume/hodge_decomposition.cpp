// apps/applications/volume/hodge_decomposition.cpp — exact part by a pinned Poisson solve,
// harmonic basis from the Whitney-closed forms on the span of the 1-forms.
#include "polydec/apps/applications/volume/hodge_decomposition.h"

#include <cmath>
#include <stdexcept>

#include "polydec/dec/detail/union_find.h"

namespace polydec {

VolumeHodgeDecomposer::VolumeHodgeDecomposer(const VolumeMesh& mesh, const VolumeRefinementOptions& options,
                                             DecComplex complex) {
  if (mesh.n_cells() == 0)
    throw InvalidMeshError("cell", 0, "volume Hodge decomposition: the mesh has no cells");
  const VolumeRefinement refinement = refine_volume(mesh, options);
  // 1-forms need d1 and star2, not the 3-forms.
  dec_ = volume_dec(mesh, refinement, VolumeDecOptions{.max_degree = 2, .complex = complex});
  const SparseMatrix& d0 = dec_.d[0];
  const SparseMatrix& star1 = dec_.star[1];

  // One pinned vertex per connected component (and every unreferenced vertex).
  const int nV = mesh.n_vertices();
  std::vector<int> parent(nV);
  for (int v = 0; v < nV; ++v) parent[v] = v;
  std::vector<unsigned char> used(nV, 0);
  edges_ = complex == DecComplex::Mesh ? mesh.edges() : Eigen::MatrixX2i(dec_.coarse.simplices(1));
  const Eigen::MatrixX2i& edges = edges_;
  for (long e = 0; e < edges.rows(); ++e) {
    used[edges(e, 0)] = used[edges(e, 1)] = 1;
    parent[find_root(parent, edges(e, 0))] = find_root(parent, edges(e, 1));
  }
  pinned_.assign(nV, 0);
  std::vector<unsigned char> has_pin(nV, 0);
  for (int v = 0; v < nV; ++v) {
    const int r = find_root(parent, v);
    if (!used[v] || !has_pin[r]) pinned_[v] = 1;
    has_pin[r] = 1;
  }
  const SparseMatrix A = d0.transpose() * star1 * d0;
  poisson_ =
      std::make_unique<SparseCholesky>(pin_to_identity(A, pinned_), "Poisson matrix d0^T star1 d0 (pinned)");

  // Closed Whitney forms on the span: the null space of R^T d1^T star2 d1 R (R = I on the mesh complex).
  FormSpan span;
  if (complex == DecComplex::Mesh) {
    span.R = SparseMatrix(star1.rows(), star1.rows());
    span.R.setIdentity();
  } else {
    span = volume_form_span(dec_, mesh, refinement, 1);
  }
  const SparseMatrix d1R = dec_.d[1] * span.R;
  const Eigen::MatrixXd C = Eigen::MatrixXd(SparseMatrix(d1R.transpose() * dec_.star[2] * d1R));
  const Eigen::MatrixXd G = Eigen::MatrixXd(SparseMatrix(span.R.transpose() * star1 * span.R));
  // Generalized problem C v = mu G v (G positive definite on the span): closed forms have mu = 0,
  // and mu is a ratio of two energies of the same form, independent of the mesh's scale only up
  // to the length^-2 of curl over value, so the cut is relative to the largest mu.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(C, G);
  const double top = eig.eigenvalues().cwiseAbs().maxCoeff();
  std::vector<long> closed;
  for (long k = 0; k < eig.eigenvalues().size(); ++k)
    if (eig.eigenvalues()(k) <= 1e-10 * top) closed.push_back(k);
  Eigen::MatrixXd H0(star1.rows(), long(closed.size()));
  for (size_t k = 0; k < closed.size(); ++k) {
    const Eigen::VectorXd g = span.R * eig.eigenvectors().col(closed[k]);
    H0.col(long(k)) = g - d0 * exact_potential(d0.transpose() * (star1 * g));
  }
  // The candidates are G-normalised; exact ones are left with (round-off) zero norm.
  const Eigen::MatrixXd gram = H0.transpose() * (star1 * H0);
  H_.resize(star1.rows(), 0);
  if (gram.rows() == 0) return;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> geig(gram);
  std::vector<long> keep;
  for (long k = 0; k < gram.rows(); ++k)
    if (geig.eigenvalues()(k) > 1e-8) keep.push_back(k);
  H_.resize(star1.rows(), long(keep.size()));
  for (size_t k = 0; k < keep.size(); ++k)
    H_.col(long(k)) = H0 * geig.eigenvectors().col(keep[k]) / std::sqrt(geig.eigenvalues()(keep[k]));
}

Eigen::VectorXd VolumeHodgeDecomposer::exact_potential(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd b = rhs;
  for (long v = 0; v < b.size(); ++v)
    if (pinned_[v]) b(v) = 0;
  return poisson_->solve(b);
}

HodgeParts VolumeHodgeDecomposer::decompose(const Eigen::VectorXd& omega) const {
  const SparseMatrix& d0 = dec_.d[0];
  const SparseMatrix& star1 = dec_.star[1];
  if (omega.size() != star1.rows())
    throw std::invalid_argument("1-form has " + std::to_string(omega.size()) + " values, the mesh has " +
                                std::to_string(star1.rows()) +
                                (dec_.complex == DecComplex::Mesh ? " edges" : " coarse pairs"));
  if (!omega.allFinite()) throw std::invalid_argument("1-form has non-finite values");
  return hodge_parts(omega, exact_potential(d0.transpose() * (star1 * omega)), d0, star1, H_);
}

}  // namespace polydec
