// operators/solvers/span_solver.cpp — Cholesky of R^T star R on the reduced basis.
#include "polydec/operators/solvers/span_solver.h"

namespace polydec {

SpanSolver::SpanSolver(const Eigen::SparseMatrix<double>& star, FormSpan span, std::string name)
    : star_(star), span_(std::move(span)) {
  const Eigen::SparseMatrix<double> A = span_.R.transpose() * star_ * span_.R;
  chol_ = std::make_unique<SparseCholesky>(A, std::move(name));
}

Eigen::VectorXd SpanSolver::solve(const Eigen::VectorXd& b) const {
  return span_.R * chol_->solve(Eigen::VectorXd(span_.R.transpose() * b));
}

Eigen::VectorXd SpanSolver::canonical(const Eigen::VectorXd& x) const { return solve(star_ * x); }

}  // namespace polydec
