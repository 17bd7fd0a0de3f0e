// apps/metrics.h — the comparison metrics of the paper's evaluation that are not an application
// of their own: the share of negative off-diagonal stiffness entries (section 5.5), a condition
// number estimate of a symmetric positive definite system (the Poisson system of section 5.8),
// and the conformal distortion between a mesh and a deformed copy of it (section 5.1, Table 1).
// The other metrics live with their applications: curvature_rmse (apps/curvature.h),
// spherical_harmonics_error (apps/harmonics.h), rmse of geodesic distances (apps/geodesics.h),
// franke_convergence (apps/poisson.h), conformal_distortion against a uv map
// (apps/parametrization.h).
#pragma once

#include "dec/mesh.h"
#include "operators/laplacian.h"

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

// Conformal distortion between a mesh and a deformed copy with the same connectivity
// (`deformed`: |V| x 3 positions), measured like conformal_distortion of a uv map: the
// area-weighted root-mean-square difference (radians) of every face corner's angle, weights
// |vector area of the face in the input| / (face valence). Used for the conformalized curvature
// flow of Table 1 (input mesh against the flowed, spherical one).
double conformal_distortion(const Mesh& mesh, const Eigen::MatrixX3d& deformed);

}  // namespace polydec
