// tests/dec/mesh/test_mesh.cpp — mesh validation and derived connectivity.
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/mesh.h"
#include "tests/support/renumbered.h"

#include <algorithm>
#include <numeric>
#include <random>
#include <cmath>
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
  // Checks m against the oracle; returns the number of boundary halfedges.
  auto check = [](const Mesh& m) {
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
    CHECK(m.n_boundary_edges() == n_boundary);
    return n_boundary;
  };
  // Vertices renumbered at random, so that edge keys are not in face order.
  auto renumbered = [](const Eigen::MatrixX3d& X, const std::vector<std::vector<int>>& faces, unsigned seed) {
    PolygonSoup s;
    s.positions = X;
    for (const auto& face : faces) s.add_face(face);
    const Mesh m(std::move(s));
    return test::renumbered(m, test::random_permutation(m.n_vertices(), seed));
  };
  // A cube sphere with one quad removed (a hole of four boundary edges).
  const Mesh sphere = cube_sphere(6);
  std::vector<std::vector<int>> faces;
  for (int f = 1; f < sphere.n_faces(); ++f) faces.emplace_back(sphere.face(f).begin(), sphere.face(f).end());
  CHECK(check(renumbered(sphere.positions(), faces, 3)) == 4);
  // A fan of 300 triangles around one vertex: its edges fill one large bucket (the sort's other path).
  const int n = 300;
  Eigen::MatrixX3d X(n + 1, 3);
  X.row(0).setZero();
  faces.clear();
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    X.row(i + 1) << std::cos(a), std::sin(a), 0;
    faces.push_back({0, 1 + i, 1 + (i + 1) % n});
  }
  CHECK(check(renumbered(X, faces, 4)) == n);
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
