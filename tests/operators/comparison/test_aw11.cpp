// tests/operators/comparison/test_aw11.cpp — Alexa & Wardetzky 2011 per polygon and on meshes.
#include "polydec/operators/comparison/aw11.h"

#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/surface/refinement.h"
#include "tests/support/plain_cotan.h"
#include "tests/support/support.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <random>

using namespace polydec;

namespace test_aw11 {
using test::star_polygon;

namespace {

double polygon_area(const PolygonPositions& X) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (int k = 0; k < X.rows(); ++k) a += 0.5 * X.row(k).transpose().cross(X.row((k + 1) % X.rows()).transpose());
  return a.norm();
}

}  // namespace

TEST_CASE("aw11 local stiffness: Dirichlet energy of linear functions, kernel term, symmetry", "[compare][aw11]") {
  std::mt19937 rng(2);
  for (int n = 3; n <= 8; ++n) {
    const PolygonPositions X = star_polygon(n, rng, 0.6, 1.0, 0.0);
    const double A = polygon_area(X);
    const Eigen::Vector3d g(0.3, -1.2, 0.0);  // in-plane gradient
    const Eigen::VectorXd u = X * g;
    for (double lambda : {0.0, 0.1, 1.0, 10.0}) {
      const Eigen::MatrixXd S = aw11_local_stiffness(X, lambda);
      CHECK((S - S.transpose()).cwiseAbs().maxCoeff() < 1e-12 * S.cwiseAbs().maxCoeff());
      CHECK((S * Eigen::VectorXd::Ones(n)).cwiseAbs().maxCoeff() < 1e-12 * S.cwiseAbs().maxCoeff());
      // -u^T S u = A |g|^2 for every lambda: the kernel term vanishes on linear functions.
      CHECK(-u.dot(S * u) == Approx(A * g.squaredNorm()).epsilon(1e-10));
      const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues();
      CHECK(ev.maxCoeff() < 1e-12 * S.cwiseAbs().maxCoeff());
      // Rank: 2 (consistency term) + (n - 2) (kernel term) - 1 (constants) for lambda > 0; 2 for lambda = 0.
      int rank = 0;
      for (int k = 0; k < n; ++k) rank += ev[k] < -1e-9 * S.cwiseAbs().maxCoeff();
      CHECK(rank == (lambda > 0 ? n - 1 : std::min(2, n - 1)));
    }
  }
}

TEST_CASE("aw11 on a non-planar polygon uses the plane of the vector area", "[compare][aw11]") {
  std::mt19937 rng(4);
  const PolygonPositions X = star_polygon(6, rng, 0.6, 1.0, 0.2);
  // Invariance under rigid motions.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const PolygonPositions Y = (X * R.transpose()).rowwise() + Eigen::RowVector3d(5, -1, 2);
  const Eigen::MatrixXd S = aw11_local_stiffness(X, 0.5), SY = aw11_local_stiffness(Y, 0.5);
  CHECK((S - SY).cwiseAbs().maxCoeff() < 1e-12 * S.cwiseAbs().maxCoeff());
  // The kernel term only sees the projected polygon: lambda-derivative of S equals the planar
  // projection's, while the consistency term keeps the 3D midpoints.
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (int k = 0; k < 6; ++k) a += X.row(k).transpose().cross(X.row((k + 1) % 6).transpose());
  const Eigen::Vector3d nrm = a.normalized();
  const PolygonPositions Xp = X - (X * nrm) * nrm.transpose();
  const Eigen::MatrixXd dS = aw11_local_stiffness(X, 1.0) - aw11_local_stiffness(X, 0.0);
  const Eigen::MatrixXd dSp = aw11_local_stiffness(Xp, 1.0) - aw11_local_stiffness(Xp, 0.0);
  CHECK((dS - dSp).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("aw11 operators on meshes: cotangent on triangles, block gradient, lumped mass", "[compare][aw11]") {
  POLYDEC_SHARED_MESH(path, "unit-sphere-low.off");
  const Mesh sphere = read_mesh(path);
  const OperatorSet tri = aw11_operators(sphere, 0.7);
  CHECK(test::relative_difference(tri.S, test::plain_cotan(sphere).S) < 1e-10);

  // Irregular planar hexagons and boundary pentagons/quads: add_noise moves vertices in 3D, so the
  // out-of-plane part is removed (on non-planar faces |G_f u| is not |grad u|, see below).
  const Mesh noisy = add_noise(hex_grid(5, 5), 0.1, 9);
  Eigen::MatrixX3d planar = noisy.positions();
  planar.col(2).setZero();
  const Mesh mesh = noisy.with_positions(planar);
  const OperatorSet ops = aw11_operators(mesh, 0.5);
  CHECK(ops.M.size() == 0);  // AW11 define no Galerkin mass
  double area = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) area += polygon_area(face_positions(mesh, f));
  CHECK(ops.M_lumped.sum() == Approx(area).epsilon(1e-12));
  REQUIRE(int(ops.G_blocks.size()) == mesh.n_faces() + 1);
  CHECK(ops.G_blocks.back() == mesh.n_halfedges());
  CHECK(test::relative_difference(SparseMatrix(ops.D * ops.G), ops.S) < 1e-12);
  // For a linear function every face block has norm |grad u| (what the heat method normalizes).
  const Eigen::Vector3d g(0.8, 0.6, 0.0);
  const Eigen::VectorXd Gu = ops.G * (mesh.positions() * g);
  for (int f = 0; f < mesh.n_faces(); ++f)
    CHECK(Gu.segment(ops.G_blocks[f], ops.G_blocks[f + 1] - ops.G_blocks[f]).norm() == Approx(g.norm()).epsilon(1e-10));
  // Non-planar faces, lambda = 0: B^T d X is the cross-product matrix of the vector area, so
  // |G_f u| is the length of g projected to the plane orthogonal to the face's vector area.
  const OperatorSet bent = aw11_operators(noisy, 0.0);
  const Eigen::VectorXd Gb = bent.G * (noisy.positions() * g);
  double worst_tilt = 0;
  for (int f = 0; f < noisy.n_faces(); ++f) {
    const PolygonPositions X = face_positions(noisy, f);
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    for (int k = 0; k < X.rows(); ++k) a += X.row(k).transpose().cross(X.row((k + 1) % X.rows()).transpose());
    const Eigen::Vector3d nrm = a.normalized(), g_plane = g - g.dot(nrm) * nrm;
    worst_tilt = std::max(worst_tilt, 1 - g_plane.norm() / g.norm());
    CHECK(Gb.segment(bent.G_blocks[f], bent.G_blocks[f + 1] - bent.G_blocks[f]).norm() ==
          Approx(g_plane.norm()).epsilon(1e-10));
  }
  CHECK(worst_tilt > 1e-4);  // the faces are really non-planar, or the check above proves nothing
}

}  // namespace test_aw11
