// tests/operators/comparison/test_intrinsic_delaunay.cpp — intrinsic Delaunay flips (Bobenko & Springborn 2007).
#include "polydec/operators/comparison/intrinsic_delaunay.h"

#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/operators/registry/laplacians.h"
#include "polydec/operators/comparison/triangulation.h"
#include "tests/support/plain_cotan.h"
#include "tests/support/support.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <set>

using namespace polydec;

namespace test_intrinsic_delaunay {

TEST_CASE("a thin rhombus is flipped to its short diagonal", "[compare][intrinsic_delaunay]") {
  Eigen::MatrixX3d X(4, 3);
  X << -2, 0, 0, 0, -0.5, 0, 2, 0, 0, 0, 0.5, 0;
  const std::vector<Eigen::Vector3i> tris = {{0, 1, 2}, {0, 2, 3}};  // long diagonal (0, 2)
  const IntrinsicTriangulation T = intrinsic_delaunay(X, tris);
  CHECK(T.n_flips == 1);
  CHECK(max_delaunay_violation(T) <= 0);
  // The flipped edge has the short diagonal's length 1; every triangle now uses vertices 1 and 3.
  for (int t = 0; t < 2; ++t) {
    const auto& c = T.triangles.triangles[t];
    CHECK((c.array() == 1).any());
    CHECK((c.array() == 3).any());
    for (int k = 0; k < 3; ++k)
      if ((c[k] == 1 && c[(k + 1) % 3] == 3) || (c[k] == 3 && c[(k + 1) % 3] == 1))
        CHECK(T.triangles.lengths[t][k] == Approx(1.0).epsilon(1e-14));
  }
  // The cotangent Laplacian of the flipped pair equals that of the extrinsic short-diagonal split.
  const std::vector<Eigen::Vector3i> good = {{0, 1, 3}, {1, 2, 3}};
  CHECK(test::relative_difference(cotan_operators(T.triangles).S, cotan_operators(X, good).S) < 1e-14);
}

TEST_CASE("after flipping every edge is Delaunay and S has non-negative off-diagonals off the boundary", "[compare][intrinsic_delaunay]") {
  POLYDEC_SHARED_MESH(t1, "tetris.obj");
  POLYDEC_SHARED_MESH(l, "L-plane.obj");
  POLYDEC_SHARED_MESH(sphere, "unit-sphere-low.off");
  const Mesh meshes[] = {read_mesh(t1), read_mesh(l), add_noise(read_mesh(sphere), 0.3, 4), hex_grid(7, 7)};
  int total_flips = 0;
  for (const Mesh& mesh : meshes) {
    const auto tris = triangulate(mesh, TriangulationRule::MinSquaredArea);
    const IntrinsicTriangulation T = intrinsic_delaunay(mesh.positions(), tris);
    total_flips += T.n_flips;
    CHECK(max_delaunay_violation(T) <= 1e-10);
    const TriangleOperators ops = cotan_operators(T.triangles);
    // Vertex pairs joined by a boundary edge: it cannot be flipped and has one opposite angle,
    // so its weight cot/2 is negative where that angle is obtuse (tetris.obj and L-plane.obj have
    // such boundary triangles). Every other pair only gets weights of interior Delaunay edges.
    std::set<std::pair<int, int>> boundary;
    for (int h = 0; h < int(T.twin.size()); ++h)
      if (T.twin[h] < 0) {
        const auto& c = T.triangles.triangles[h / 3];
        boundary.insert(std::minmax(c[h % 3], c[(h + 1) % 3]));
      }
    CHECK(int(boundary.size()) == mesh.n_boundary_edges());  // flips keep the boundary (none on the sphere)
    double smax = 0, worst_off = 0;
    for (int j = 0; j < ops.S.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(ops.S, j); it; ++it) {
        smax = std::max(smax, std::abs(it.value()));
        if (it.row() != it.col() && !boundary.count(std::minmax(int(it.row()), int(it.col()))))
          worst_off = std::min(worst_off, it.value());
      }
    CHECK(worst_off >= -1e-10 * smax);
    CHECK((ops.S * Eigen::VectorXd::Ones(mesh.n_vertices())).cwiseAbs().maxCoeff() <= 1e-12 * smax);
    // Flips keep the total area and the metric: intrinsic areas add up to the extrinsic ones.
    const TriangleOperators ext = cotan_operators(mesh.positions(), tris);
    CHECK(ops.M_lumped.sum() == Approx(ext.M_lumped.sum()).epsilon(1e-10));
    CHECK(voronoi_areas(T.triangles).sum() == Approx(ext.M_lumped.sum()).epsilon(1e-10));
    // Dirichlet energy never increases under Delaunay flips (Rippa / Bobenko-Springborn): for
    // the coordinate functions on planar meshes (linear precision) they are equal.
    const Eigen::VectorXd u = mesh.positions().col(0).array().square();
    CHECK(-u.dot(ops.S * u) <= -u.dot(ext.S * u) * (1 + 1e-10));
  }
  CHECK(total_flips > 0);
}

TEST_CASE("an already Delaunay triangulation is kept: plain cotangent Laplacian", "[compare][intrinsic_delaunay]") {
  const Mesh grid = triangle_grid(5, 4);
  std::vector<Eigen::Vector3i> tris;
  for (int f = 0; f < grid.n_faces(); ++f) tris.emplace_back(grid.face(f)[0], grid.face(f)[1], grid.face(f)[2]);
  const IntrinsicTriangulation T = intrinsic_delaunay(grid.positions(), tris);
  CHECK(T.n_flips == 0);
  CHECK(test::relative_difference(cotan_operators(T.triangles).S, test::plain_cotan(grid).S) < 1e-12);
  // Bad input: an edge used twice in the same direction.
  const std::vector<Eigen::Vector3i> bad = {{0, 1, 2}, {0, 1, 3}};
  CHECK_THROWS_AS(intrinsic_delaunay(grid.positions(), bad), std::invalid_argument);
}

}  // namespace test_intrinsic_delaunay
