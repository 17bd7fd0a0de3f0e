// tests/operators/surface/test_bench_reference.cpp — polydec's surface S, M and lumped M against the
// plain reference of bench/plain_surface_reference.cpp (the benchmark's baseline, an independent
// second route: the virtual vertex from the 3x3 normal equations of the squared-area sum, weights
// from the minimum-norm solution of [X^T; 1^T] w = [x_f; 1], dense fan matrices, triplet assembly).
#include <catch2/catch.hpp>

#include "bench/plain_surface_reference.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/operators/surface/laplacian.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_surface_bench_reference {
using polydec::test::relative_difference;

namespace {

// Total area of the fan triangles (x_i, x_{i+1}, x_f) of the reference's own virtual vertices:
// recomputed here from polydec's refinement, so that the reference's mass is checked against a
// quantity it does not compute itself.
double fan_area(const Mesh& mesh, const Refinement& r) {
  double area = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const Eigen::Vector3d xf = r.virtual_points.row(f).transpose();
    for (size_t i = 0; i < face.size(); ++i) {
      const Eigen::Vector3d a = mesh.position(face[i]) - xf, b = mesh.position(face[(i + 1) % face.size()]) - xf;
      area += 0.5 * a.cross(b).norm();
    }
  }
  return area;
}

// The two agree to 1e-12 relative (Frobenius): the routes differ only in round-off, and every
// face of these meshes is either exactly planar or clearly not (the rank of the least-norm
// weights is decided the same way by both).
void check_against_reference(const Mesh& mesh) {
  const Refinement r = refine(mesh);
  const Laplacian L = assemble_laplacian(mesh, r);
  SparseMatrix S, M;
  plain_surface_reference::build(plain_surface_reference::from_mesh(mesh), S, M);
  REQUIRE(S.rows() == mesh.n_vertices());
  REQUIRE(S.norm() > 0);
  REQUIRE(M.norm() > 0);
  CHECK(relative_difference(L.S, S) < 1e-12);
  CHECK(relative_difference(L.M, M) < 1e-12);
  const Eigen::VectorXd lumped = M * Eigen::VectorXd::Ones(mesh.n_vertices());
  CHECK((L.M_lumped - lumped).norm() < 1e-12 * lumped.norm());
  // Checks of the oracle itself: constants in the kernel of S, total mass = fan area.
  CHECK((S * Eigen::VectorXd::Ones(mesh.n_vertices())).cwiseAbs().maxCoeff() < 1e-12 * S.norm());
  const double area = fan_area(mesh, r);
  CHECK(std::abs(M.sum() - area) < 1e-12 * area);
}

}  // namespace

TEST_CASE("surface S and M equal the plain benchmark reference on generated meshes", "[laplacian][surface-bench-ref]") {
  SECTION("planar quad grid") {
    const Mesh grid = quad_grid(9, 7);
    check_against_reference(grid);
    // Planar and convex: the fans tile the unit square.
    SparseMatrix S, M;
    plain_surface_reference::build(plain_surface_reference::from_mesh(grid), S, M);
    CHECK(std::abs(M.sum() - 1.0) < 1e-13);
  }
  SECTION("hexagon sphere (non-planar hexagons and pentagons)") { check_against_reference(hex_sphere(3)); }
  SECTION("noisy hexagon grid (non-planar, boundary)") { check_against_reference(add_noise(hex_grid(8, 7), 0.2, 5)); }
  SECTION("noisy quad torus (non-planar quads)") { check_against_reference(add_noise(torus(12, 8), 0.15, 3)); }
}

}  // namespace test_surface_bench_reference
