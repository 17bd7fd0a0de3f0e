// tests/dec/mesh/test_generators.cpp — the sample-mesh generators produce the expected topology and geometry.
#include "polydec/dec/mesh/generators.h"
#include "tests/support/support.h"
#include "polydec/dec/io/mesh_io.h"

#include <catch2/catch.hpp>

using namespace polydec;

namespace test_generators {

TEST_CASE("planar grids tile the unit square", "[generators]") {
  for (const Mesh& m : {quad_grid(4, 3), triangle_grid(4, 3), hex_grid(6, 6)}) {
    CHECK(m.euler_characteristic() == 1);
    CHECK(m.boundary_loops().size() == 1);
    CHECK(m.positions().col(0).minCoeff() == Approx(0.0).margin(1e-15));
    CHECK(m.positions().col(0).maxCoeff() == Approx(1.0));
    CHECK(m.positions().col(1).maxCoeff() == Approx(1.0));
    // Total (signed) area is 1: sum of the faces' shoelace areas, all positive.
    double area = 0;
    for (int f = 0; f < m.n_faces(); ++f) {
      const auto c = m.face(f);
      double a = 0;
      for (size_t k = 0; k < c.size(); ++k) {
        const auto p = m.position(c[k]), q = m.position(c[(k + 1) % c.size()]);
        a += 0.5 * (p.x() * q.y() - q.x() * p.y());
      }
      CHECK(a > 0);
      area += a;
    }
    CHECK(area == Approx(1.0));
  }
  const Mesh h = hex_grid(6, 6);
  CHECK(h.n_faces() == 49);  // one per vertex of the 6x6 triangle grid
  int interior = 0;
  for (int f = 0; f < h.n_faces(); ++f) {
    bool on_boundary = false;
    for (int v : h.face(f)) on_boundary = on_boundary || h.is_boundary_vertex(v);
    if (on_boundary) continue;
    ++interior;
    CHECK(h.face_size(f) == 6);  // interior dual faces are hexagons
  }
  CHECK(interior == 25);
}

TEST_CASE("closed generators have the right Euler characteristic", "[generators]") {
  CHECK(uv_sphere(8, 12).euler_characteristic() == 2);
  CHECK(cube_sphere(5).euler_characteristic() == 2);
  CHECK(cube_sphere(5).n_faces() == 150);
  const Mesh hs = hex_sphere(2);
  CHECK(hs.euler_characteristic() == 2);
  CHECK(hs.n_faces() == 162);  // vertices of the twice-subdivided icosahedron
  int pentagons = 0;
  for (int f = 0; f < hs.n_faces(); ++f) pentagons += hs.face_size(f) == 5;
  CHECK(pentagons == 12);
  CHECK(torus(12, 8).euler_characteristic() == 0);
  CHECK(genus2(0).euler_characteristic() == -2);
  CHECK(genus2(1).euler_characteristic() == -2);
  CHECK(genus2(1).n_boundary_edges() == 0);
  for (int v = 0; v < hs.n_vertices(); ++v) CHECK(hs.position(v).norm() == Approx(1.0));
}

TEST_CASE("Catmull-Clark follows the documented rules", "[generators]") {
  // A planar grid stays planar, keeps its vertex indices for old vertices, and every face becomes n quads.
  const Mesh g = quad_grid(3, 3);
  const Mesh s = catmull_clark(g);
  CHECK(s.n_faces() == 4 * g.n_faces());
  CHECK(s.n_vertices() == g.n_vertices() + g.n_edges() + g.n_faces());
  CHECK(s.positions().col(2).cwiseAbs().maxCoeff() == 0.0);
  // Interior vertex of a regular grid stays put: (4 neighbours + 4 face points)/16 + 1/2 x = x.
  CHECK((s.position(5) - g.position(5)).norm() < 1e-15);
  // Corner (boundary) vertex 0: (6 x0 + x1 + x4) / 8.
  CHECK((s.position(0) - (6 * g.position(0) + g.position(1) + g.position(4)) / 8).norm() < 1e-15);
  // The dual of a closed mesh swaps face and vertex counts.
  const Mesh c = cube_sphere(3);
  const Mesh d = dual(c);
  CHECK(d.n_faces() == c.n_vertices());
  CHECK(d.n_vertices() == c.n_faces());
}

TEST_CASE("the paper's HEX and FINE spheres from unit-sphere.off", "[generators]") {
  POLYDEC_SHARED_MESH(path, "unit-sphere.off");
  const Mesh tri = read_mesh(path);
  const Mesh hex = project_to_unit_sphere(dual(tri));
  CHECK(hex.n_faces() == 16070);
  const Mesh fine = project_to_unit_sphere(catmull_clark(hex));
  CHECK(fine.n_faces() == 96408);
}

}  // namespace test_generators
