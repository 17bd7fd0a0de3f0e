// tests/dec/surface/test_quadratic.cpp — the quadratic elements' building blocks: the P2 triangle
// matrices against an independent basis and quadrature, the per-face least-norm weights
// (quadratic reproduction, minimum norm, invariance, the P2 basis on triangles) and the global
// quadratic prolongation.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <random>

#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/surface/quadratic.h"
#include "tests/support/feec_meshes.h"
#include "tests/support/p2_reference.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_quadratic_dec {
namespace {

// A random rigid motion and scale applied to the rows of X.
PolygonPositions moved(const PolygonPositions& X, std::mt19937& rng, double scale) {
  std::normal_distribution<double> N(0.0, 1.0);
  const Eigen::Quaterniond q = Eigen::Quaterniond(N(rng), N(rng), N(rng), N(rng)).normalized();
  const Eigen::RowVector3d t(N(rng), N(rng), N(rng));
  PolygonPositions Y = (scale * X * q.toRotationMatrix().transpose()).rowwise() + 10 * scale * t;
  return Y;
}

// A random quadratic polynomial of the plane spanned by the orthonormal (a, b) through o.
struct PlaneQuadratic {
  Eigen::Vector3d o, a, b;
  Eigen::Matrix<double, 6, 1> c;
  double operator()(const Eigen::Vector3d& x) const {
    const double u = (x - o).dot(a), v = (x - o).dot(b);
    return c[0] + c[1] * u + c[2] * v + c[3] * u * u + c[4] * u * v + c[5] * v * v;
  }
};

// The planar polygon's plane from three of its corners (not the SVD the library uses).
PlaneQuadratic plane_quadratic(const PolygonPositions& X, std::mt19937& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  PlaneQuadratic q;
  q.o = X.row(0).transpose();
  q.a = (X.row(1) - X.row(0)).transpose().normalized();
  const Eigen::Vector3d n = q.a.cross(Eigen::Vector3d(X.row(2) - X.row(0)));
  q.b = n.normalized().cross(q.a);
  for (int i = 0; i < 6; ++i) q.c[i] = N(rng);
  return q;
}

// Values of q at the 2n coarse nodes and the n + 1 targets of quadratic_face_weights.
std::pair<Eigen::VectorXd, Eigen::VectorXd> sample(const PolygonPositions& X, const Eigen::Vector3d& xf,
                                                   const PlaneQuadratic& q) {
  const int n = int(X.rows());
  Eigen::VectorXd coarse(2 * n), target(n + 1);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d a = X.row(k).transpose(), b = X.row((k + 1) % n).transpose();
    coarse[k] = q(a);
    coarse[n + k] = q(0.5 * (a + b));
    target[1 + k] = q(0.5 * (a + xf));
  }
  target[0] = q(xf);
  return {coarse, target};
}

}  // namespace

TEST_CASE("P2 triangle matrices equal an independent basis and quadrature", "[quadratic]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> N(0.0, 1.0);
  for (double scale : {1e-6, 1.0, 1e5})
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Vector3d p0 = scale * Eigen::Vector3d(N(rng), N(rng), N(rng));
      const Eigen::Vector3d p1 = scale * Eigen::Vector3d(N(rng), N(rng), N(rng));
      const Eigen::Vector3d p2 = scale * Eigen::Vector3d(N(rng), N(rng), N(rng));
      const Matrix6d K = p2_triangle_stiffness(p0, p1, p2), M = p2_triangle_mass(p0, p1, p2);
      const test::P2Reference ref = test::p2_reference(p0, p1, p2);
      CHECK((K - ref.K).norm() <= 1e-11 * ref.K.norm());
      CHECK((M - ref.M).norm() <= 1e-11 * ref.M.norm());
      const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
      // Constants: zero energy, mass sums to the area; the gradient of a linear function a.x:
      // energy |a_tangential|^2 area.
      CHECK((K * Matrix6d::Ones().col(0)).cwiseAbs().maxCoeff() <= 1e-12 * K.norm());
      CHECK(std::abs(M.sum() - area) <= 1e-13 * area);
      const Eigen::Vector3d a(N(rng), N(rng), N(rng)), nrm = (p1 - p0).cross(p2 - p0).normalized();
      Eigen::Matrix<double, 6, 1> u;
      const Eigen::Vector3d nodes[6] = {p0, p1, p2, (p0 + p1) / 2, (p1 + p2) / 2, (p2 + p0) / 2};
      for (int i = 0; i < 6; ++i) u[i] = a.dot(nodes[i]);
      const Eigen::Vector3d at = a - a.dot(nrm) * nrm;
      CHECK(std::abs(u.dot(K * u) - at.squaredNorm() * area) <= 1e-11 * a.squaredNorm() * area);
    }
  // A zero-area triangle: no stiffness, no mass.
  const Eigen::Vector3d x(0, 0, 0), y(1, 1, 1);
  CHECK(p2_triangle_stiffness(x, y, 2 * y).norm() == 0.0);
  CHECK(p2_triangle_mass(x, y, 2 * y).norm() == 0.0);
}

TEST_CASE("quadratic face weights reproduce the quadratics of the face's plane", "[quadratic]") {
  std::mt19937 rng(5);
  for (int n : {3, 4, 5, 6, 9})
    for (int trial = 0; trial < 10; ++trial) {
      INFO("n = " << n << ", trial " << trial);
      const PolygonPositions X =
          moved(test::star_polygon(n, rng, 0.4, 1.0, 0.0), rng, trial % 2 ? 1e-4 : 1e3);
      const Eigen::Vector3d xf = X.transpose() * squared_area_weights(X);
      const Eigen::MatrixXd W = quadratic_face_weights(X, xf);
      REQUIRE(W.rows() == n + 1);
      REQUIRE(W.cols() == 2 * n);
      for (int q = 0; q < 3; ++q) {
        const auto [coarse, target] = sample(X, xf, plane_quadratic(X, rng));
        CHECK((W * coarse - target).cwiseAbs().maxCoeff() <= 1e-10 * coarse.cwiseAbs().maxCoeff());
      }
    }
}

TEST_CASE("quadratic face weights are the minimum-norm ones and do not depend on the frame", "[quadratic]") {
  std::mt19937 rng(7);
  for (int n : {4, 5, 7}) {
    const PolygonPositions X0 = test::star_polygon(n, rng, 0.5, 1.0, 0.0);
    const Eigen::Vector3d xf0 = X0.transpose() * squared_area_weights(X0);
    const Eigen::MatrixXd W0 = quadratic_face_weights(X0, xf0);
    // Minimum norm: every row lies in the row space of the Vandermonde matrix (monomials of the
    // plane z = 0, built here), i.e. is orthogonal to all weight changes that keep reproduction.
    Eigen::MatrixXd A(6, 2 * n);
    for (int k = 0; k < 2 * n; ++k) {
      const Eigen::RowVector3d y = k < n
                                       ? Eigen::RowVector3d(X0.row(k))
                                       : Eigen::RowVector3d(0.5 * (X0.row(k - n) + X0.row((k - n + 1) % n)));
      A.col(k) << 1, y[0], y[1], y[0] * y[0], y[0] * y[1], y[1] * y[1];
    }
    const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(A.transpose()).householderQ() *
                              Eigen::MatrixXd::Identity(2 * n, 6);
    CHECK((W0.transpose() - Q * (Q.transpose() * W0.transpose())).norm() <= 1e-12 * W0.norm());
    // Rigid motions and scaling leave the weights unchanged (an affine map keeps the quadratics).
    const PolygonPositions X1 = moved(X0, rng, 37.0);
    const Eigen::Vector3d xf1 = X1.transpose() * squared_area_weights(X1);
    CHECK((quadratic_face_weights(X1, xf1) - W0).norm() <= 1e-10 * W0.norm());
    // Starting the corner list elsewhere permutes the columns and the spoke rows alike.
    PolygonPositions X2(n, 3);
    for (int k = 0; k < n; ++k) X2.row(k) = X0.row((k + 2) % n);
    const Eigen::MatrixXd W2 = quadratic_face_weights(X2, xf0);
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j) {
        CHECK(std::abs(W2(0, j) - W0(0, (j + 2) % n)) <= 1e-12);
        CHECK(std::abs(W2(1 + k, j) - W0(1 + (k + 2) % n, (j + 2) % n)) <= 1e-12);
        CHECK(std::abs(W2(1 + k, n + j) - W0(1 + (k + 2) % n, n + (j + 2) % n)) <= 1e-12);
      }
  }
}

TEST_CASE("on a triangle the quadratic weights are the P2 basis values", "[quadratic]") {
  const Eigen::Vector3d p0(0.1, 0.2, 0.3), p1(1.3, 0.1, -0.2), p2(0.4, 1.1, 0.5);
  PolygonPositions X(3, 3);
  X << p0.transpose(), p1.transpose(), p2.transpose();
  const Eigen::Vector3d w = squared_area_weights(X);
  const Eigen::Vector3d xf = X.transpose() * w;
  const Eigen::MatrixXd W = quadratic_face_weights(X, xf);
  // phi_i = l_i (2 l_i - 1), phi_ij = 4 l_i l_j at barycentric l; x_f has l = w, the spoke
  // midpoint of corner k has l = (e_k + w) / 2.
  auto basis = [](const Eigen::Vector3d& l) {
    Eigen::Matrix<double, 6, 1> b;
    b << l[0] * (2 * l[0] - 1), l[1] * (2 * l[1] - 1), l[2] * (2 * l[2] - 1), 4 * l[0] * l[1],
        4 * l[1] * l[2], 4 * l[2] * l[0];
    return b;
  };
  CHECK((W.row(0).transpose() - basis(w)).cwiseAbs().maxCoeff() <= 1e-13);
  for (int k = 0; k < 3; ++k)
    CHECK((W.row(1 + k).transpose() - basis((Eigen::Vector3d::Unit(k) + w) / 2)).cwiseAbs().maxCoeff() <=
          1e-13);
}

TEST_CASE("non-planar faces: the weights of the polygon projected to its best-fit plane", "[quadratic]") {
  std::mt19937 rng(3);
  for (int n : {4, 6, 8}) {
    const PolygonPositions X = moved(test::star_polygon(n, rng, 0.5, 1.0, 0.3), rng, 2.0);
    const Eigen::Vector3d xf = X.transpose() * squared_area_weights(X);
    const Eigen::MatrixXd W = quadratic_face_weights(X, xf);
    CHECK((W.rowwise().sum().array() - 1.0).abs().maxCoeff() <= 1e-12);
    // The best-fit plane here from the covariance's eigenvectors: the projected polygon (and
    // virtual vertex) is planar and gets the same weights.
    const Eigen::RowVector3d c = X.colwise().mean();
    const Eigen::Matrix3d C = (X.rowwise() - c).transpose() * (X.rowwise() - c);
    const Eigen::Vector3d nrm = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvectors().col(0);
    const Eigen::Matrix3d proj = Eigen::Matrix3d::Identity() - nrm * nrm.transpose();
    const PolygonPositions Xp = ((X.rowwise() - c) * proj).rowwise() + c;
    const Eigen::Vector3d xfp = proj * (xf - c.transpose()) + c.transpose();
    CHECK((quadratic_face_weights(Xp, xfp) - W).norm() <= 1e-10 * W.norm());
  }
}

TEST_CASE("a polygon collapsed to a point gets finite uniform weights", "[quadratic]") {
  const PolygonPositions X = PolygonPositions::Constant(4, 3, 0.25);
  const Eigen::MatrixXd W = quadratic_face_weights(X, Eigen::Vector3d::Constant(0.25));
  REQUIRE(W.allFinite());
  CHECK((W.rowwise().sum().array() - 1.0).abs().maxCoeff() <= 1e-15);
}

TEST_CASE("quadratic prolongation: identity on the coarse dofs, quadratics exact on planar meshes",
          "[quadratic]") {
  const Mesh meshes[] = {test::planar_grid(5, 4, 0.3, true), hex_grid(4, 4), chevron_grid(4, 3),
                         triangle_grid(3, 3)};
  for (const Mesh& mesh : meshes) {
    const Refinement r = refine(mesh);
    const Eigen::SparseMatrix<double> P = quadratic_prolongation(mesh, r);
    const int nc = mesh.n_vertices() + mesh.n_edges();
    REQUIRE(P.rows() == nc + mesh.n_faces() + mesh.n_halfedges());
    REQUIRE(P.cols() == nc);
    const Eigen::MatrixX3d D = quadratic_dof_positions(mesh), R = quadratic_refined_positions(mesh, r);
    CHECK((R.topRows(nc) - D).norm() == 0.0);
    auto q = [](const Eigen::RowVector3d& x) {
      return 0.3 + x[0] - 2 * x[1] + 1.5 * x[0] * x[0] - x[0] * x[1] + 0.7 * x[1] * x[1];
    };
    Eigen::VectorXd u(nc), uf(R.rows());
    for (int i = 0; i < nc; ++i) u[i] = q(D.row(i));
    for (int i = 0; i < R.rows(); ++i) uf[i] = q(R.row(i));
    const Eigen::VectorXd Pu = P * u;
    CHECK((Pu.head(nc) - u).norm() == 0.0);
    CHECK((Pu - uf).cwiseAbs().maxCoeff() <= 1e-12 * uf.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("chevron_grid: non-convex hexagons tiling the unit square", "[quadratic][generators]") {
  const Mesh m = chevron_grid(4, 3);
  CHECK(m.n_faces() == 12);
  CHECK(m.n_vertices() == 5 * 4 + 4 * 4);
  CHECK(m.n_boundary_edges() == 2 * 4 + 2 * 3 + 4 + 4);  // bottom and top sides hold the midpoints too
  double area = 0;
  for (int f = 0; f < m.n_faces(); ++f) {
    const PolygonPositions X = face_positions(m, f);
    for (int k = 0; k < 6; ++k) area += 0.5 * (X(k, 0) * X((k + 1) % 6, 1) - X((k + 1) % 6, 0) * X(k, 1));
  }
  CHECK(std::abs(area - 1.0) <= 1e-14);
  // The bottom midpoint of an interior-row face is a reflex corner (cross product of its two
  // edges negative in a counter-clockwise face).
  const PolygonPositions X = face_positions(m, 4 * 1 + 2);
  const Eigen::RowVector3d a = X.row(1) - X.row(0), b = X.row(2) - X.row(1);
  CHECK(a[0] * b[1] - a[1] * b[0] < 0);
  CHECK_THROWS_AS(chevron_grid(2, 2, 0.5), std::invalid_argument);
}

}  // namespace test_quadratic_dec
