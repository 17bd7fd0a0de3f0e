// apps/applications/detail/mixed_shift_invert.h — (internal, not installed) the shift-inverted Hodge
// Laplacian of k-forms applied through a quasi-definite mixed system, shared by the surface
// (form_spectrum.cpp) and volume (volume/spectrum.cpp) form spectra.
//
// K = A + C D^-1 C^T (A = d_k^T star_{k+1} d_k, C = star_k d_{k-1}, D = star_{k-1}, all on the
// reduced bases) is never formed (D^-1 makes it dense-ish): (K - sigma B)^-1 x is the first block of
// the solution of [A - sigma B, C; C^T, -D] [y; z] = [x; 0], factored once (sigma < 0) by sparse
// LDL^T (Eigen's SimplicialLDLT with AMD: a quasi-definite matrix has an LDL^T factorization in
// every symmetric ordering, Vanderbei 1995).
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <string>
#include <utility>
#include <vector>

#include "polydec/operators/solvers/cholesky.h"

namespace polydec::mixed_shift_invert_detail {

using SpMat = Eigen::SparseMatrix<double>;

// The 2 x 2 block matrix [A, C; C^T, -D] (A: n1 x n1, C: n1 x n2, D: n2 x n2), lower triangle.
inline SpMat quasi_definite(const SpMat& A, const SpMat& C, const SpMat& D) {
  const Eigen::Index n1 = A.rows(), n2 = D.rows();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(size_t(A.nonZeros() + C.nonZeros() + D.nonZeros()));
  for (int j = 0; j < A.outerSize(); ++j)
    for (SpMat::InnerIterator it(A, j); it; ++it)
      if (it.row() >= it.col()) t.emplace_back(int(it.row()), int(it.col()), it.value());
  for (int j = 0; j < C.outerSize(); ++j)
    for (SpMat::InnerIterator it(C, j); it; ++it) t.emplace_back(int(n1 + it.col()), int(it.row()), it.value());
  for (int j = 0; j < D.outerSize(); ++j)
    for (SpMat::InnerIterator it(D, j); it; ++it)
      if (it.row() >= it.col()) t.emplace_back(int(n1 + it.row()), int(n1 + it.col()), -it.value());
  SpMat N(n1 + n2, n1 + n2);
  N.setFromTriplets(t.begin(), t.end());
  return N;
}

// Spectra's shift-invert operator y = (K - sigma B)^-1 x, K - sigma B the Schur complement of the
// quasi-definite matrix [A - sigma B, C; C^T, -D] on its first block (K = A + C D^-1 C^T). The
// matrices are referenced, not copied. SolverError (naming `name`) when the factorization fails.
class MixedShiftInvert {
 public:
  using Scalar = double;
  MixedShiftInvert(const SpMat& A, const SpMat& B, const SpMat& C, const SpMat& D, std::string name)
      : A_(A), B_(B), C_(C), D_(D), name_(std::move(name)) {}
  Eigen::Index rows() const { return A_.rows(); }
  Eigen::Index cols() const { return A_.rows(); }
  void set_shift(double sigma) {
    const SpMat N = quasi_definite(SpMat(A_ - sigma * B_), C_, D_);
    ldlt_.compute(N);
    if (ldlt_.info() != Eigen::Success)
      throw SolverError("form spectrum: LDL^T of the quasi-definite system " + name_ + " failed");
    rhs_ = Eigen::VectorXd::Zero(N.rows());
  }
  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Index n = rows();
    rhs_.head(n) = Eigen::Map<const Eigen::VectorXd>(x_in, n);
    rhs_.tail(rhs_.size() - n).setZero();
    Eigen::Map<Eigen::VectorXd>(y_out, n) = ldlt_.solve(rhs_).head(n);
  }

 private:
  const SpMat &A_, &B_, &C_, &D_;
  std::string name_;
  Eigen::SimplicialLDLT<SpMat, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  mutable Eigen::VectorXd rhs_;
};

}  // namespace polydec::mixed_shift_invert_detail
