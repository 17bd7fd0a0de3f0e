// tests/dec/mesh/test_mesh.cpp — mesh validation and derived connectivity.
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/mesh.h"

#include <algorithm>
#include <numeric>
#include <random>
#include <catch2/catch.hpp>

using namespace polydec;

namespace test_mesh {

namespace {

PolygonSoup soup(std::vector<Eigen::Vector3d> p, std::vector<std::vector<int>> faces) {
  PolygonSoup s;
  s.positions.resize(long(p.size()), 3);
  for (size_t i = 0; i < p.size(); ++i) s.positions.row(long(i)) = p[i].transpose();
  for (auto& f : faces) s.add_face(f);
  return s;
}

std::vector<Eigen::Vector3d> square_pts() { return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}}; }

}  // namespace

TEST_CASE("validation rejects each kind of invalid soup with the element named", "[mesh]") {
  auto expect = [](PolygonSoup s, const std::string& element, long index, const std::string& words) {
    try {
      Mesh m(std::move(s));
      FAIL("accepted an invalid mesh");
    } catch (const InvalidMeshError& e) {
      CHECK(e.element == element);
      CHECK(e.index == index);
      CHECK_THAT(e.what(), Catch::Contains(words));
    }
  };
  expect(soup(square_pts(), {{0, 1}}), "face", 0, "2 vertices");
  expect(soup(square_pts(), {{0, 1, 2}, {0, 2, 7}}), "face", 1, "out of range");
  expect(soup(square_pts(), {{0, 1, 2}, {0, 2, -1}}), "face", 1, "out of range");
  expect(soup(square_pts(), {{0, 1, 1, 2}}), "face", 0, "repeats vertex 1");
  expect(soup(square_pts(), {{0, 1, 2}, {0, 1, 3}}), "edge", 0, "same direction");
  auto p = square_pts();
  p[2].x() = std::numeric_limits<double>::quiet_NaN();
  expect(soup(p, {{0, 1, 2}}), "vertex", 2, "non-finite");
  p = square_pts();
  p.push_back({0, 0, 1});
  expect(soup(p, {{0, 1, 2}, {1, 0, 3}, {0, 1, 5}}), "edge", 0, "shared by 3 faces");
}

TEST_CASE("connectivity of a quad grid", "[mesh]") {
  const Mesh m = quad_grid(3, 2);
  CHECK(m.n_vertices() == 12);
  CHECK(m.n_faces() == 6);
  CHECK(m.n_edges() == 17);
  CHECK(m.euler_characteristic() == 1);
  CHECK(m.boundary_loops().size() == 1);
  CHECK(m.boundary_loops()[0].size() == 10);
  CHECK(m.n_boundary_edges() == 10);
  CHECK(m.n_components() == 1);
  // Edges sorted lexicographically with i < j.
  for (int e = 0; e + 1 < m.n_edges(); ++e) {
    CHECK(m.edges()(e, 0) < m.edges()(e, 1));
    CHECK(std::make_pair(m.edges()(e, 0), m.edges()(e, 1)) < std::make_pair(m.edges()(e + 1, 0), m.edges()(e + 1, 1)));
  }
  // Opposite halfedges run in reverse and share the edge.
  for (int h = 0; h < m.n_halfedges(); ++h) {
    const int o = m.halfedge_opposite(h);
    if (o < 0) continue;
    CHECK(m.halfedge_source(o) == m.halfedge_target(h));
    CHECK(m.halfedge_target(o) == m.halfedge_source(h));
    CHECK(m.halfedge_edge(o) == m.halfedge_edge(h));
  }
  // Vertex 4 (interior on the bottom row? no: (1,1) is 5) — vertex 5 is interior with 4 faces.
  CHECK(m.vertex_faces(5).size() == 4);
  CHECK_FALSE(m.is_boundary_vertex(5));
  CHECK(m.is_boundary_vertex(0));
}

TEST_CASE("edges and halfedge links equal a comparison sort of the halfedges' vertex pairs", "[mesh]") {
  // A cube sphere with its vertices renumbered at random (so that edge keys are not in face order)
  // and a hole (boundary halfedges without opposites).
  const Mesh base = cube_sphere(6);
  std::vector<int> perm(size_t(base.n_vertices()));
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(3));
  PolygonSoup s;
  s.positions.resize(base.n_vertices(), 3);
  for (int v = 0; v < base.n_vertices(); ++v) s.positions.row(perm[size_t(v)]) = base.positions().row(v);
  for (int f = 1; f < base.n_faces(); ++f) {
    std::vector<int> face;
    for (int v : base.face(f)) face.push_back(perm[size_t(v)]);
    s.add_face(face);
  }
  const Mesh m(std::move(s));
  std::vector<std::pair<int, int>> keys;
  for (int h = 0; h < m.n_halfedges(); ++h)
    keys.emplace_back(std::min(m.halfedge_source(h), m.halfedge_target(h)),
                      std::max(m.halfedge_source(h), m.halfedge_target(h)));
  std::vector<std::pair<int, int>> unique = keys;
  std::sort(unique.begin(), unique.end());
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
  REQUIRE(m.n_edges() == int(unique.size()));
  for (int e = 0; e < m.n_edges(); ++e) CHECK(std::pair(m.edges()(e, 0), m.edges()(e, 1)) == unique[size_t(e)]);
  int n_boundary = 0;
  for (int h = 0; h < m.n_halfedges(); ++h) {
    CHECK(unique[size_t(m.halfedge_edge(h))] == keys[size_t(h)]);
    const int o = m.halfedge_opposite(h);
    if (o < 0) {
      ++n_boundary;
      CHECK(std::count(keys.begin(), keys.end(), keys[size_t(h)]) == 1);
    } else {
      CHECK(o != h);
      CHECK(m.halfedge_opposite(o) == h);
      CHECK(keys[size_t(o)] == keys[size_t(h)]);
    }
  }
  CHECK(n_boundary == 4);  // the removed quad's four edges
  CHECK(m.n_boundary_edges() == 4);
}

TEST_CASE("unreferenced vertices are accepted and counted, components counted", "[mesh]") {
  auto p = square_pts();
  p.push_back({5, 5, 5});
  p.push_back({6, 5, 5});
  p.push_back({5, 6, 5});
  const Mesh m(soup(p, {{0, 1, 2, 3}, {5, 6, 7}}));
  CHECK(m.n_unreferenced_vertices() == 1);  // vertex 4
  CHECK(m.n_components() == 2);
  CHECK(m.vertex_faces(4).empty());
}

TEST_CASE("with_positions keeps connectivity and rejects wrong sizes", "[mesh]") {
  const Mesh m = quad_grid(2, 2);
  const Mesh moved = m.with_positions(2.0 * m.positions());
  CHECK(moved.n_edges() == m.n_edges());
  CHECK(moved.mean_edge_length() == Approx(2.0 * m.mean_edge_length()));
  CHECK_THROWS_AS(m.with_positions(Eigen::MatrixX3d::Zero(3, 3)), InvalidMeshError);
}

}  // namespace test_mesh
