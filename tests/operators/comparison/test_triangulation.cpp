// tests/operators/comparison/test_triangulation.cpp — the O(n^3) polygon triangulation DP against brute
// force enumeration of all triangulations.
#include "polydec/operators/comparison/triangulation.h"

#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "tests/support/support.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <map>
#include <random>

using namespace polydec;

namespace test_triangulation {
using test::star_polygon;

namespace {

// Every triangulation of the sub-polygon i..j (corners in order), by recursion on the apex of
// edge (i, j): Catalan-many, fine for n <= 9.
void all_triangulations(int i, int j, std::vector<PolygonTriangulation>& out) {
  out.clear();
  if (j - i < 2) {
    out.emplace_back();
    return;
  }
  for (int k = i + 1; k < j; ++k) {
    std::vector<PolygonTriangulation> left, right;
    all_triangulations(i, k, left);
    all_triangulations(k, j, right);
    for (const auto& l : left)
      for (const auto& r : right) {
        PolygonTriangulation t = l;
        t.insert(t.end(), r.begin(), r.end());
        t.emplace_back(i, k, j);
        out.push_back(std::move(t));
      }
  }
}

}  // namespace

TEST_CASE("triangulation DP finds the brute-force optimum", "[compare][triangulation]") {
  std::mt19937 rng(7);
  for (int n = 3; n <= 8; ++n)
    for (int trial = 0; trial < 6; ++trial) {
      const PolygonPositions X = star_polygon(n, rng, 0.3, 1.0, trial % 2 == 0 ? 0.0 : 0.3);
      std::vector<PolygonTriangulation> all;
      all_triangulations(0, n - 1, all);
      for (auto rule : {TriangulationRule::MinSquaredArea, TriangulationRule::MaxMinAngle}) {
        const bool area = rule == TriangulationRule::MinSquaredArea;
        double best = area ? INFINITY : -INFINITY;
        for (const auto& T : all) {
          const double c = triangulation_cost(X, T, rule);
          best = area ? std::min(best, c) : std::max(best, c);
        }
        const PolygonTriangulation T = triangulate_polygon(X, rule);
        REQUIRE(int(T.size()) == n - 2);
        const double c = triangulation_cost(X, T, rule);
        INFO("n = " << n << ", trial " << trial << ", rule " << int(rule));
        CHECK(c == Approx(best).epsilon(1e-12));
        // The result is a triangulation: every corner pair used by a triangle is a polygon edge or a
        // diagonal used by exactly two triangles.
        std::map<std::pair<int, int>, int> uses;
        for (const auto& t : T)
          for (int k = 0; k < 3; ++k) ++uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
        for (const auto& [e, cnt] : uses) {
          const bool boundary = e.second - e.first == 1 || (e.first == 0 && e.second == n - 1);
          CHECK(cnt == (boundary ? 1 : 2));
        }
      }
    }
}

TEST_CASE("ties are broken by apex index, not by round-off: same triangles at any scale and position",
          "[compare][triangulation]") {
  // A regular polygon: many triangulations share the optimal cost up to round-off.
  for (int n : {4, 6, 8}) {
    PolygonPositions X(n, 3);
    for (int k = 0; k < n; ++k) X.row(k) << std::cos(2 * M_PI * k / n), std::sin(2 * M_PI * k / n), 0.0;
    for (auto rule : {TriangulationRule::MinSquaredArea, TriangulationRule::MaxMinAngle}) {
      const PolygonTriangulation T = triangulate_polygon(X, rule);
      for (double s : {1e-8, 3.7, 1e8}) {
        INFO("n = " << n << ", rule " << int(rule) << ", scale " << s);
        const PolygonPositions Y = (s * X).rowwise() + Eigen::RowVector3d(0.3 * s, -7 * s, 2 * s);
        CHECK(triangulate_polygon(Y, rule) == T);
      }
    }
  }
}

TEST_CASE("triangulations of a convex planar polygon cover its area", "[compare][triangulation]") {
  PolygonPositions X(6, 3);
  for (int k = 0; k < 6; ++k) X.row(k) << 2.0 * std::cos(M_PI * k / 3), std::sin(M_PI * k / 3), 0.0;
  const double area = 2.0 * 3 * std::sqrt(3.0) / 2;  // regular hexagon of radius 1, stretched by 2 in x
  for (auto rule : {TriangulationRule::MinSquaredArea, TriangulationRule::MaxMinAngle}) {
    double sum = 0;
    for (const auto& t : triangulate_polygon(X, rule))
      sum += 0.5 * (X.row(t[1]) - X.row(t[0])).cross(X.row(t[2]) - X.row(t[0])).dot(Eigen::RowVector3d::UnitZ());
    CHECK(sum == Approx(area).epsilon(1e-12));
  }
}

TEST_CASE("max-min-angle triangulation folds a non-convex polygon that min-area does not", "[compare][triangulation]") {
  // An arrow-head quad: the reflex corner 2 makes diagonal (1, 3) leave the polygon.
  PolygonPositions X(4, 3);
  X << 0, 0, 0, 1, -1, 0, 0.2, 0, 0, 1, 1, 0;
  auto signed_areas = [&](const PolygonTriangulation& T) {
    std::vector<double> a;
    for (const auto& t : T) a.push_back((X.row(t[1]) - X.row(t[0])).cross(X.row(t[2]) - X.row(t[0])).z());
    return a;
  };
  // Reflex corner at 2 (signed turn negative): the only proper triangulation uses diagonal (0, 2).
  const auto good = triangulate_polygon(X, TriangulationRule::MinSquaredArea);
  for (double a : signed_areas(good)) CHECK(a > 0);
  const auto maxmin = triangulate_polygon(X, TriangulationRule::MaxMinAngle);
  int folded = 0;
  for (double a : signed_areas(maxmin)) folded += a < 0;
  CHECK(folded == 1);
}

TEST_CASE("triangulate() splits every n-gon of a mesh into n - 2 triangles", "[compare][triangulation]") {
  POLYDEC_SHARED_MESH(path, "tetris.obj");
  const Mesh mesh = read_mesh(path);
  const auto tris = triangulate(mesh, TriangulationRule::MinSquaredArea);
  CHECK(int(tris.size()) == mesh.n_halfedges() - 2 * mesh.n_faces());
  // Per face, the triangles' vector areas add up to the polygon's (fold-overs would cancel). In
  // 3D: tetris.obj lies in a plane y = const, where every z component is 0 up to round-off.
  int t = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto c = mesh.face(f);
    Eigen::Vector3d a_poly = Eigen::Vector3d::Zero(), a_tri = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < c.size(); ++k) a_poly += 0.5 * mesh.position(c[k]).cross(mesh.position(c[(k + 1) % c.size()]));
    for (size_t k = 0; k + 2 < c.size(); ++k, ++t) {
      const Eigen::Vector3i& tri = tris[t];
      a_tri += 0.5 * (mesh.position(tri[1]) - mesh.position(tri[0])).cross(mesh.position(tri[2]) - mesh.position(tri[0]));
    }
    INFO("face " << f);
    REQUIRE(a_poly.norm() > 0);
    CHECK((a_tri - a_poly).norm() <= 1e-12 * a_poly.norm());
  }
}

}  // namespace test_triangulation
