// apps/paper/metrics.h — the comparison metrics of the paper's evaluation that are not an application
// of their own: the share of negative off-diagonal stiffness entries (section 5.5), a condition
// number estimate of a symmetric positive definite system (the Poisson system of section 5.8).
// The other metrics live with their applications: curvature_rmse (apps/applications/curvature.h),
// spherical_harmonics_error (apps/applications/harmonics.h), rmse of geodesic distances (apps/applications/geodesics.h),
// franke_convergence (apps/applications/poisson.h), conformal_distortion against a uv map or a deformed
// copy (apps/applications/parametrization.h).
#pragma once

#include "polydec/dec/mesh/mesh.h"
#include "polydec/operators/surface/laplacian.h"

namespace polydec {

// Fraction of the structurally non-zero off-diagonal entries of S whose value is negative
// (below -1e-12 times the largest |S_ij|): with our sign convention (S negative semi-definite,
// cotangent weights positive off the diagonal) these are the couplings that let the heat flow
// run "backwards" (paper section 5.5: ours 11%, [AW11] 21%, intrinsic Delaunay 0%).
double negative_offdiagonal_ratio(const SparseMatrix& S);

struct ConditionEstimate {
  double lambda_min = 0, lambda_max = 0;
  double condition = 0;  // lambda_max / lambda_min
  int iterations = 0;
};

// Extreme eigenvalues of a symmetric positive definite A by power iteration (lambda_max) and
// inverse iteration with a sparse Cholesky factor (lambda_min), each from a fixed pseudo-random
// start, stopped when the Rayleigh quotient changes by less than `tolerance` relative or after
// `max_iterations`. Rayleigh quotients bound the extremes from inside, so the estimate is a lower
// bound of the true condition number that converges to it. Throws SolverError when A is not
// positive definite, std::invalid_argument for an empty or non-square A.
ConditionEstimate condition_number_estimate(const SparseMatrix& A, int max_iterations = 300,
                                            double tolerance = 1e-6);


}  // namespace polydec
