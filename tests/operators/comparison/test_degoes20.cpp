// tests/operators/comparison/test_degoes20.cpp — de Goes, Butts & Desbrun 2020 per polygon and on meshes.
#include "polydec/operators/comparison/degoes20.h"

#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/surface/refinement.h"
#include "tests/support/plain_cotan.h"
#include "tests/support/support.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <random>

using namespace polydec;

namespace test_degoes20 {

using test::star_polygon;

TEST_CASE("degoes20 gradient is exact on linear functions of planar polygons", "[compare][degoes20]") {
  std::mt19937 rng(8);
  for (int n = 3; n <= 9; ++n) {
    PolygonPositions X = star_polygon(n, rng, 0.6, 1.0, 0.0);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4 * n, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
    X = (X * R.transpose()).rowwise() + Eigen::RowVector3d(1, 2, 3);  // a tilted plane
    const Eigen::Vector3d nrm = R.col(2);
    Eigen::Vector3d g(0.5, -0.25, 1.5);
    g -= g.dot(nrm) * nrm;  // tangential gradient
    const Eigen::VectorXd u = X * g + Eigen::VectorXd::Constant(n, 7.0);
    CHECK((degoes20_local_gradient(X) * u - g).norm() < 1e-12 * g.norm());
    // The stabilization vanishes on linear functions: -u^T S u = A |g|^2 for every lambda.
    double A = 0;
    for (int k = 0; k < n; ++k) A += 0.5 * X.row(k).cross(X.row((k + 1) % n)).dot(nrm.transpose());
    for (double lambda : {0.0, 1.0, 5.0}) {
      const Eigen::MatrixXd S = degoes20_local_stiffness(X, lambda);
      CHECK(-u.dot(S * u) == Approx(A * g.squaredNorm()).epsilon(1e-10));
      CHECK((S - S.transpose()).cwiseAbs().maxCoeff() < 1e-12 * S.cwiseAbs().maxCoeff());
      const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues();
      CHECK(ev.maxCoeff() < 1e-12 * S.cwiseAbs().maxCoeff());
      int rank = 0;
      for (int k = 0; k < n; ++k) rank += ev[k] < -1e-9 * S.cwiseAbs().maxCoeff();
      CHECK(rank == (lambda > 0 ? n - 1 : std::min(2, n - 1)));  // the stabilization fills the rest
    }
  }
}

TEST_CASE("degoes20 operators: cotangent on triangles, S = D G at lambda 0, lumped mass", "[compare][degoes20]") {
  POLYDEC_SHARED_MESH(path, "unit-sphere-low.off");
  const Mesh sphere = read_mesh(path);
  const test::PlainCotan ref = test::plain_cotan(sphere);
  for (double lambda : {0.0, 1.0, 3.0}) {
    const OperatorSet ops = degoes20_operators(sphere, lambda);
    CHECK(test::relative_difference(ops.S, ref.S) < 1e-10);
    // On triangles the gradient is the hat-function gradient: D G is the cotangent Laplacian too.
    CHECK(test::relative_difference(SparseMatrix(ops.D * ops.G), ref.S) < 1e-10);
  }
  const Mesh mesh = add_noise(uv_sphere(8, 10), 0.15, 2);  // non-planar quads
  const OperatorSet o0 = degoes20_operators(mesh, 0.0), o1 = degoes20_operators(mesh, 1.0);
  CHECK(test::relative_difference(SparseMatrix(o0.D * o0.G), o0.S) < 1e-12);
  // The stabilization is outside D G and makes S strictly more negative on non-linear functions.
  CHECK(test::relative_difference(SparseMatrix(o1.D * o1.G), o0.S) < 1e-12);
  const Eigen::VectorXd u = mesh.positions().col(0).array().square();
  CHECK(-u.dot(o1.S * u) > -u.dot(o0.S * u));
  double area = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const PolygonPositions X = face_positions(mesh, f);
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    for (int k = 0; k < X.rows(); ++k) a += 0.5 * X.row(k).cross(X.row((k + 1) % X.rows())).transpose();
    area += a.norm();
  }
  CHECK(o1.M_lumped.sum() == Approx(area).epsilon(1e-12));
}

}  // namespace test_degoes20
