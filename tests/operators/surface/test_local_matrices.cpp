// tests/operators/surface/test_local_matrices.cpp — the per-polygon kernel of
// operators/surface/local_matrices.h on its own, on one hexagon and without a Mesh: symmetry,
// constants in the kernel of S, S negative semi-definite, linear precision, mass = area, equality
// with the refined fan's P^T S^f P and P^T M^f P built here from scratch, and, as an independent
// route, with the assembled S, M of a one-face mesh.
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <vector>

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/refinement.h"
#include "polydec/dec/surface/virtual_vertex.h"
#include "polydec/operators/surface/laplacian.h"
#include "polydec/operators/surface/local_matrices.h"

using namespace polydec;

namespace test_local_matrices {
namespace {

// An irregular convex hexagon in the plane z = 0 (counter-clockwise).
PolygonPositions planar_hexagon() {
  PolygonPositions X(6, 3);
  X << 0.0, 0.0, 0.0,  //
      2.0, -0.3, 0.0,  //
      3.1, 0.9, 0.0,   //
      2.6, 2.2, 0.0,   //
      0.7, 2.5, 0.0,   //
      -0.6, 1.1, 0.0;
  return X;
}

// The same hexagon lifted out of its plane (corners alternately up and down).
PolygonPositions nonplanar_hexagon() {
  PolygonPositions X = planar_hexagon();
  for (int k = 0; k < 6; ++k) X(k, 2) = (k % 2 ? 0.35 : -0.25);
  return X;
}

double polygon_area(const PolygonPositions& X) {
  double a = 0;
  for (int k = 0; k < X.rows(); ++k) {
    const int l = (k + 1) % int(X.rows());
    a += X(k, 0) * X(l, 1) - X(l, 0) * X(k, 1);
  }
  return 0.5 * std::abs(a);
}

struct Local {
  Eigen::MatrixXd S, M;
  Eigen::VectorXd w;
  Eigen::Vector3d xf;
};

// The kernel with the paper's squared-area weights, all fan triangles valid.
Local kernel(const PolygonPositions& X) {
  Local L;
  L.w = squared_area_weights(X);
  L.xf = X.transpose() * L.w;
  const std::vector<FanTriangle> fan(size_t(X.rows()), FanTriangle::Valid);
  polygon_matrices(X, L.w, L.xf, fan.data(), &L.S, &L.M);
  return L;
}

// The refined fan's stiffness and mass on corners 0..n-1 and the virtual point n, written out
// from the triangle formulas (cotangents from dot and cross products, P1 mass area/12 (1 + delta)),
// and coarsened by P = [I; w^T].
void refined_fan(const PolygonPositions& X, const Eigen::VectorXd& w, const Eigen::Vector3d& xf,
                 Eigen::MatrixXd& S, Eigen::MatrixXd& M) {
  const int n = int(X.rows());
  Eigen::MatrixXd Sf = Eigen::MatrixXd::Zero(n + 1, n + 1), Mf = Sf;
  for (int k = 0; k < n; ++k) {
    const int v[3] = {k, (k + 1) % n, n};
    const Eigen::Vector3d p[3] = {X.row(k).transpose(), X.row((k + 1) % n).transpose(), xf};
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      // Angle at corner a is opposite edge (b, c).
      const Eigen::Vector3d e1 = p[b] - p[a], e2 = p[c] - p[a];
      const double half_cot = 0.5 * e1.dot(e2) / e1.cross(e2).norm();
      Sf(v[b], v[c]) += half_cot;
      Sf(v[c], v[b]) += half_cot;
      Sf(v[b], v[b]) -= half_cot;
      Sf(v[c], v[c]) -= half_cot;
      for (int d = 0; d < 3; ++d) Mf(v[a], v[d]) += area / 12.0 * (a == d ? 2.0 : 1.0);
    }
  }
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(n + 1, n);
  P.topRows(n).setIdentity();
  P.row(n) = w.transpose();
  S = P.transpose() * Sf * P;
  M = P.transpose() * Mf * P;
}

}  // namespace

TEST_CASE("local matrices: symmetric, constants in the kernel, negative semi-definite", "[local-matrices]") {
  for (const PolygonPositions& X : {planar_hexagon(), nonplanar_hexagon()}) {
    const Local L = kernel(X);
    REQUIRE(L.S.rows() == 6);
    REQUIRE(L.S.cols() == 6);
    const double scale = L.S.norm();
    CHECK((L.S - L.S.transpose()).norm() <= 1e-14 * scale);
    CHECK((L.M - L.M.transpose()).norm() <= 1e-14 * L.M.norm());
    CHECK((L.S * Eigen::VectorXd::Ones(6)).norm() <= 1e-13 * scale);
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(L.S).eigenvalues();
    CHECK(ev.maxCoeff() <= 1e-13 * scale);     // negative semi-definite
    CHECK(ev(ev.size() - 2) < -1e-3 * scale);  // ... with a one-dimensional kernel
    const Eigen::VectorXd mv = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(L.M).eigenvalues();
    CHECK(mv.minCoeff() > 0);  // the mass is positive definite
  }
}

TEST_CASE("local matrices: linear precision and mass = area on a planar hexagon", "[local-matrices]") {
  const PolygonPositions X = planar_hexagon();
  const Local L = kernel(X);
  const double area = polygon_area(X);
  // The Dirichlet energy of a linear function is exact for the refined linear elements, since the
  // virtual point's value w^T u = a . xf is the linear function's value there.
  for (const Eigen::Vector3d& a :
       {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0.7, -1.3, 0)}) {
    const Eigen::VectorXd u = X * a;
    CHECK(u.dot(L.S * u) == Approx(-a.squaredNorm() * area).epsilon(1e-12));
  }
  // The normal component of a gradient does not show on a planar polygon.
  const Eigen::VectorXd z = X * Eigen::Vector3d(0.4, 0.2, 5.0);
  CHECK(z.dot(L.S * z) == Approx(-(0.4 * 0.4 + 0.2 * 0.2) * area).epsilon(1e-12));
  CHECK(L.M.sum() == Approx(area).epsilon(1e-13));
  // Virtual-vertex weights sum to one, so the lumped mass (row sums) also sums to the area.
  CHECK(L.w.sum() == Approx(1.0).epsilon(1e-14));
}

TEST_CASE("local matrices: equal the refined fan's P^T S^f P and P^T M^f P", "[local-matrices]") {
  for (const PolygonPositions& X : {planar_hexagon(), nonplanar_hexagon()}) {
    for (const Eigen::VectorXd& w : {squared_area_weights(X), centroid_weights(6)}) {
      const Eigen::Vector3d xf = X.transpose() * w;
      const std::vector<FanTriangle> fan(6, FanTriangle::Valid);
      Eigen::MatrixXd S, M, S_ref, M_ref;
      polygon_matrices(X, w, xf, fan.data(), &S, &M);
      refined_fan(X, w, xf, S_ref, M_ref);
      CHECK((S - S_ref).norm() <= 1e-13 * S_ref.norm());
      CHECK((M - M_ref).norm() <= 1e-13 * M_ref.norm());
    }
  }
}

TEST_CASE("local matrices: a degenerate fan triangle adds no stiffness but keeps its mass",
          "[local-matrices]") {
  const PolygonPositions X = planar_hexagon();
  const Eigen::VectorXd w = squared_area_weights(X);
  const Eigen::Vector3d xf = X.transpose() * w;
  std::vector<FanTriangle> fan(6, FanTriangle::Valid);
  Eigen::MatrixXd S_all, M_all, S_flag, M_flag;
  polygon_matrices(X, w, xf, fan.data(), &S_all, &M_all);
  fan[2] = FanTriangle::Degenerate;
  polygon_matrices(X, w, xf, fan.data(), &S_flag, &M_flag);
  CHECK((M_flag - M_all).norm() == 0.0);
  CHECK((S_flag - S_all).norm() > 1e-3 * S_all.norm());
  CHECK((S_flag * Eigen::VectorXd::Ones(6)).norm() <= 1e-13 * S_all.norm());
  // Either output may be omitted.
  Eigen::MatrixXd S_only;
  polygon_matrices(X, w, xf, fan.data(), &S_only, nullptr);
  CHECK((S_only - S_flag).norm() == 0.0);
}

TEST_CASE("local matrices: the compact form expands to the dense one", "[local-matrices]") {
  const PolygonPositions X = nonplanar_hexagon();
  const Local L = kernel(X);
  const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> x = X;
  const std::vector<FanTriangle> fan(6, FanTriangle::Valid);
  double cS[18], cM[18];
  polygon_matrices_compact(x.data(), 6, L.w.data(), L.xf.data(), fan.data(), cS, cM);
  Eigen::MatrixXd S(6, 6), M(6, 6);
  for (int b = 0; b < 6; ++b) {
    expand_local_column(6, b, L.w.data(), cS, S.col(b).data());
    expand_local_column(6, b, L.w.data(), cM, M.col(b).data());
  }
  CHECK((S - L.S).norm() <= 1e-14 * L.S.norm());
  CHECK((M - L.M).norm() <= 1e-14 * L.M.norm());
}

TEST_CASE("local matrices: the compact form's column sums equal the expanded columns' sums",
          "[local-matrices]") {
  const PolygonPositions X = nonplanar_hexagon();
  const Local L = kernel(X);
  const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> x = X;
  const std::vector<FanTriangle> fan(6, FanTriangle::Valid);
  // The paper's weights, and weights that are not affine (the sums hold for any weights).
  Eigen::VectorXd skewed = L.w;
  skewed[2] += 0.4;
  skewed[5] -= 0.1;
  for (const Eigen::VectorXd& w : {L.w, skewed}) {
    double cS[18], cM[18], sums[6];
    polygon_matrices_compact(x.data(), 6, w.data(), L.xf.data(), fan.data(), cS, cM);
    for (const double* c : {cS, cM}) {
      Eigen::MatrixXd A(6, 6);
      for (int b = 0; b < 6; ++b) expand_local_column(6, b, w.data(), c, A.col(b).data());
      local_column_sums(6, w.data(), c, sums);
      const Eigen::VectorXd expected = A.colwise().sum().transpose();
      CHECK((Eigen::Map<const Eigen::VectorXd>(sums, 6) - expected).cwiseAbs().maxCoeff() <=
            1e-14 * A.cwiseAbs().maxCoeff());
      CHECK((A.rowwise().sum() - expected).cwiseAbs().maxCoeff() <= 1e-14 * A.cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("local matrices: equal the assembled S and M of a one-face mesh", "[local-matrices]") {
  for (const PolygonPositions& X : {planar_hexagon(), nonplanar_hexagon()}) {
    PolygonSoup soup;
    soup.positions = X;
    soup.face_indices = {0, 1, 2, 3, 4, 5};
    soup.face_offsets = {0, 6};
    const Mesh mesh(soup);
    const Refinement r = refine(mesh);
    const Laplacian A = assemble_laplacian(mesh, r);
    // The one face's corners in face order are the mesh vertices 0..5.
    REQUIRE(std::vector<int>(mesh.face(0).begin(), mesh.face(0).end()) == soup.face_indices);
    const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(r.weights.data(), 6);
    const Eigen::Vector3d xf = r.virtual_points.row(0).transpose();
    Eigen::MatrixXd S, M;
    polygon_matrices(X, w, xf, r.fan.data(), &S, &M);
    CHECK((S - Eigen::MatrixXd(A.S)).norm() <= 1e-14 * S.norm());
    CHECK((M - Eigen::MatrixXd(A.M)).norm() <= 1e-14 * M.norm());
    CHECK((M.rowwise().sum() - A.M_lumped).norm() <= 1e-14 * M.norm());
    // The mesh route picks the same weights as the kernel route above.
    CHECK((w - squared_area_weights(X)).norm() <= 1e-12);
  }
}

}  // namespace test_local_matrices
