// apps/applications/spectrum.cpp — shift-invert Lanczos on -S x = lambda M x: our thick-restart Lanczos for
// lumped M, Spectra's generalized solver for Galerkin M.
#include "polydec/apps/applications/spectrum.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>

#include "polydec/apps/applications/detail/complete_eigs.h"
#include "polydec/dec/detail/huge_pages.h"
#include "polydec/operators/solvers/cholesky.h"

namespace polydec {

namespace {

// Spectra's shift-invert operator: y = (A - sigma B)^-1 x, refactored whenever the shift changes,
// by our SparseCholesky or (the reference route) by Eigen's SimplicialLDLT.
class ShiftInvert {
 public:
  using Scalar = double;
  ShiftInvert(const SparseMatrix& A, const SparseMatrix& B, bool reference) : A_(A), B_(B), reference_(reference) {}
  Eigen::Index rows() const { return A_.rows(); }
  Eigen::Index cols() const { return A_.cols(); }
  void set_shift(double sigma) {
    const SparseMatrix K = A_ - sigma * B_;
    if (reference_) {
      ldlt_.compute(K);
      if (ldlt_.info() != Eigen::Success)
        throw SolverError("spectrum: Eigen's SimplicialLDLT failed on -S - sigma M (reference route)");
    } else if (chol_) {
      chol_->refactor(K);
    } else {
      chol_ = std::make_unique<SparseCholesky>(K, "-S - sigma M (spectrum shift-invert)");
    }
  }
  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    if (reference_)
      y = ldlt_.solve(x);
    else
      chol_->solve(x_in, y_out, 1);
  }

 private:
  const SparseMatrix& A_;
  const SparseMatrix& B_;
  bool reference_;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  std::unique_ptr<SparseCholesky> chol_;
};

// w -= V h with h = V^T w, repeated once when the first pass cancelled more than 30% of w
// (Daniel-Gragg-Kaufman-Stewart: "twice is enough"); returns the accumulated h.
Eigen::VectorXd orthogonalize(const Eigen::Ref<const Eigen::MatrixXd>& V, Eigen::Ref<Eigen::VectorXd> w) {
  const double before = w.norm();
  Eigen::VectorXd h = V.transpose() * w;
  w.noalias() -= V * h;
  if (w.norm() < 0.7 * before) {
    const Eigen::VectorXd h2 = V.transpose() * w;
    w.noalias() -= V * h2;
    h += h2;
  }
  return h;
}

// A deterministic start vector with components along every eigenvector (almost surely).
Eigen::VectorXd start_vector(int n) {
  Eigen::VectorXd v(n);
  std::uint64_t x = 0x9E3779B97F4A7C15ull;
  for (int i = 0; i < n; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    v[i] = double(x >> 11) * 0x1.0p-53 - 0.5;
  }
  return v / v.norm();
}

// The k largest eigenpairs of the symmetric positive semi-definite operator `op` (y = op(x) on
// raw vectors) by Lanczos with full reorthogonalization and thick restarts (Wu & Simon 2000):
// a cycle extends the basis V to m vectors, V^T op V = H is computed column by column during
// the orthogonalization, and the restart keeps the best p Ritz vectors (one n x m x p product)
// plus the residual direction. Convergence (as Spectra): |beta_m y_m| <= tol * |theta| per
// wanted Ritz pair (theta, y). Returns the Ritz values (descending) and vectors.
template <class Op>
int thick_restart_lanczos(const Op& op, int n, int k, int m, double tol, int max_restarts, Eigen::VectorXd& theta_out,
                          Eigen::MatrixXd& Z, int& n_ops, const Eigen::VectorXd* v0 = nullptr) {
  // Fresh pages cost ~13 us each on the CI's virtual machine: huge pages for the two bases.
  Eigen::MatrixXd V(n, m + 1), W(n, m);
  advise_huge_pages(V.data(), sizeof(double) * V.size());
  advise_huge_pages(W.data(), sizeof(double) * W.size());
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m, m);
  V.col(0) = v0 ? *v0 : start_vector(n);
  int p = 0;  // kept Ritz vectors: columns [0, p) of V, v_p the current Lanczos vector
  const double eps23 = std::pow(std::numeric_limits<double>::epsilon(), 2.0 / 3.0);
  for (int restart = 0; restart <= max_restarts; ++restart) {
    double beta = 0;
    for (int j = p; j < m; ++j) {
      op(V.col(j).data(), V.col(j + 1).data());
      ++n_ops;
      auto w = V.col(j + 1);
      if (j == p) {
        H.col(j).head(j + 1) = orthogonalize(V.leftCols(j + 1), w);  // couples to every kept Ritz vector
      } else {
        // Three-term recurrence, then one full reorthogonalization pass against the rounding
        // errors (op v_j is orthogonal to v_0 .. v_{j-2} in exact arithmetic).
        const double alpha = V.col(j).dot(w), beta_prev = H(j - 1, j);
        w -= alpha * V.col(j) + beta_prev * V.col(j - 1);
        const Eigen::VectorXd h = V.leftCols(j + 1).transpose() * w;
        w.noalias() -= V.leftCols(j + 1) * h;
        H.col(j).head(j + 1) = h;
        H(j, j) += alpha;
        H(j - 1, j) += beta_prev;
      }
      beta = w.norm();
      if (!(beta > 1e-12 * std::max(1.0, H(j, j)))) {
        // Invariant subspace found: continue with any direction orthogonal to V (none once V
        // spans everything; then every residual is zero and the cycle ends converged).
        beta = 0;
        if (j + 1 < n) {
          w = start_vector(n + j + 1).head(n);
          orthogonalize(V.leftCols(j + 1), w);
          orthogonalize(V.leftCols(j + 1), w);
          w /= w.norm();
        } else {
          w.setZero();
        }
      } else {
        w /= beta;
      }
      if (j + 1 < m) H(j, j + 1) = beta;  // overwritten by the next column's h (the same in exact arithmetic)
    }
    // Rayleigh-Ritz on the upper triangle of H (computed as v_i^T op v_j, i <= j).
    const Eigen::MatrixXd Hs = H.selfadjointView<Eigen::Upper>();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Hs);
    if (es.info() != Eigen::Success) throw SolverError("spectrum: Rayleigh-Ritz eigensolver failed");
    // Descending order: the wanted (largest) Ritz values first.
    const Eigen::VectorXd theta = es.eigenvalues().reverse();
    const Eigen::MatrixXd Y = es.eigenvectors().rowwise().reverse();
    int n_conv = 0;
    for (int i = 0; i < k; ++i)
      if (std::abs(beta * Y(m - 1, i)) <= tol * std::max(eps23, std::abs(theta[i]))) ++n_conv;
    if (n_conv == k || restart == max_restarts) {
      theta_out = theta.head(k);
      Z.topLeftCorner(n, k).noalias() = V.leftCols(m) * Y.leftCols(k);  // Z: at least n x k, allocated by the caller
      return n_conv;
    }
    // Thick restart: keep p Ritz vectors (Spectra's rule: k plus up to half the remaining room).
    p = std::min(m - 1, k + std::min(n_conv, (m - k) / 2));
    W.leftCols(p).noalias() = V.leftCols(m) * Y.leftCols(p);
    V.leftCols(p) = W.leftCols(p);
    V.col(p) = V.col(m);
    H.setZero();
    H.diagonal().head(p) = theta.head(p);
  }
  return 0;
}

// Lanczos from one start vector meets further copies of a multiple eigenvalue only through
// round-off and can converge without them (hex_sphere(3), k = 9: 4 of the 5 copies of lambda = 6).
// The check: Lanczos, converged, on op deflated by the pairs found (z -> (I - Z Z^T) op (I - Z Z^T) z,
// their Ritz values mapped to 0), for its `batch` largest pairs; a value above the k-th one found is
// a missed pair: the missed pairs are merged in, the k largest kept, and the check repeated until a
// pass finds none (the PETSc engine's rule). A converged pass returns the deflated operator's
// largest values, so a missed pair above the k-th value is among them. (A cheaper screen, one
// unconverged 12-step cycle, missed pairs within 0.2% of the k-th value: cube_sphere(6), k = 19.)
// theta (descending) and the top n rows of Z (orthonormal columns) are updated in place.
template <class Op>
void complete_multiplicities(const Op& op, int n, const SpectrumOptions& options, Eigen::VectorXd& theta,
                             Eigen::MatrixXd& Z, int& n_ops) {
  const int k = options.k;
  const int kk = std::min(std::max(3, k / 4), n - k - 1);  // pairs per pass
  if (kk < 1) return;
  // Another start vector than the first run's.
  const Eigen::VectorXd v0 = start_vector(2 * n).tail(n).normalized();
  for (int pass = 0; pass < k; ++pass) {
    const Eigen::MatrixXd Zk = Z.topRows(n).leftCols(k);
    Eigen::VectorXd u(n);
    auto deflated = [&](const double* x, double* y) {
      u = Eigen::Map<const Eigen::VectorXd>(x, n);
      u.noalias() -= Zk * (Zk.transpose() * u);
      op(u.data(), y);
      Eigen::Map<Eigen::VectorXd> w(y, n);
      w.noalias() -= Zk * (Zk.transpose() * w);
    };
    const double margin = theta[k - 1] * (1 + 1e3 * options.tolerance);
    Eigen::VectorXd theta2;
    Eigen::MatrixXd Z2(n, kk);
    thick_restart_lanczos(deflated, n, kk, std::min(n - k, spectrum_krylov_size(kk, n)), options.tolerance,
                          options.max_iterations, theta2, Z2, n_ops, &v0);
    int missed = 0;
    while (missed < kk && theta2[missed] > margin) ++missed;
    if (missed == 0) return;
    // Merge: the missed pairs, orthogonalized against the found ones, then the k largest of all.
    Eigen::MatrixXd all(n, k + missed);
    all.leftCols(k) = Zk;
    Eigen::VectorXd values(k + missed);
    values.head(k) = theta.head(k);
    for (int i = 0; i < missed; ++i) {
      Eigen::VectorXd w = Z2.col(i);
      orthogonalize(all.leftCols(k + i), w);
      all.col(k + i) = w / w.norm();
      values[k + i] = theta2[i];
    }
    std::vector<int> order(size_t(k + missed));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return values[a] > values[b]; });
    for (int i = 0; i < k; ++i) {
      theta[i] = values[order[size_t(i)]];
      Z.col(i).head(n) = all.col(order[size_t(i)]);
    }
  }
}

}  // namespace

int spectrum_krylov_size(int k, int n) { return std::min(n, std::max(2 * k + 1, k + 20)); }

Spectrum laplacian_spectrum(const OperatorSet& ops, const SpectrumOptions& options) {
  const int nv = int(ops.S.rows());
  if (!options.lumped_mass && ops.M.size() == 0)
    throw std::invalid_argument("spectrum: Laplacian '" + ops.name + "' defines no unlumped mass");
  // Vertices with positive lumped mass take part; the others (no face) are left out.
  std::vector<int> keep;
  for (int v = 0; v < nv; ++v)
    if (ops.M_lumped[v] > 0) keep.push_back(v);
  const int n = int(keep.size());
  if (options.k < 1 || options.k >= n)
    throw std::invalid_argument(fmt::format("spectrum: k = {} must lie in [1, {})", options.k, n));

  SparseMatrix M;
  if (options.lumped_mass) {
    M.resize(nv, nv);
    M.reserve(Eigen::VectorXi::Constant(nv, 1));
    for (int v = 0; v < nv; ++v) M.insert(v, v) = ops.M_lumped[v];
  } else {
    M = ops.M;
  }
  std::vector<int> index(size_t(nv), -1);
  for (int i = 0; i < n; ++i) index[size_t(keep[size_t(i)])] = i;
  const SparseMatrix A = principal_submatrix(-ops.S, index);
  const SparseMatrix B = principal_submatrix(M, index);
  const double area = ops.M_lumped.sum();
  if (!(area > 0)) throw SolverError("spectrum: the mesh has zero area");

  Spectrum result;
  result.shift = -options.shift_factor / area;
  const int ncv = options.krylov_size > 0 ? std::clamp(options.krylov_size, options.k + 1, n)
                                          : spectrum_krylov_size(options.k, n);
  if (options.lumped_mass && !options.reference) {
    // Standard problem for z = M^1/2 x: (M^-1/2 A M^-1/2 - sigma I)^-1 = M^1/2 (A - sigma M)^-1 M^1/2,
    // symmetric positive definite; its largest eigenvalues theta give lambda = sigma + 1 / theta.
    // CHOLMOD's default supernodes: a few hundred solves follow one factorization.
    const Eigen::VectorXd m = B.diagonal();
    const Eigen::VectorXd sq = m.cwiseSqrt();
    CholeskyOptions copt;
    copt.relaxed_supernodes = false;
    const SparseCholesky chol(A - result.shift * B, "-S - sigma M (spectrum shift-invert)", copt);
    Eigen::VectorXd tmp(n);
    auto op = [&](const double* x, double* y) {
      tmp = sq.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(x, n));
      chol.solve(tmp.data(), y, 1);
      Eigen::Map<Eigen::VectorXd>(y, n).array() *= sq.array();
    };
    Eigen::VectorXd theta;
    Eigen::MatrixXd& Z = result.eigenvectors;  // z = M^1/2 x, rows of `keep` only for now
    Z.resize(nv, options.k);
    advise_huge_pages(Z.data(), sizeof(double) * Z.size());
    result.n_converged = thick_restart_lanczos(op, n, options.k, ncv, options.tolerance, options.max_iterations,
                                               theta, Z, result.n_solves);
    result.method = "thick-restart Lanczos (lumped M)";
    if (result.n_converged < options.k)
      throw SolverError(fmt::format("spectrum: Lanczos did not converge ({} of {} eigenpairs after {} restarts)",
                                    result.n_converged, options.k, options.max_iterations));
    complete_multiplicities(op, n, options, theta, Z, result.n_solves);
    result.eigenvalues = (result.shift + theta.array().inverse()).matrix();
    // x = M^-1/2 z, moved from row i to row keep[i] (keep ascending: in place, last row first).
    for (int c = 0; c < options.k; ++c) {
      double* z = Z.col(c).data();
      for (int i = n - 1; i >= 0; --i) z[keep[i]] = z[i] / sq[i];
      for (int v = 0, i = 0; v < nv; ++v)
        if (i < n && keep[i] == v) ++i;
        else z[v] = 0;
    }
  } else {
    // Complete in the copies of multiple eigenvalues (complete_eigs.h).
    ShiftInvert op(A, B, options.reference);
    op.set_shift(result.shift);
    result.method = options.reference ? "Spectra SymGEigsShiftSolver + Eigen SimplicialLDLT (reference)"
                                      : "Spectra SymGEigsShiftSolver";
    const complete_eigs_detail::Pairs pairs = complete_eigs_detail::smallest_pairs(
        op, B, options.k, ncv, result.shift, options.max_iterations, options.tolerance, "spectrum");
    result.n_converged = pairs.n_converged;
    result.n_solves += pairs.n_solves;
    result.eigenvalues = pairs.values;
    result.eigenvectors = Eigen::MatrixXd::Zero(nv, options.k);
    for (int c = 0; c < options.k; ++c)
      for (int i = 0; i < n; ++i) result.eigenvectors(keep[i], c) = pairs.vectors(i, c);
  }
  return result;
}

Spectrum laplacian_spectrum(const Mesh& mesh, const SpectrumOptions& options) {
  return laplacian_spectrum(build_operators(mesh, parse_laplacian("ours"), false), options);
}

}  // namespace polydec
