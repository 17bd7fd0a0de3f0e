// apps/paper/metrics.cpp — negative off-diagonal ratio and condition number estimate.
#include "polydec/apps/paper/metrics.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include "polydec/operators/solvers/cholesky.h"

namespace polydec {

double negative_offdiagonal_ratio(const SparseMatrix& S) {
  double largest = 0;
  for (int k = 0; k < S.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(S, k); it; ++it) largest = std::max(largest, std::abs(it.value()));
  long total = 0, negative = 0;
  for (int k = 0; k < S.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(S, k); it; ++it) {
      if (it.row() == it.col()) continue;
      ++total;
      if (it.value() < -1e-12 * largest) ++negative;
    }
  return total ? double(negative) / double(total) : 0.0;
}

namespace {

Eigen::VectorXd random_unit(int n) {
  std::mt19937_64 rng(20200525);
  std::normal_distribution<double> g;
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = g(rng);
  return x.normalized();
}

// Rayleigh quotient iteration of x <- apply(x), returning the limit of x^T apply(x) / x^T x.
template <class Apply>
double power_iteration(int n, Apply&& apply, int max_iterations, double tolerance, int& iterations) {
  Eigen::VectorXd x = random_unit(n);
  double rho = 0;
  for (int it = 0; it < max_iterations; ++it) {
    const Eigen::VectorXd y = apply(x);
    const double next = x.dot(y);
    iterations = it + 1;
    const double norm = y.norm();
    if (!(norm > 0) || !std::isfinite(norm)) return next;
    x = y / norm;
    if (it > 0 && std::abs(next - rho) <= tolerance * std::abs(next)) return next;
    rho = next;
  }
  return rho;
}

}  // namespace

ConditionEstimate condition_number_estimate(const SparseMatrix& A, int max_iterations, double tolerance) {
  if (A.rows() == 0 || A.rows() != A.cols())
    throw std::invalid_argument("condition_number_estimate: A must be square and non-empty");
  const int n = int(A.rows());
  ConditionEstimate e;
  int it_max = 0, it_min = 0;
  e.lambda_max = power_iteration(n, [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(A * x); },
                                 max_iterations, tolerance, it_max);
  const SparseCholesky chol(A, "condition estimate");
  const double inv = power_iteration(n, [&](const Eigen::VectorXd& x) { return chol.solve(x); }, max_iterations,
                                     tolerance, it_min);
  e.lambda_min = inv > 0 ? 1.0 / inv : 0.0;
  e.condition = e.lambda_min > 0 ? e.lambda_max / e.lambda_min : INFINITY;
  e.iterations = std::max(it_max, it_min);
  return e;
}

}  // namespace polydec
