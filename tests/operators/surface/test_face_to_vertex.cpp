// tests/operators/surface/test_face_to_vertex.cpp — the face-to-vertex average: means over the
// faces around each vertex, constants kept, isolated vertices 0, a size mismatch rejected.
#include <catch2/catch.hpp>
#include <stdexcept>

#include "polydec/dec/mesh/generators.h"
#include "polydec/operators/surface/face_to_vertex.h"

using namespace polydec;

namespace test_face_to_vertex {

TEST_CASE("face_to_vertex averages the faces around each vertex", "[face-to-vertex]") {
  // Two quads sharing the edge (1, 4), and vertex 6 in no face.
  PolygonSoup soup;
  soup.positions.resize(7, 3);
  soup.positions << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 5, 5, 5;
  soup.face_indices = {0, 1, 4, 3, 1, 2, 5, 4};
  soup.face_offsets = {0, 4, 8};
  const Mesh mesh(soup);
  REQUIRE(mesh.n_vertices() == 7);
  const Eigen::VectorXd v = face_to_vertex(mesh, Eigen::Vector2d(2.0, 6.0));
  Eigen::VectorXd expect(7);
  expect << 2, 4, 6, 2, 4, 6, 0;
  CHECK(v == expect);

  const Mesh grid = quad_grid(4, 3);
  const Eigen::VectorXd c = face_to_vertex(grid, Eigen::VectorXd::Constant(grid.n_faces(), -1.5));
  CHECK(c.size() == grid.n_vertices());
  CHECK((c.array() == -1.5).all());

  CHECK_THROWS_AS(face_to_vertex(grid, Eigen::VectorXd::Zero(grid.n_faces() + 1)), std::invalid_argument);
}

}  // namespace test_face_to_vertex
