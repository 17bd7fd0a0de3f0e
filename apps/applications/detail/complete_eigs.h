// apps/applications/detail/complete_eigs.h — (internal, not installed) the k smallest eigenpairs of a
// symmetric pencil (A, B) by Spectra's shift-invert solver, complete in the copies of multiple
// eigenvalues: passes on the pencil deflated by every pair found so far. Shared by the 0-form
// spectrum (spectrum.cpp) and the 1- and 2-form spectra (form_spectrum.cpp).
#pragma once

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "polydec/apps/applications/spectrum.h"
#include "polydec/operators/solvers/cholesky.h"

namespace polydec::complete_eigs_detail {

// Op (y = (A - sigma B)^-1 x, factored at sigma) deflated by B-orthonormal vectors X:
// y = (I - X X^T B) (A - sigma B)^-1 (I - B X X^T) x. With Spectra's B-inner product this is the
// shift-inverted pencil restricted to the B-orthogonal complement of X: the pairs in X get Ritz
// value 0 (lambda = infinity) and are not found again.
template <class Op>
class DeflatedShiftInvert {
 public:
  using Scalar = double;
  DeflatedShiftInvert(const Op& op, const Eigen::SparseMatrix<double>& B, const Eigen::MatrixXd& X, double sigma)
      : op_(op), B_(B), X_(X), sigma_(sigma), t_(op.rows()) {}
  Eigen::Index rows() const { return op_.rows(); }
  Eigen::Index cols() const { return op_.cols(); }
  void set_shift(double sigma) {
    if (sigma != sigma_) throw SolverError("spectrum: the deflated operator keeps its shift");
  }
  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    t_ = x;
    if (X_.cols() > 0) t_.noalias() -= B_ * (X_ * (X_.transpose() * x));
    op_.perform_op(t_.data(), y_out);
    if (X_.cols() > 0) y.noalias() -= X_ * (X_.transpose() * (B_ * y));
  }

 private:
  const Op& op_;
  const Eigen::SparseMatrix<double>& B_;
  const Eigen::MatrixXd& X_;
  double sigma_;
  mutable Eigen::VectorXd t_;
};

struct Pairs {
  Eigen::VectorXd values;   // k, ascending
  Eigen::MatrixXd vectors;  // n x k, B-orthonormal
  int n_converged = 0;      // pairs found over all passes (>= k)
  int n_solves = 0;         // applications of op
};

// The k smallest eigenpairs of (A, B) from `op` = (A - shift B)^-1, already factored at `shift`.
// Spectra from one start vector, like any single-vector Krylov method, meets further copies of a
// multiple eigenvalue only through round-off and often converges without them (cube_sphere(6),
// k = 4: two of the three copies of lambda_1; hex_sphere(1)'s 1-forms, k = 10: one of four). So
// solve again on the pencil deflated by every pair found so far, until a pass finds nothing below
// the k-th value found (the PETSc engine's rule): a converged pass returns the deflated pencil's
// smallest values, so a missed copy below the k-th value would be among them. `who` names the
// caller in SolverError messages; ncv is the first pass's Krylov dimension.
template <class Op>
Pairs smallest_pairs(const Op& op, const Eigen::SparseMatrix<double>& B, int k, int ncv, double shift,
                     int max_iterations, double tolerance, const std::string& who) {
  const int n = int(B.rows());
  Spectra::SparseSymMatProd<double> Bop(B);
  Eigen::MatrixXd X(n, 0);  // B-orthonormal pairs found
  std::vector<double> lambda;
  Pairs out;
  for (int pass = 0; pass <= k; ++pass) {
    const int nev = std::min(k, n - int(X.cols()) - 1);
    if (nev < 1) break;
    const int pass_ncv = pass == 0 ? ncv : spectrum_krylov_size(nev, n - int(X.cols()));
    DeflatedShiftInvert<Op> dop(op, B, X, shift);
    Spectra::SymGEigsShiftSolver<DeflatedShiftInvert<Op>, Spectra::SparseSymMatProd<double>,
                                 Spectra::GEigsMode::ShiftInvert>
        solver(dop, Bop, nev, std::max(pass_ncv, nev + 1), shift);
    solver.init();
    const int converged = int(
        solver.compute(Spectra::SortRule::LargestMagn, max_iterations, tolerance, Spectra::SortRule::SmallestAlge));
    out.n_solves += int(solver.num_operations());
    if (solver.info() != Spectra::CompInfo::Successful)
      throw SolverError(fmt::format("{}: Spectra did not converge ({} of {} eigenpairs after {} restarts{})", who,
                                    converged, nev, max_iterations,
                                    pass > 0 ? fmt::format(", completeness pass {}", pass) : ""));
    // The k-th smallest value found before this pass; new values below it are missed pairs.
    std::vector<double> sorted = lambda;
    std::sort(sorted.begin(), sorted.end());
    const double bound =
        int(sorted.size()) >= k ? sorted[size_t(k) - 1] : std::numeric_limits<double>::infinity();
    const Eigen::VectorXd values = solver.eigenvalues();
    const Eigen::MatrixXd U = solver.eigenvectors();
    const double scale =
        std::max(std::abs(bound) < INFINITY ? std::abs(bound) : 0.0, values.cwiseAbs().maxCoeff());
    int below = 0;
    for (int i = 0; i < int(values.size()); ++i) {
      if (values[i] < bound - 1e-9 * scale) ++below;
      // B-orthogonal to the pairs found (twice, against rounding), B-normalized.
      Eigen::VectorXd u = U.col(i);
      for (int twice = 0; twice < 2 && X.cols() > 0; ++twice) u.noalias() -= X * (X.transpose() * (B * u));
      u /= std::sqrt(u.dot(B * u));
      X.conservativeResize(Eigen::NoChange, X.cols() + 1);
      X.col(X.cols() - 1) = u;
      lambda.push_back(values[i]);
    }
    out.n_converged = int(lambda.size());
    if (below == 0) break;
  }
  if (int(lambda.size()) < k)
    throw SolverError(fmt::format("{}: {} of {} eigenpairs found", who, lambda.size(), k));
  std::vector<int> order(lambda.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return lambda[size_t(a)] < lambda[size_t(b)]; });
  out.values.resize(k);
  out.vectors.resize(n, k);
  for (int c = 0; c < k; ++c) {
    out.values[c] = lambda[size_t(order[size_t(c)])];
    out.vectors.col(c) = X.col(order[size_t(c)]);
  }
  return out;
}

}  // namespace polydec::complete_eigs_detail
