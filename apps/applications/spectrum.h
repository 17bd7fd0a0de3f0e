// apps/applications/spectrum.h — the k smallest eigenpairs of the generalized problem -S x = lambda M x
// (manifold harmonics, paper section 5.4) by shift-invert Lanczos, using our SparseCholesky
// (operators/solvers/cholesky.h) to apply (-S - sigma M)^-1.
// Lumped (diagonal) M: the equivalent standard problem for z = M^1/2 x, whose shift-inverted
// operator M^1/2 (-S - sigma M)^-1 M^1/2 is symmetric, by our thick-restart Lanczos (full
// reorthogonalization, restarts by one matrix product): Spectra's SymEigsSolver on the same
// operator measured no faster than its generalized solver (docs/benchmarks.md, Spectrum), ours
// 1.6x. Galerkin M: Spectra's generalized shift-invert solver (SymGEigsShiftSolver).
//
// Conventions: S negative semi-definite (operators/surface/laplacian.h), so the eigenvalues are
// lambda >= 0 (0 once per connected component); eigenvectors are M-orthonormal
// (U^T M U = I) and satisfy S U + M U diag(lambda) = 0. Unreferenced vertices (no face, zero
// mass) are left out of the problem and get 0 in every eigenvector.
#pragma once

#include "polydec/operators/registry/laplacians.h"

namespace polydec {

struct SpectrumOptions {
  int k = 10;                 // number of eigenpairs (1 <= k < number of referenced vertices)
  bool lumped_mass = true;    // lumped (default) or Galerkin mass as M
  double shift_factor = 0.1;  // sigma = -shift_factor / (surface area): a small negative shift,
                              // so -S - sigma M is positive definite and the smallest lambda dominate
  double tolerance = 1e-10;   // relative convergence tolerance (Spectra's criterion: Ritz residual
                              // <= tolerance * |Ritz value| of the shift-inverted operator)
  int max_iterations = 1000;  // restarts
  int krylov_size = 0;        // Krylov subspace dimension; 0: spectrum_krylov_size(k, n)
  bool reference = false;     // the reference route, for either mass: Spectra's generalized solver
                              // driven by Eigen's SimplicialLDLT (neither our Lanczos nor CHOLMOD),
                              // the independent check of tests and the benchmark's baseline
};

struct Spectrum {
  Eigen::VectorXd eigenvalues;   // k, ascending
  Eigen::MatrixXd eigenvectors;  // |V| x k (of the operator set's domain), M-orthonormal columns
  double shift = 0;              // the sigma that was used
  int n_converged = 0;
  int n_solves = 0;       // applications of (-S - sigma M)^-1
  std::string method;     // "thick-restart Lanczos (lumped M)" or "Spectra SymGEigsShiftSolver"
};

// The default Krylov subspace dimension for k eigenpairs of an n x n problem: min(n, max(2k + 1, k + 20)).
int spectrum_krylov_size(int k, int n);

// Eigenpairs with any operator set. Throws SolverError when the factorization or Spectra fails
// (Spectra's info() is checked), std::invalid_argument for k out of range or a missing mass.
Spectrum laplacian_spectrum(const OperatorSet& operators, const SpectrumOptions& options = {});
// With the paper's operator ("ours").
Spectrum laplacian_spectrum(const Mesh& mesh, const SpectrumOptions& options = {});

}  // namespace polydec
