// apps/applications/volume/hodge_decomposition.cpp — exact part by a pinned Poisson solve,
// harmonic basis from closed forms: on the mesh complex by a spanning tree and face peeling
// (sparse, linear in the mesh), on the complete complex from the Whitney-closed forms of the span
// of the 1-forms (dense).
#include "polydec/apps/applications/volume/hodge_decomposition.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <stdexcept>

#include "polydec/dec/detail/union_find.h"

namespace polydec {

Eigen::MatrixXd closed_edge_generators(const SparseMatrix& d0, const SparseMatrix& d1) {
  const long nE = d0.rows(), nV = d0.cols(), nF = d1.rows();
  if (d1.cols() != nE) throw std::invalid_argument("closed_edge_generators: d1 is not |F| x |E| for d0's edges");
  using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  const RowMatrix D0 = d0, D1 = d1;
  // Gauge: a spanning forest of the edges (their forms are zero on it).
  std::vector<int> parent(static_cast<size_t>(nV));
  for (long v = 0; v < nV; ++v) parent[size_t(v)] = int(v);
  std::vector<unsigned char> known(static_cast<size_t>(nE), 0);
  for (long e = 0; e < nE; ++e) {
    int ends[2] = {-1, -1}, n = 0;
    for (RowMatrix::InnerIterator it(D0, e); it && n < 2; ++it) ends[n++] = int(it.col());
    if (n != 2) throw std::invalid_argument("closed_edge_generators: edge " + std::to_string(e) + " has no two ends");
    const int a = find_root(parent, ends[0]), b = find_root(parent, ends[1]);
    if (a != b) {
      parent[size_t(a)] = b;
      known[size_t(e)] = 1;
    }
  }
  // Peeling: a face with exactly one edge not yet known fixes that edge (d1 omega = 0 on it).
  std::vector<int> unknown(static_cast<size_t>(nF), 0), match_face(static_cast<size_t>(nE), -1);
  std::deque<int> queue;
  for (long f = 0; f < nF; ++f) {
    for (RowMatrix::InnerIterator it(D1, f); it; ++it) unknown[size_t(f)] += !known[size_t(it.col())];
    if (unknown[size_t(f)] == 1) queue.push_back(int(f));
  }
  std::vector<int> order;
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop_front();
    if (unknown[size_t(f)] != 1) continue;
    int e = -1;
    for (RowMatrix::InnerIterator it(D1, f); it; ++it)
      if (!known[size_t(it.col())]) e = int(it.col());
    known[size_t(e)] = 1;
    match_face[size_t(e)] = f;
    order.push_back(e);
    for (SparseMatrix::InnerIterator it(d1, e); it; ++it)
      if (--unknown[size_t(it.row())] == 1) queue.push_back(int(it.row()));
  }
  // The edges left free: one form each, propagated through the peel (edges in the order they were
  // fixed: each matched face's other edges were known before it).
  std::vector<long> free_edges;
  for (long e = 0; e < nE; ++e)
    if (!known[size_t(e)]) free_edges.push_back(e);
  const long u = long(free_edges.size());
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(nE, u);
  for (long j = 0; j < u; ++j) W(free_edges[size_t(j)], j) = 1.0;
  for (const int e : order) {
    const int f = match_face[size_t(e)];
    double own = 0;
    Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(u);
    for (RowMatrix::InnerIterator it(D1, f); it; ++it) {
      if (it.col() == e) own = it.value();
      else sum += it.value() * W.row(it.col());
    }
    W.row(e) = -sum / own;
  }
  if (u == 0) return W;
  // The closed combinations: the null space of the remaining faces' conditions (all of them when
  // the peel left exactly b1 edges; otherwise a small dense problem on the free edges' forms).
  const Eigen::MatrixXd R = d1 * W;
  const Eigen::MatrixXd N = R.transpose() * R;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(N);
  // N's entries are sums of products of the (integer) residuals: a closed combination has an
  // eigenvalue at round-off of the largest one, or of the forms' own size when all are closed.
  const double scale = W.cwiseAbs().maxCoeff();
  const double tol = 1e-9 * std::max(eig.eigenvalues().cwiseAbs().maxCoeff(), scale * scale);
  std::vector<long> closed;
  for (long k = 0; k < u; ++k)
    if (eig.eigenvalues()(k) <= tol) closed.push_back(k);
  Eigen::MatrixXd Z(nE, long(closed.size()));
  for (size_t k = 0; k < closed.size(); ++k) Z.col(long(k)) = W * eig.eigenvectors().col(closed[k]);
  return Z;
}

namespace {

const VolumeMesh& with_cells(const VolumeMesh& mesh) {
  if (mesh.n_cells() == 0)
    throw InvalidMeshError("cell", 0, "volume Hodge decomposition: the mesh has no cells");
  return mesh;
}

}  // namespace

VolumeHodgeDecomposer::VolumeHodgeDecomposer(const VolumeMesh& mesh, const VolumeRefinementOptions& options,
                                             DecComplex complex)
    : VolumeHodgeDecomposer(OnRefinement{}, mesh, refine_volume(with_cells(mesh), options), complex) {}

VolumeHodgeDecomposer VolumeHodgeDecomposer::on_refinement(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                                           DecComplex complex) {
  return VolumeHodgeDecomposer(OnRefinement{}, mesh, refinement, complex);
}

VolumeHodgeDecomposer::VolumeHodgeDecomposer(OnRefinement, const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                             DecComplex complex) {
  with_cells(mesh);
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

  Eigen::MatrixXd H0;
  if (complex == DecComplex::Mesh) {
    // Closed forms on the mesh edges from the tree and the peel, normalised in star1.
    H0 = closed_edge_generators(d0, dec_.d[1]);
    for (long k = 0; k < H0.cols(); ++k) {
      Eigen::VectorXd g = H0.col(k);
      g -= d0 * exact_potential(d0.transpose() * (star1 * g));
      const double n = std::sqrt(std::max(0.0, g.dot(star1 * g)));
      H0.col(k) = n > 0 ? Eigen::VectorXd(g / n) : Eigen::VectorXd(g);
    }
  } else {
    // Closed Whitney forms on the span: the null space of R^T d1^T star2 d1 R.
    const FormSpan span = volume_form_span(dec_, mesh, refinement, 1);
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
    H0.resize(star1.rows(), long(closed.size()));
    for (size_t k = 0; k < closed.size(); ++k) {
      const Eigen::VectorXd g = span.R * eig.eigenvectors().col(closed[k]);
      H0.col(long(k)) = g - d0 * exact_potential(d0.transpose() * (star1 * g));
    }
  }
  // The candidates are normalised (G or star1); exact ones are left with (round-off) zero norm.
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
