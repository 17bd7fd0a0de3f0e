// apps/spectrum.cpp — shift-invert Lanczos (Spectra) on -S x = lambda M x.
#include "apps/spectrum.h"

#include "operators/cholesky.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>
#include <memory>
#include <stdexcept>

namespace polydec {

namespace {

// Spectra's shift-invert operator: y = (A - sigma B)^-1 x by our sparse Cholesky, refactored
// whenever the shift changes.
class CholeskyShiftInvert {
 public:
  using Scalar = double;
  CholeskyShiftInvert(const SparseMatrix& A, const SparseMatrix& B) : A_(A), B_(B) {}
  Eigen::Index rows() const { return A_.rows(); }
  Eigen::Index cols() const { return A_.cols(); }
  void set_shift(double sigma) {
    const SparseMatrix K = A_ - sigma * B_;
    if (chol_)
      chol_->refactor(K);
    else
      chol_ = std::make_unique<SparseCholesky>(K, "-S - sigma M (spectrum shift-invert)");
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<Eigen::VectorXd>(y_out, rows()) = chol_->solve(Eigen::Map<const Eigen::VectorXd>(x_in, rows()).eval());
  }

 private:
  const SparseMatrix& A_;
  const SparseMatrix& B_;
  std::unique_ptr<SparseCholesky> chol_;
};

// Restricts a square matrix to the rows/columns listed in `keep` (ascending).
SparseMatrix restrict_to(const SparseMatrix& A, const std::vector<int>& keep, int n) {
  std::vector<int> map(n, -1);
  for (size_t i = 0; i < keep.size(); ++i) map[keep[i]] = int(i);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(A.nonZeros());
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (map[it.row()] >= 0 && map[it.col()] >= 0) t.emplace_back(map[it.row()], map[it.col()], it.value());
  SparseMatrix B(Eigen::Index(keep.size()), Eigen::Index(keep.size()));
  B.setFromTriplets(t.begin(), t.end());
  return B;
}

}  // namespace

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
  const SparseMatrix A = restrict_to(-ops.S, keep, nv);
  const SparseMatrix B = restrict_to(M, keep, nv);
  const double area = ops.M_lumped.sum();
  if (!(area > 0)) throw SolverError("spectrum: the mesh has zero area");

  Spectrum result;
  result.shift = -options.shift_factor / area;
  CholeskyShiftInvert op(A, B);
  Spectra::SparseSymMatProd<double> Bop(B);
  const int ncv = std::min(n, std::max(2 * options.k + 1, options.k + 20));
  Spectra::SymGEigsShiftSolver<CholeskyShiftInvert, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert>
      solver(op, Bop, options.k, ncv, result.shift);
  solver.init();
  result.n_converged = int(solver.compute(Spectra::SortRule::LargestMagn, options.max_iterations, options.tolerance,
                                          Spectra::SortRule::SmallestAlge));
  if (solver.info() != Spectra::CompInfo::Successful)
    throw SolverError(fmt::format("spectrum: Spectra did not converge ({} of {} eigenpairs after {} restarts)",
                                  result.n_converged, options.k, options.max_iterations));
  result.eigenvalues = solver.eigenvalues();
  const Eigen::MatrixXd U = solver.eigenvectors();
  result.eigenvectors = Eigen::MatrixXd::Zero(nv, options.k);
  for (int i = 0; i < n; ++i) result.eigenvectors.row(keep[i]) = U.row(i);
  return result;
}

Spectrum laplacian_spectrum(const Mesh& mesh, const SpectrumOptions& options) {
  return laplacian_spectrum(build_operators(mesh, parse_laplacian("ours"), false), options);
}

}  // namespace polydec
