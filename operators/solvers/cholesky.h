// operators/solvers/cholesky.h — sparse Cholesky factorization of a symmetric positive definite matrix,
// factored once, solved many times; the symbolic analysis (ordering, elimination tree,
// supernodes) is kept for numeric refactorization of matrices with the same pattern. Backends:
// CHOLMOD supernodal (when built with POLYDEC_HAVE_CHOLMOD; the default) and Eigen's
// SimplicialLDLT (the fallback). Failures raise SolverError naming the operator.
#pragma once

#include "polydec/dec/mesh/eigen_abi.h"
#include <Eigen/Sparse>
#include <memory>
#include <span>
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
// handful of times; pass NestedDissection for many refactorizations of one pattern. BestFill
// orders by AMD and by CHOLMOD's nested dissection (NESDIS) and keeps the one whose factor has
// fewer non-zeros (CHOLMOD's own comparison of the two analyses): worth its ~0.5 s when a factor
// serves many solves, or its analysis several matrices (SparseCholesky::with_values). On FINE
// SPHERE's heat operator NESDIS gives 3.41M non-zeros, METIS 3.56M, AMD 4.14M (docs/benchmarks.md).
enum class CholeskyOrdering { Automatic, Amd, Metis, NestedDissection, BestFill };

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
// A with the rows and columns of the pinned vertices replaced by the identity; with
// `keep_pattern` their off-diagonal entries stay as explicit zeros (and a missing diagonal entry
// is added), so that matrices pinned at different vertices share one pattern.
Eigen::SparseMatrix<double> pin_to_identity(const Eigen::SparseMatrix<double>& A, const std::vector<unsigned char>& pinned,
                                            bool keep_pattern = false);
// The principal submatrix of A on the vertices v with index[v] >= 0, vertex v becoming row and
// column index[v]; index must increase with v on those vertices.
Eigen::SparseMatrix<double> principal_submatrix(const Eigen::SparseMatrix<double>& A, const std::vector<int>& index);

// The BLAS thread policy of the solvers. CHOLMOD's supernodal factorization and its solves do
// their dense work in BLAS, and copy into large supernodes on up to 4 OpenMP threads of CHOLMOD's
// own (kept on the calling thread while the policy is one thread); OpenBLAS's default of one
// thread per core spins against other processes on a loaded machine (measured when this policy
// was introduced: geodesics on HEX SPHERE 7.5-9.1 s wall with the default threads, 3.1-3.4 s
// with one, same CPU time). The policy, applied once before the first factorization (or by
// set_blas_threads()):
//   1. set_blas_threads(n) (the CLI's --blas-threads), else
//   2. the environment variable POLYDEC_BLAS_THREADS (n >= 1, or 0 for OpenBLAS's own default), else
//   3. OPENBLAS_NUM_THREADS or OMP_NUM_THREADS when set (the user asked OpenBLAS directly), else
//   4. one thread (the default).
// OpenBLAS is found at run time (openblas_set_num_threads, looked up with dlsym); with another
// BLAS the policy is reported but cannot be applied.
struct BlasThreads {
  int threads = -1;      // threads in effect (openblas_get_num_threads), -1 when BLAS is not OpenBLAS
  int requested = 1;     // what the policy asked for (0: OpenBLAS's own default)
  std::string source;    // "default", "set_blas_threads", "POLYDEC_BLAS_THREADS", "OPENBLAS_NUM_THREADS",
                         // "OMP_NUM_THREADS"
  bool applied = false;  // whether openblas_set_num_threads was found and called
};
// Applies the policy (once; later calls return the recorded choice). Throws
// std::invalid_argument for a POLYDEC_BLAS_THREADS that is not a count from 0 to 1024.
BlasThreads blas_threads();
// Sets the BLAS threads now (n >= 1; 0: OpenBLAS's own default, one per core) and records
// source "set_blas_threads"; throws std::invalid_argument for n < 0 or n > 1024.
BlasThreads set_blas_threads(int n);

// A symmetric positive definite factorization that factors once and solves many times. With
// CHOLMOD, the first factorization of the process also replaces SuiteSparse_config's malloc and
// calloc, where they are still glibc's own, by wrappers that advise blocks of 2 MB and more onto
// transparent huge pages (fewer page faults and TLB misses; POLYDEC_NO_HUGE_PAGES turns the
// advice off): this affects every CHOLMOD user in the process, with the same memory semantics.
class SparseCholesky {
 public:
  // Analyses and factors A (symmetric positive definite; only its lower triangle is read).
  // `name` is the operator's name used in error messages, e.g. "M - t S".
  SparseCholesky(const Eigen::SparseMatrix<double>& A, std::string name, const CholeskyOptions& options = {});
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  // New values, same pattern: numeric factorization only (the symbolic analysis is reused).
  // SolverError when A's pattern differs from the analysed one.
  void refactor(const Eigen::SparseMatrix<double>& A);
  // A second factorization, of A with the same pattern as this one's matrix (explicit zeros
  // count as entries), reusing this analysis (ordering, supernodes) instead of its own; this one
  // is unchanged. SolverError when the patterns differ.
  SparseCholesky with_values(const Eigen::SparseMatrix<double>& A, std::string name) const;

  // Solves A x = b. Not safe to call concurrently on one object (CHOLMOD keeps workspace). With
  // CHOLMOD, a single column's forward solve skips the supernodes that b's zeros leave at zero
  // (zero in their rows and in every row below them in the elimination tree): the same solution.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  // The same on raw column-major storage: B and X are rows() x n_columns (they may alias).
  void solve(const double* B, double* X, int n_columns) const;
  // Solves A X = B in place for n_columns right-hand sides stored row by row: row v's n_columns
  // values at X + v n_columns (a vertex's values together, as per-vertex passes want them). With
  // CHOLMOD, supernode by supernode with the columns' updates vectorized across the row.
  void solve_rows(double* X, int n_columns) const;
  // The factorization's fill-reducing order: row k of the factor is row factor_order()[k] of A;
  // empty when the solves take A's own order (the Eigen backend). with_values keeps it.
  std::span<const int> factor_order() const;
  // solve_rows on rows in factor_order() (row k's values at X + k n_columns are those of A's row
  // factor_order()[k]), without the copies into and out of that order that solve_rows makes.
  // With `nonzero_rows` (in that order; X zero in every other row; std::invalid_argument for one
  // outside [0, rows())), the forward solve runs over their reach only, as solve_sparse's does.
  void solve_rows_in_factor_order(double* X, int n_columns, std::span<const int> nonzero_rows = {}) const;
  // Solves A x = b for a right-hand side with few non-zeros, b(rows[i]) = values[i] (rows distinct,
  // in [0, rows()); std::invalid_argument otherwise), zero elsewhere. With CHOLMOD the forward solve
  // runs over the rows' reach only (the supernodes from theirs to the root of the supernodal
  // elimination tree, on the supernodal factor itself), the backward solve over the whole factor;
  // equal to solve() up to round-off. Eigen: solve(). Not safe to call concurrently either.
  Eigen::VectorXd solve_sparse(std::span<const int> rows, std::span<const double> values) const;
  // The same into x (rows() values).
  void solve_sparse(std::span<const int> rows, std::span<const double> values, double* x) const;

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
  SparseCholesky(std::string name, int rows);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string name_;
  int rows_ = 0;
};

}  // namespace polydec
