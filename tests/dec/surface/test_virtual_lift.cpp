// tests/dec/surface/test_virtual_lift.cpp — virtual vertices off their affine points: given positions
// equal to the affine points change nothing, lifted operators keep S 1 = 0, symmetry, S <= 0 and M > 0
// and equal P^T (cotangent Laplacian of the lifted refined mesh) P, the sphere lift lands on the sphere,
// the quadric lift is exact on a paraboloid and the identity on planar meshes.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <fmt/format.h>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/virtual_positions.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/dec/surface/virtual_lift.h"
#include "polydec/operators/registry/laplacians.h"
#include "polydec/operators/surface/gradient.h"
#include "polydec/operators/surface/laplacian.h"
#include "tests/support/plain_cotan.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_virtual_lift {

namespace {

RefinementOptions with_lift(const VirtualLift& lift) {
  RefinementOptions o;
  o.lift = lift;
  return o;
}

bool bitwise_equal(const SparseMatrix& A, const SparseMatrix& B) {
  if (A.rows() != B.rows() || A.cols() != B.cols() || A.nonZeros() != B.nonZeros()) return false;
  for (long k = 0; k < A.nonZeros(); ++k)
    if (A.valuePtr()[k] != B.valuePtr()[k] || A.innerIndexPtr()[k] != B.innerIndexPtr()[k]) return false;
  return true;
}

// The rigid motion x -> R x + t applied to every vertex (R a rotation about (1, 2, 3)).
Mesh moved(const Mesh& mesh, double scale, const Eigen::Vector3d& t) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::MatrixX3d X = (scale * mesh.positions() * R.transpose()).rowwise() + t.transpose();
  return mesh.with_positions(X);
}

// The properties every lifted operator keeps, and the route through the explicit refined mesh:
// S = P^T S^f P and M = P^T M^f P with S^f, M^f the plain cotangent Laplacian and mass of the refined
// triangle mesh whose virtual vertices sit at the lifted points (eq. 12-13).
void check_lifted_operator(const Mesh& mesh, const Refinement& r) {
  const Laplacian L = assemble_laplacian(mesh, r);
  const Eigen::MatrixXd S = Eigen::MatrixXd(L.S), M = Eigen::MatrixXd(L.M);
  const double s = S.cwiseAbs().maxCoeff(), m = M.cwiseAbs().maxCoeff();
  CHECK((S - S.transpose()).cwiseAbs().maxCoeff() <= 1e-14 * s);
  CHECK((M - M.transpose()).cwiseAbs().maxCoeff() <= 1e-14 * m);
  CHECK((S * Eigen::VectorXd::Ones(S.cols())).cwiseAbs().maxCoeff() <= 1e-12 * s);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S), em(M);
  CHECK(es.eigenvalues().maxCoeff() <= 1e-12 * s);  // negative semi-definite
  CHECK(em.eigenvalues().minCoeff() > 0);           // positive definite
  const Mesh refined = refined_mesh(mesh, r);
  const test::PlainCotan ref = test::plain_cotan(refined);
  const SparseMatrix P = prolongation(mesh, r);
  CHECK(test::relative_difference(SparseMatrix(P.transpose() * ref.S * P), L.S) < 1e-12);
  CHECK(test::relative_difference(SparseMatrix(P.transpose() * ref.M * P), L.M) < 1e-12);
}

}  // namespace

TEST_CASE("virtual positions equal to the affine points change nothing, bit for bit", "[virtual-lift]") {
  for (const Mesh& mesh : {cube_sphere(4), hex_grid(5, 5), moved(hex_sphere(1), 3.0, {10, -20, 5})}) {
    const Refinement r0 = refine(mesh);
    VirtualLift lift;
    lift.kind = VirtualLiftKind::Positions;
    lift.positions = r0.virtual_points;
    const Refinement r1 = refine(mesh, with_lift(lift));
    CHECK(r1.weights == r0.weights);
    CHECK(r1.fan == r0.fan);
    CHECK(r1.quality.n_faces_affected == r0.quality.n_faces_affected);
    CHECK((r1.virtual_points.array() == r0.virtual_points.array()).all());
    const Laplacian L0 = assemble_laplacian(mesh, r0), L1 = assemble_laplacian(mesh, r1);
    CHECK(bitwise_equal(L0.S, L1.S));
    CHECK(bitwise_equal(L0.M, L1.M));
    CHECK((L0.M_lumped.array() == L1.M_lumped.array()).all());
    CHECK(bitwise_equal(gradient(mesh, r0), gradient(mesh, r1)));
  }
}

TEST_CASE("lifted operators: symmetric, S 1 = 0, S <= 0, M > 0, and P^T S^f P of the lifted refinement",
          "[virtual-lift]") {
  const Mesh sphere = moved(cube_sphere(3), 2.0, {1, 2, 3});
  const Mesh hexes = hex_sphere(1);
  for (const Mesh& mesh : {sphere, hexes}) {
    for (const char* spec : {"sphere", "quadric"}) {
      INFO(spec);
      check_lifted_operator(mesh, refine(mesh, with_lift(parse_virtual_lift(spec))));
    }
  }
  // Given positions: the affine points pushed off their faces by up to a fifth of the mean edge length.
  const Mesh grid = hex_grid(4, 4);
  const Refinement r0 = refine(grid);
  VirtualLift lift;
  lift.kind = VirtualLiftKind::Positions;
  lift.positions = r0.virtual_points;
  for (int f = 0; f < grid.n_faces(); ++f) lift.positions(f, 2) += 0.2 * grid.mean_edge_length() * std::sin(1.0 + f);
  const Refinement r1 = refine(grid, with_lift(lift));
  CHECK(r1.weights == r0.weights);  // the weights, and so P, do not move with the virtual point
  CHECK((r1.virtual_points - lift.positions).norm() == 0);
  check_lifted_operator(grid, r1);
}

TEST_CASE("the sphere lift puts every virtual vertex on the sphere", "[virtual-lift]") {
  const Eigen::Vector3d c(1, -2, 0.5);
  const double radius = 2.5;
  const Mesh mesh = moved(hex_sphere(2), radius, c);
  // The fitted sphere of points on a sphere is that sphere.
  const Sphere fit = best_fit_sphere(mesh.positions());
  CHECK((fit.center - c).norm() <= 1e-12 * radius);
  CHECK(std::abs(fit.radius - radius) <= 1e-12 * radius);
  const double tol = 1e-14 * radius;
  const Refinement affine = refine(mesh);
  for (const std::string& spec : {std::string("sphere"), fmt::format("sphere:{:.17g},{:.17g},{:.17g},{:.17g}", c[0],
                                                                    c[1], c[2], radius)}) {
    const Refinement r = refine(mesh, with_lift(parse_virtual_lift(spec)));
    double off = 0, below = INFINITY;
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const Eigen::Vector3d x = r.virtual_points.row(f).transpose(), a = affine.virtual_points.row(f).transpose();
      off = std::max(off, std::abs((x - c).norm() - radius));
      // Radially outward from the affine point, which lies inside the sphere.
      below = std::min(below, (x - a).dot((a - c).normalized()));
    }
    CHECK(off <= 16 * tol);
    CHECK(below > 0);
  }
  // A sphere of another radius: the closest point on that sphere.
  const Refinement r = refine(mesh, with_lift(parse_virtual_lift("sphere:1,-2,0.5,4")));
  for (int f = 0; f < mesh.n_faces(); ++f) CHECK(std::abs((r.virtual_points.row(f).transpose() - c).norm() - 4) <= 1e-13);
}

TEST_CASE("the quadric lift is exact on a paraboloid and the identity on planar meshes", "[virtual-lift]") {
  // z = x^2 + 2 y^2 over a 5x5 quad grid centred at the origin: the central face is symmetric, so its
  // best-fit plane is horizontal, its affine point is (0, 0, mean height), and the fitted quadric is
  // the surface itself; the lift lands on the surface at the origin.
  Mesh grid = quad_grid(5, 5);
  Eigen::MatrixX3d X = grid.positions();
  const double h = 0.1;
  for (int v = 0; v < X.rows(); ++v) {
    const double x = (X(v, 0) - 0.5) * 5 * h, y = (X(v, 1) - 0.5) * 5 * h;
    X.row(v) << x, y, x * x + 2 * y * y;
  }
  grid = grid.with_positions(X);
  int centre = -1;
  for (int f = 0; f < grid.n_faces(); ++f) {
    Eigen::Vector3d m = Eigen::Vector3d::Zero();
    for (int v : grid.face(f)) m += grid.position(v);
    if (std::abs(m[0]) < 1e-12 && std::abs(m[1]) < 1e-12) centre = f;
  }
  REQUIRE(centre >= 0);
  const Refinement affine = refine(grid);
  const Refinement lifted = refine(grid, with_lift(parse_virtual_lift("quadric")));
  CHECK(affine.virtual_points(centre, 2) > 0.5 * h * h);  // the affine point is off the surface
  CHECK(lifted.virtual_points.row(centre).norm() <= 1e-14);
  // Every lifted point is closer to the surface than its affine point (interior and boundary faces).
  for (int f = 0; f < grid.n_faces(); ++f) {
    auto gap = [](const Eigen::RowVector3d& p) { return std::abs(p[2] - p[0] * p[0] - 2 * p[1] * p[1]); };
    CHECK(gap(lifted.virtual_points.row(f)) < 0.5 * gap(affine.virtual_points.row(f)));
  }

  // Planar meshes: in the plane z = 0 the heights are exactly zero and nothing changes, bit for bit;
  // in a moved plane, up to round-off relative to the mesh's size.
  for (const Mesh& plane : {hex_grid(5, 5), quad_grid(4, 3)}) {
    const Refinement r0 = refine(plane), r1 = refine(plane, with_lift(parse_virtual_lift("quadric")));
    CHECK((r1.virtual_points.array() == r0.virtual_points.array()).all());
    CHECK(bitwise_equal(assemble_laplacian(plane, r0).S, assemble_laplacian(plane, r1).S));
    const Mesh tilted = moved(plane, 1e3, {1e4, 2e4, -3e4});
    const Refinement t0 = refine(tilted), t1 = refine(tilted, with_lift(parse_virtual_lift("quadric")));
    CHECK((t1.virtual_points - t0.virtual_points).cwiseAbs().maxCoeff() <= 1e-10 * 1e3);
    CHECK(t1.fan == t0.fan);
    const Laplacian L0 = assemble_laplacian(tilted, t0), L1 = assemble_laplacian(tilted, t1);
    CHECK(test::relative_difference(L0.S, L1.S) < 1e-9);
    CHECK(test::relative_difference(L0.M, L1.M) < 1e-9);
  }
}

TEST_CASE("virtual lifts refuse what does not fit", "[virtual-lift]") {
  const Mesh grid = hex_grid(3, 3);
  VirtualLift lift;
  lift.kind = VirtualLiftKind::Positions;
  lift.positions = Eigen::MatrixX3d::Zero(grid.n_faces() - 1, 3);
  CHECK_THROWS_WITH(refine(grid, with_lift(lift)), Catch::Contains("rows for a mesh of"));
  lift.positions = refine(grid).virtual_points;
  lift.positions(2, 1) = NAN;
  CHECK_THROWS_WITH(refine(grid, with_lift(lift)), Catch::Contains("face 2"));
  // A planar mesh has no best-fit sphere; a sphere through the affine point's center has no closest point.
  CHECK_THROWS_WITH(refine(grid, with_lift(parse_virtual_lift("sphere"))), Catch::Contains("coplanar"));
  const Eigen::RowVector3d a = refine(grid).virtual_points.row(4);
  CHECK_THROWS_WITH(refine(grid, with_lift(parse_virtual_lift(fmt::format("sphere:{:.17g},{:.17g},{:.17g},1", a[0],
                                                                          a[1], a[2])))),
                    Catch::Contains("face 4"));
  for (const char* bad : {"ball", "sphere:", "sphere:1,2,3", "sphere:1,2,3,0", "sphere:1,2,3,-1", "sphere:1,2,x,1",
                          "sphere:1,2,3,1,", "sphere:nan,0,0,1", "quadric:1"})
    CHECK_THROWS_AS(parse_virtual_lift(bad), std::invalid_argument);
  CHECK(to_string(parse_virtual_lift("sphere:1,2,3,4")) == "sphere:1,2,3,4");
  CHECK(to_string(parse_virtual_lift("quadric")) == "quadric");
  // The registry: a lift for a method without virtual vertices is refused; a lifted set is named.
  OperatorOptions o;
  o.lift = parse_virtual_lift("quadric");
  CHECK_THROWS_WITH(build_operators(grid, parse_laplacian("diamond"), o), Catch::Contains("no virtual vertices"));
  CHECK(build_operators(grid, parse_laplacian("ours"), o).name == "ours+lift:quadric");
}

TEST_CASE("virtual positions files: exact round trip, errors with file and line", "[virtual-lift][io]") {
  const test::ScratchDir dir("virtual_lift");
  const Mesh mesh = hex_sphere(1);
  const Eigen::MatrixX3d X = refine(mesh, with_lift(parse_virtual_lift("quadric"))).virtual_points;
  write_virtual_positions(dir.path("x.txt"), X);
  CHECK((read_virtual_positions(dir.path("x.txt"), mesh.n_faces()).array() == X.array()).all());
  const Eigen::MatrixX3d Y =
      read_virtual_positions_from_memory("\xEF\xBB\xBF# two faces\r\n1 2 3\r\n\n  -4e-1\t+5 6e2\n", 2, "m");
  CHECK(Y(0, 2) == 3.0);
  CHECK(Y(1, 0) == -0.4);
  CHECK(Y(1, 2) == 600.0);
  auto error = [](std::string_view text, int n) {
    try {
      read_virtual_positions_from_memory(text, n, "m");
    } catch (const FileError& e) {
      return fmt::format("{}:{}: {}", e.file, e.line, e.reason);
    }
    return std::string("no error");
  };
  CHECK(error("1 2 3\n4  5\n", 2) == "m:2: expected 'x y z', found 2 values");
  CHECK(error("1 2 3\n4 5 nan\n", 2) == "m:2: 'nan' is not a finite number");
  CHECK(error("1 2 3\n4 5 1e999\n", 2).find("m:2:") == 0);
  CHECK(error("1 2 3\n4 5 6\n", 1) == "m:2: more position lines than the mesh's 1 faces");
  CHECK(error("1 2 3\n# 4 5 6\n1 1 1\n", 3) == "m:3: 2 position lines for the mesh's 3 faces");
  CHECK(error("1 2 3\n", 1000000000).find("cannot hold") != std::string::npos);
  CHECK_THROWS_AS(read_virtual_positions(dir.path("missing.txt"), 2), FileError);
}

}  // namespace test_virtual_lift
