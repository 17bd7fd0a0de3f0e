// operators/cholesky.cpp — SparseCholesky on Eigen's SimplicialLDLT.
#include "operators/cholesky.h"

#include <Eigen/SparseCholesky>

namespace polydec {

struct SparseCholesky::Impl {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
};

namespace {

void check(const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& s, const std::string& name) {
  if (s.info() != Eigen::Success)
    throw SolverError("Cholesky factorization of " + name + " failed (matrix not positive definite?)");
  // A singular positive semi-definite matrix leaves a rounding-level last pivot of either sign:
  // pivots at most kSingularPivot times the largest count as zero.
  constexpr double kSingularPivot = 1e-12;
  const Eigen::VectorXd d = s.vectorD();
  if (d.size() > 0 && (!d.allFinite() || !(d.minCoeff() > kSingularPivot * d.cwiseAbs().maxCoeff())))
    throw SolverError("Cholesky factorization of " + name + " failed: matrix is singular or not positive definite");
}

}  // namespace

SparseCholesky::SparseCholesky(const Eigen::SparseMatrix<double>& A, std::string name)
    : impl_(std::make_unique<Impl>()), name_(std::move(name)), rows_(int(A.rows())) {
  if (A.rows() != A.cols()) throw SolverError("Cholesky of " + name_ + ": matrix is not square");
  impl_->ldlt.analyzePattern(A);
  impl_->ldlt.factorize(A);
  check(impl_->ldlt, name_);
}

SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::refactor(const Eigen::SparseMatrix<double>& A) {
  impl_->ldlt.factorize(A);
  check(impl_->ldlt, name_);
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) const { return impl_->ldlt.solve(b); }
Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const { return impl_->ldlt.solve(B); }

std::string SparseCholesky::backend() const { return "eigen-simplicial-ldlt"; }

}  // namespace polydec
