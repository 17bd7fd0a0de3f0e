// tests/dec/surface/test_virtual_vertex.cpp — squared-area virtual vertex (eq. 15-16, Appendix A).
#include "polydec/dec/surface/virtual_vertex.h"
#include "tests/support/support.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <random>

using namespace polydec;

namespace test_virtual_vertex {
using test::star_polygon;

namespace {

// Sum of squared fan-triangle areas with apex x.
double fan_energy(const PolygonPositions& X, const Eigen::Vector3d& x) {
  double e = 0;
  for (int k = 0; k < X.rows(); ++k) {
    const Eigen::Vector3d a = X.row(k).transpose() - x, b = X.row((k + 1) % X.rows()).transpose() - x;
    e += 0.25 * a.cross(b).squaredNorm();
  }
  return e;
}

}  // namespace

TEST_CASE("squared-area weights: affine, minimizing, least-norm", "[virtual-vertex]") {
  std::mt19937 rng(11);
  for (int n = 3; n <= 9; ++n)
    for (bool planar : {true, false}) {
      const PolygonPositions X = star_polygon(n, rng, 0.7, 1.3, planar ? 0.0 : 0.3);
      const Eigen::VectorXd w = squared_area_weights(X);
      CHECK(w.sum() == Approx(1.0).epsilon(1e-14));
      const Eigen::Vector3d x = X.transpose() * w;
      // A minimizer: perturbing the apex in any direction does not lower the energy.
      const double e0 = fan_energy(X, x);
      for (int d = 0; d < 3; ++d)
        for (double s : {-1e-4, 1e-4}) {
          Eigen::Vector3d y = x;
          y[d] += s;
          CHECK(fan_energy(X, y) >= e0 - 1e-14);
        }
      // Least norm: w is orthogonal to the null space of [X^T; 1^T].
      Eigen::MatrixXd A(4, n);
      A.topRows(3) = X.transpose();
      A.row(3).setOnes();
      Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
      const Eigen::MatrixXd N = lu.kernel();
      if (lu.rank() < n) CHECK((N.transpose() * w).cwiseAbs().maxCoeff() < 1e-12);
    }
}

TEST_CASE("triangle weights are barycentric and reproduce the minimizer", "[virtual-vertex]") {
  PolygonPositions X(3, 3);
  X << 0, 0, 0, 2, 0, 0, 0, 1, 0;
  const Eigen::VectorXd w = squared_area_weights(X);
  CHECK(w.minCoeff() > 0);
  CHECK(w.sum() == Approx(1.0));
}

}  // namespace test_virtual_vertex
