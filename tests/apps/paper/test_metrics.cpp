// tests/apps/paper/test_metrics.cpp — the comparison metrics of apps/paper/metrics.h against independent
// computations: negative off-diagonal ratio by hand, condition number against dense eigenvalues,
// conformal distortion of a deformed copy zero for similarities and positive for a shear.
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include "polydec/apps/paper/metrics.h"
#include "polydec/apps/applications/parametrization.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/operators/registry/laplacians.h"

using namespace polydec;

namespace test_metrics {

TEST_CASE("negative_offdiagonal_ratio counts strictly negative couplings among stored off-diagonals",
          "[metrics]") {
  SparseMatrix S(3, 3);
  std::vector<Eigen::Triplet<double>> t = {{0, 0, -2}, {1, 1, -2}, {2, 2, -1}, {0, 1, 1.5}, {1, 0, 1.5},
                                           {0, 2, 0.5}, {2, 0, 0.5}, {1, 2, -0.25}, {2, 1, -0.25}};
  S.setFromTriplets(t.begin(), t.end());
  CHECK(negative_offdiagonal_ratio(S) == Approx(2.0 / 6.0));
  // The cotangent Laplacian of a Delaunay grid has none; a long thin triangle fan has some.
  CHECK(negative_offdiagonal_ratio(build_operators(triangle_grid(6, 6), parse_laplacian("ours")).S) == 0.0);
  CHECK(negative_offdiagonal_ratio(SparseMatrix(4, 4)) == 0.0);
}

TEST_CASE("condition_number_estimate agrees with the dense eigenvalues", "[metrics]") {
  const Mesh grid = hex_grid(6, 6);
  const OperatorSet ops = build_operators(grid, parse_laplacian("ours"), false);
  // -S + M (lumped) is symmetric positive definite.
  const SparseMatrix A = SparseMatrix(-ops.S) + SparseMatrix(ops.M_lumped.asDiagonal());
  const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(A)).eigenvalues();
  const ConditionEstimate e = condition_number_estimate(A, 2000, 1e-12);
  CHECK(e.lambda_min == Approx(lambda.minCoeff()).epsilon(1e-6));
  CHECK(e.lambda_max == Approx(lambda.maxCoeff()).epsilon(1e-6));
  CHECK(e.condition == Approx(lambda.maxCoeff() / lambda.minCoeff()).epsilon(1e-5));
  CHECK_THROWS_AS(condition_number_estimate(SparseMatrix(0, 0)), std::invalid_argument);
}

TEST_CASE("conformal_distortion of a deformed copy: zero for similarities, positive for a shear", "[metrics]") {
  const Mesh m = add_noise(cube_sphere(4), 0.02, 3);
  Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::MatrixX3d similar = (3.5 * m.positions() * R.transpose()).rowwise() + Eigen::RowVector3d(1, -2, 5);
  CHECK(conformal_distortion(m, similar) < 1e-12);
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
  shear(0, 1) = 0.3;
  const double d = conformal_distortion(m, Eigen::MatrixX3d(m.positions() * shear.transpose()));
  CHECK(d > 0.01);
  CHECK(d < 0.5);
  CHECK_THROWS_AS(conformal_distortion(m, Eigen::MatrixX3d(2, 3)), std::invalid_argument);
}

}  // namespace test_metrics
