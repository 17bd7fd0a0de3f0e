// operators/cholesky.h — sparse Cholesky factorization of a symmetric positive definite matrix,
// factored once, solved many times; the symbolic analysis is kept for numeric refactorization
// of matrices with the same pattern. Failures raise SolverError naming the operator.
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <stdexcept>
#include <string>

namespace polydec {

class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SparseCholesky {
 public:
  // Factors A (symmetric positive definite; only its lower triangle is read). `name` is the
  // operator's name used in error messages, e.g. "M - t S".
  SparseCholesky(const Eigen::SparseMatrix<double>& A, std::string name);
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  // New values, same pattern: numeric factorization only.
  void refactor(const Eigen::SparseMatrix<double>& A);

  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;

  int rows() const { return rows_; }
  const std::string& name() const { return name_; }
  // "cholmod-supernodal" or "eigen-simplicial-ldlt".
  std::string backend() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string name_;
  int rows_ = 0;
};

}  // namespace polydec
