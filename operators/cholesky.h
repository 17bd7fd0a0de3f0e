// operators/cholesky.h — sparse Cholesky factorization of a symmetric positive definite matrix,
// factored once, solved many times; the symbolic analysis (ordering, elimination tree,
// supernodes) is kept for numeric refactorization of matrices with the same pattern. Backends:
// CHOLMOD supernodal (when built with POLYDEC_HAVE_CHOLMOD; the default) and Eigen's
// SimplicialLDLT (the fallback). Failures raise SolverError naming the operator.
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace polydec {

class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class CholeskyBackend {
  Automatic,  // CHOLMOD when available, else Eigen
  Cholmod,    // CHOLMOD supernodal LL^T (throws SolverError when not compiled in)
  Eigen,      // Eigen SimplicialLDLT with AMD ordering
};

// Fill-reducing ordering for the CHOLMOD backend (Eigen always uses AMD). Automatic is AMD,
// chosen by measurement on FINE SPHERE's M - 0.1 S (docs/benchmarks.md): nested dissection
// (NESDIS) cuts the flops from 1.2 to 0.65 GFLOP and the numeric factorization by ~20%, but its
// analysis costs ~0.5 s more, so AMD is faster whenever a matrix is factored fewer than a
// handful of times; pass NestedDissection for many refactorizations of one pattern.
enum class CholeskyOrdering { Automatic, Amd, Metis, NestedDissection };

struct CholeskyOptions {
  CholeskyBackend backend = CholeskyBackend::Automatic;
  CholeskyOrdering ordering = CholeskyOrdering::Automatic;
  // CHOLMOD supernode amalgamation relaxed to 4x its defaults: a faster factorization (FINE
  // SPHERE: ~155 vs ~240 ms) but twice the stored entries of L (explicit zeros), so each solve
  // is slower (14 vs 10 ms). false: CHOLMOD's defaults, for many solves per factorization.
  bool relaxed_supernodes = true;
};

// The matrices the solvers are given, written column by column into compressed storage (no
// triplet lists: on the 1.5M-quad mesh those took seconds).
// A with the rows and columns of the pinned vertices replaced by the identity.
Eigen::SparseMatrix<double> pin_to_identity(const Eigen::SparseMatrix<double>& A, const std::vector<unsigned char>& pinned);
// The principal submatrix of A on the vertices v with index[v] >= 0, vertex v becoming row and
// column index[v]; index must increase with v on those vertices.
Eigen::SparseMatrix<double> principal_submatrix(const Eigen::SparseMatrix<double>& A, const std::vector<int>& index);

class SparseCholesky {
 public:
  // Analyses and factors A (symmetric positive definite; only its lower triangle is read).
  // `name` is the operator's name used in error messages, e.g. "M - t S".
  SparseCholesky(const Eigen::SparseMatrix<double>& A, std::string name, const CholeskyOptions& options = {});
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  // New values, same pattern: numeric factorization only (the symbolic analysis is reused).
  void refactor(const Eigen::SparseMatrix<double>& A);

  // Solves A x = b. Not safe to call concurrently on one object (CHOLMOD keeps workspace).
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  // The same on raw column-major storage: B and X are rows() x n_columns (they may alias).
  void solve(const double* B, double* X, int n_columns) const;

  int rows() const { return rows_; }
  const std::string& name() const { return name_; }
  // "cholmod-supernodal" or "eigen-simplicial-ldlt".
  std::string backend() const;
  // Non-zeros of the factor L (a measure of fill), and the ordering used ("amd", "metis", ...).
  double factor_nonzeros() const;
  std::string ordering() const;

  // Whether the CHOLMOD backend was compiled in.
  static bool cholmod_available();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string name_;
  int rows_ = 0;
};

}  // namespace polydec
