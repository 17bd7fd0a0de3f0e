// tests/dec/mesh/test_degenerate_meshes.cpp — the documented policy for every kind of bad mesh
// (docs/robustness.md): rejected with the location, or accepted with operators that stay finite,
// symmetric, with S 1 = 0 and S = D G, and heat geodesics that are finite wherever a source
// reaches and +inf elsewhere.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "polydec/apps/applications/geodesics.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/mesh/mesh_checks.h"
#include "polydec/dec/mesh/repair.h"
#include "polydec/operators/surface/gradient.h"
#include "polydec/operators/surface/laplacian.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_degenerate_meshes {

namespace {

PolygonSoup to_soup(const Mesh& m) {
  PolygonSoup s;
  s.positions = m.positions();
  s.face_offsets = m.face_offsets();
  s.face_indices = m.face_indices();
  return s;
}

int add_vertex(PolygonSoup& s, const Eigen::RowVector3d& p) {
  const int v = s.n_vertices();
  s.positions.conservativeResize(v + 1, 3);
  s.positions.row(v) = p;
  return v;
}

// Index of the grid vertex at (i, j) of quad_grid(nx, ny), found by position.
int grid_vertex(const Mesh& m, double x, double y) {
  for (int v = 0; v < m.n_vertices(); ++v)
    if ((m.position(v) - Eigen::Vector3d(x, y, 0)).norm() < 1e-12) return v;
  FAIL("no vertex at " << x << ", " << y);
  return -1;
}

// The properties every accepted mesh's operators must have.
struct Operators {
  Refinement r;
  Laplacian L;
  SparseMatrix G, D;
};

Operators check_operators(const Mesh& mesh) {
  Operators o;
  o.r = refine(mesh);
  o.L = assemble_laplacian(mesh, o.r);
  o.G = gradient(mesh, o.r);
  o.D = divergence(mesh, o.r);
  const SparseMatrix& S = o.L.S;
  // Frobenius norm that is 0 for an empty (0 x 0) matrix: Eigen asserts on the sum of an empty one.
  auto fro = [](const SparseMatrix& A) { return A.rows() && A.cols() ? A.norm() : 0.0; };
  const double s = std::max(fro(S), 1e-300);
  CHECK(Eigen::MatrixXd(S).allFinite());
  CHECK(Eigen::MatrixXd(o.L.M).allFinite());
  CHECK(o.L.M_lumped.allFinite());
  CHECK(Eigen::MatrixXd(o.G).allFinite());
  CHECK(Eigen::MatrixXd(o.D).allFinite());
  CHECK(fro(S - SparseMatrix(S.transpose())) <= 1e-14 * s);
  CHECK(fro(o.L.M - SparseMatrix(o.L.M.transpose())) <= 1e-14 * std::max(fro(o.L.M), 1e-300));
  CHECK((S * Eigen::VectorXd::Ones(mesh.n_vertices())).norm() <= 1e-12 * s);
  CHECK(fro(S - o.D * o.G) <= 1e-10 * s);
  return o;
}

// Asserts: finite exactly on `reachable`, +inf elsewhere, minimum 0.
void check_distances(const Eigen::VectorXd& d, const std::vector<bool>& reachable) {
  REQUIRE(d.size() == long(reachable.size()));
  double mn = INFINITY;
  for (int v = 0; v < d.size(); ++v) {
    INFO("vertex " << v);
    CHECK(!std::isnan(d[v]));
    if (reachable[v]) {
      CHECK(std::isfinite(d[v]));
      CHECK(d[v] >= 0);
      mn = std::min(mn, d[v]);
    } else {
      CHECK(d[v] == INFINITY);
    }
  }
  CHECK(mn == 0.0);
}

}  // namespace

TEST_CASE("policy: invalid faces and coordinates are rejected naming the element", "[robust][degenerate]") {
  const Mesh grid = quad_grid(2, 2);
  auto rejected = [](PolygonSoup s, const std::string& element, long index, const std::string& words) {
    try {
      Mesh m(std::move(s));
      FAIL("accepted");
    } catch (const InvalidMeshError& e) {
      CHECK(e.element == element);
      CHECK(e.index == index);
      CHECK_THAT(e.what(), Catch::Contains(words));
    }
  };
  PolygonSoup s = to_soup(grid);
  s.add_face(std::vector<int>{0, 1});
  rejected(s, "face", 4, "2 vertices");
  s = to_soup(grid);
  s.add_face(std::vector<int>{0, 1, 99});
  rejected(s, "face", 4, "out of range");
  s = to_soup(grid);
  s.add_face(std::vector<int>{0, 1, -3});
  rejected(s, "face", 4, "out of range");
  s = to_soup(grid);
  s.add_face(std::vector<int>{0, 1, 2, 1});
  rejected(s, "face", 4, "repeats vertex 1");
  s = to_soup(grid);
  s.positions(5, 1) = std::nan("");
  rejected(s, "vertex", 5, "non-finite");
  s = to_soup(grid);
  s.positions(3, 2) = INFINITY;
  rejected(s, "vertex", 3, "non-finite");
}

TEST_CASE("policy: non-manifold edges are rejected naming the edge and its faces", "[robust][degenerate]") {
  // A fin: a third face on an interior edge of a grid.
  const Mesh grid = quad_grid(2, 1);
  PolygonSoup s = to_soup(grid);
  const int a = grid_vertex(grid, 0.5, 0), b = grid_vertex(grid, 0.5, 1);
  const int top = add_vertex(s, {0.5, 0.5, 1});
  s.add_face(std::vector<int>{a, b, top});
  try {
    Mesh m(s);
    FAIL("accepted");
  } catch (const InvalidMeshError& e) {
    CHECK(e.element == "edge");
    CHECK_THAT(e.what(), Catch::Contains(fmt::format("({}, {})", std::min(a, b), std::max(a, b))));
    CHECK_THAT(e.what(), Catch::Contains("non-manifold"));
    CHECK_THAT(e.what(), Catch::Contains("3 faces"));
  }
}

TEST_CASE("policy: inconsistent orientation is rejected naming both faces", "[robust][degenerate]") {
  const Mesh grid = quad_grid(2, 2);
  PolygonSoup s = to_soup(grid);
  // Reverse face 3.
  std::reverse(s.face_indices.begin() + s.face_offsets[3], s.face_indices.begin() + s.face_offsets[4]);
  try {
    Mesh m(s);
    FAIL("accepted");
  } catch (const InvalidMeshError& e) {
    CHECK(e.element == "edge");
    CHECK_THAT(e.what(), Catch::Contains("inconsistent orientation"));
    CHECK_THAT(e.what(), Catch::Contains("3"));
  }
}

TEST_CASE("policy: unreferenced vertices get zero rows and +inf distance", "[robust][degenerate]") {
  PolygonSoup s = to_soup(quad_grid(3, 3));
  const int n0 = s.n_vertices();
  const int iso1 = add_vertex(s, {0.5, 0.5, 0.5}), iso2 = add_vertex(s, {2, 2, 2});
  const Mesh mesh(s);
  CHECK(mesh.n_unreferenced_vertices() == 2);
  const MeshReport rep = check_mesh(mesh);
  CHECK(rep.unreferenced_vertices == std::vector<int>{iso1, iso2});
  CHECK(rep.component[iso1] == -1);
  const Operators o = check_operators(mesh);
  for (int v : {iso1, iso2}) {
    CHECK(o.L.S.col(v).norm() == 0);
    CHECK(o.L.M.col(v).norm() == 0);
    CHECK(o.L.M_lumped[v] == 0);
    CHECK(o.G.col(v).norm() == 0);
    CHECK(SparseMatrix(o.D.transpose()).col(v).norm() == 0);
  }
  const HeatGeodesics heat(mesh);
  std::vector<bool> reach(mesh.n_vertices(), true);
  reach[iso1] = reach[iso2] = false;
  check_distances(heat.distance(0), reach);
  CHECK_THROWS_AS(heat.distance(iso1), std::out_of_range);
  // The repair removes exactly them.
  const VertexRemoval r = remove_unreferenced_vertices(s);
  CHECK(r.n_removed == 2);
  CHECK(s.n_vertices() == n0);
}

TEST_CASE("policy: duplicate faces", "[robust][degenerate]") {
  SECTION("same orientation: rejected as inconsistent orientation; repair makes it valid") {
    PolygonSoup s = to_soup(quad_grid(2, 2));
    s.add_face(std::vector<int>(s.face_indices.begin(), s.face_indices.begin() + 4));
    CHECK_THROWS_WITH(Mesh(s),
                      Catch::Contains("inconsistent orientation") || Catch::Contains("non-manifold"));
    CHECK(remove_duplicate_faces(s).n_same_orientation == 1);
    CHECK(Mesh(s).n_faces() == 4);
  }
  SECTION("opposite orientation on an interior face: rejected as non-manifold") {
    const Mesh grid = quad_grid(3, 3);
    PolygonSoup s = to_soup(grid);
    const auto f = grid.face(4);  // the middle face: all its edges are interior
    s.add_face(std::vector<int>(f.rbegin(), f.rend()));
    CHECK_THROWS_WITH(Mesh(s), Catch::Contains("non-manifold"));
    CHECK(remove_duplicate_faces(s).n_opposite_orientation == 1);
    CHECK_NOTHROW(Mesh(s));
  }
  SECTION(
      "a doubled sheet (two faces, opposite orientation) is a valid closed mesh: reported, operators sound") {
    PolygonSoup s;
    s.positions.resize(5, 3);
    s.positions << 0, 0, 0, 1, 0, 0, 1.2, 0.8, 0, 0.3, 1.1, 0, -0.4, 0.5, 0;
    s.add_face(std::vector<int>{0, 1, 2, 3, 4});
    s.add_face(std::vector<int>{4, 3, 2, 1, 0});
    const Mesh mesh(s);
    CHECK(mesh.n_boundary_edges() == 0);
    const MeshReport rep = check_mesh(mesh);
    REQUIRE(rep.duplicate_faces.size() == 1);
    CHECK(rep.duplicate_faces[0] == std::pair<int, int>{1, 0});
    const Operators o = check_operators(mesh);
    // Both sides carry the same stiffness: S is twice the single pentagon's.
    PolygonSoup one = s;
    one.face_offsets.pop_back();
    one.face_indices.resize(5);
    const SparseMatrix S1 = stiffness(Mesh(one), refine(Mesh(one)));
    CHECK(test::relative_difference(o.L.S, 2 * S1) <= 1e-14);
    check_distances(HeatGeodesics(mesh).distance(0), std::vector<bool>(5, true));
  }
}

TEST_CASE("check_mesh pairs each duplicate face with the first face of its cycle, as a search of all pairs does",
          "[robust][degenerate]") {
  // Three components: a hexagon fanned around vertex 0 (six triangles with the same smallest vertex,
  // compared and all different), a doubled pentagon and a doubled quad, each face listed from another
  // corner.
  PolygonSoup s;
  s.positions.resize(16, 3);
  s.positions.row(0) << 0, 0, 0;
  for (int k = 0; k < 6; ++k) s.positions.row(1 + k) << std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0;
  for (int k = 0; k < 5; ++k) s.positions.row(7 + k) << 5 + std::cos(k * 2 * M_PI / 5), std::sin(k * 2 * M_PI / 5), 0;
  s.positions.block(12, 0, 4, 3) << 9, 0, 0, 10, 0, 0, 10, 1, 0, 9, 1, 0;
  const std::vector<std::vector<int>> faces = {{0, 1, 2},         {9, 10, 11, 7, 8}, {0, 2, 3},   {15, 12, 13, 14},
                                               {3, 4, 0},         {8, 7, 11, 10, 9}, {0, 4, 5},   {13, 12, 15, 14},
                                               {5, 6, 0},         {6, 1, 0}};
  // The first earlier face whose cycle, read from any corner in either direction, is the face's.
  auto search = [](const std::vector<std::vector<int>>& F) {
    std::vector<std::pair<int, int>> pairs;
    for (size_t f = 0; f < F.size(); ++f)
      for (size_t g = 0; g < f; ++g) {
        const size_t n = F[f].size();
        bool same = false;
        for (size_t start = 0; start < n && F[g].size() == n && !same; ++start)
          for (const int dir : {1, -1}) {
            bool all = true;
            for (size_t k = 0; k < n && all; ++k) all = F[g][k] == F[f][(start + n + dir * long(k) % long(n)) % n];
            same = same || all;
          }
        if (same) {
          pairs.emplace_back(int(f), int(g));
          break;
        }
      }
    return pairs;
  };
  std::vector<int> order(faces.size());
  std::iota(order.begin(), order.end(), 0);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::vector<int>> F;
    for (int i : order) F.push_back(faces[size_t(i)]);
    PolygonSoup t;
    t.positions = s.positions;
    for (const auto& f : F) t.add_face(f);
    const MeshReport rep = check_mesh(Mesh(t));
    const auto expected = search(F);
    CHECK(expected.size() == 2);
    CHECK(rep.duplicate_faces == expected);
    std::shuffle(order.begin(), order.end(), rng);
  }
}

TEST_CASE("policy: a zero-area face adds nothing, vertices only it holds are unreachable",
          "[robust][degenerate]") {
  // A collinear triangle hanging off the bottom boundary edge (a, b) of a grid: c on the line
  // through a and b, beyond b.
  const Mesh grid = quad_grid(3, 3);
  PolygonSoup s = to_soup(grid);
  const int a = grid_vertex(grid, 0, 0), b = grid_vertex(grid, 1.0 / 3, 0);
  const int c = add_vertex(s, {1.5, 0, 0});
  s.add_face(std::vector<int>{b, a, c});
  const Mesh mesh(s);
  const MeshReport rep = check_mesh(mesh);
  CHECK(rep.zero_area_faces == std::vector<int>{mesh.n_faces() - 1});
  const Operators o = check_operators(mesh);
  CHECK(o.r.quality.n_degenerate == 3);
  CHECK(o.r.quality.n_faces_affected == 1);
  // S on the grid's vertices is the grid's S; row c is zero.
  const SparseMatrix Sg = stiffness(grid, refine(grid));
  CHECK(test::relative_difference(SparseMatrix(o.L.S.topLeftCorner(grid.n_vertices(), grid.n_vertices())),
                                  Sg) <= 1e-15);
  CHECK(o.L.S.col(c).norm() == 0);
  std::vector<bool> reach(mesh.n_vertices(), true);
  reach[c] = false;
  const HeatGeodesics heat(mesh);
  check_distances(heat.distance(a), reach);
  CHECK_THROWS_AS(heat.distance(c), std::out_of_range);
  // The repair drops it.
  const FaceDrop d = drop_invalid_faces(s);
  CHECK(d.n_zero_area == 1);
}

TEST_CASE("policy: a row of collapsed quads splits the mesh for the operators", "[robust][degenerate]") {
  // quad_grid(3, 3) with its second row of vertices moved onto the first: the bottom row of
  // faces has zero area, its bottom vertices carry no stiffness.
  const Mesh grid = quad_grid(3, 3);
  Eigen::MatrixX3d P = grid.positions();
  std::vector<bool> reach(grid.n_vertices(), true);
  for (int v = 0; v < grid.n_vertices(); ++v) {
    if (std::abs(P(v, 1) - 1.0 / 3) < 1e-12)
      P(v, 1) = 0;
    else if (P(v, 1) == 0)
      reach[v] = false;
  }
  const Mesh mesh = grid.with_positions(P);
  const MeshReport rep = check_mesh(mesh);
  CHECK(rep.zero_area_faces.size() == 3);
  const Operators o = check_operators(mesh);
  CHECK(o.r.quality.n_degenerate == 12);
  const int source = grid_vertex(grid, 1, 1);
  check_distances(HeatGeodesics(mesh).distance(source), reach);
}

TEST_CASE("policy: collinear consecutive corners are accepted, linear precision holds",
          "[robust][degenerate]") {
  // A T-junction: a pentagon (0,0) (1,0) (1,1) (1,2) (0,2) beside two unit quads; the pentagon's
  // corner (1,1) is collinear with its neighbours.
  PolygonSoup s;
  s.positions.resize(8, 3);
  s.positions << 0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0, 2, 0, 0, 2, 1, 0, 2, 2, 0;
  s.add_face(std::vector<int>{0, 1, 2, 3, 4});
  s.add_face(std::vector<int>{1, 5, 6, 2});
  s.add_face(std::vector<int>{2, 6, 7, 3});
  // Rotate into a general plane so that nothing is axis-aligned.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  s.positions = (s.positions * R.transpose()).eval();
  const Mesh mesh(s);
  const MeshReport rep = check_mesh(mesh);
  REQUIRE(rep.collinear_corners.size() == 1);
  CHECK(rep.collinear_corners[0].face == 0);
  CHECK(rep.collinear_corners[0].vertex == 2);
  CHECK_FALSE(rep.collinear_corners[0].spike);
  const Operators o = check_operators(mesh);
  CHECK(o.r.quality.ok());
  // S applied to each coordinate function vanishes at the interior vertex 2.
  const Eigen::MatrixXd SX = o.L.S * mesh.positions();
  CHECK(SX.row(2).norm() <= 1e-12 * o.L.S.norm());
}

TEST_CASE("policy: virtual vertex on an edge's line (tetris.obj): counted, zero weight, finite",
          "[robust][degenerate]") {
  POLYDEC_SHARED_MESH(path, "tetris.obj");
  const Mesh mesh = read_mesh(path);
  const Operators o = check_operators(mesh);
  REQUIRE(o.r.quality.n_degenerate > 0);
  // Exactly the fan triangles with relative height at most the tolerance are degenerate; they
  // have zero area and zero gradient rows.
  const Eigen::VectorXd areas = fan_areas(mesh, o.r);
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    if (o.r.fan[h] != FanTriangle::Degenerate) continue;
    CHECK(areas[h] == 0);
    CHECK(o.G.middleRows(3 * h, 3).norm() == 0);
  }
  // Relative: the same fan triangles are degenerate at scales 1e-8 and 1e+8.
  for (double scale : {1e-8, 1e8}) {
    const Refinement rs = refine(mesh.with_positions(scale * mesh.positions()));
    CHECK(rs.fan == o.r.fan);
  }
  const HeatGeodesics heat(mesh);
  check_distances(heat.distance(0), std::vector<bool>(mesh.n_vertices(), true));
  check_distances(heat.distance(mesh.n_vertices() - 1), std::vector<bool>(mesh.n_vertices(), true));
}

TEST_CASE("policy: extremely thin polygons: finite operators, degenerate fans counted",
          "[robust][degenerate]") {
  // A strip of quads whose second column has relative width 1e-7 (thin) and fourth 1e-13 (zero
  // area up to the tolerance: it carries no stiffness and separates the strip for the heat flow).
  const std::vector<double> xs = {0, 1, 1 + 1e-7, 2, 2 + 1e-13, 3};
  PolygonSoup s;
  s.positions.resize(2 * long(xs.size()), 3);
  for (size_t i = 0; i < xs.size(); ++i) {
    s.positions.row(2 * long(i)) << xs[i], 0, 0;
    s.positions.row(2 * long(i) + 1) << xs[i], 1, 0;
  }
  for (int i = 0; i + 1 < int(xs.size()); ++i)
    s.add_face(std::vector<int>{2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1});
  const Mesh mesh(s);
  const MeshReport rep = check_mesh(mesh);
  CHECK(rep.thin_faces == std::vector<int>{1});
  CHECK(rep.zero_area_faces == std::vector<int>{3});
  const Operators o = check_operators(mesh);
  CHECK(o.r.quality.n_degenerate == 4);  // all of the 1e-13 quad's, none of the 1e-7 quad's
  for (int h = mesh.face_offsets()[3]; h < mesh.face_offsets()[4]; ++h)
    CHECK(o.r.fan[h] == FanTriangle::Degenerate);
  const HeatGeodesics heat(mesh);
  std::vector<bool> left(mesh.n_vertices()), right(mesh.n_vertices());
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    left[v] = mesh.position(v).x() <= 2;
    right[v] = !left[v];
  }
  check_distances(heat.distance(0), left);
  check_distances(heat.distance(mesh.n_vertices() - 1), right);
  // Across the thin (not zero-area) column the distance is continuous: vertex 2 at x = 1 and
  // vertex 4 at x = 1 + 1e-7 differ by about their separation.
  const Eigen::VectorXd d = heat.distance(0);
  CHECK(std::abs(d[4] - d[2]) <= 1e-3 * d[2]);
}

TEST_CASE("policy: several components: block-diagonal operators, +inf across", "[robust][degenerate]") {
  const Mesh a = quad_grid(3, 2), b = hex_grid(3, 3);
  PolygonSoup s = to_soup(a);
  const int na = a.n_vertices();
  s.positions.conservativeResize(na + b.n_vertices(), 3);
  s.positions.bottomRows(b.n_vertices()) = b.positions().rowwise() + Eigen::RowVector3d(3, 0, 1);
  for (int f = 0; f < b.n_faces(); ++f) {
    std::vector<int> face(b.face(f).begin(), b.face(f).end());
    for (int& v : face) v += na;
    s.add_face(face);
  }
  const Mesh mesh(s);
  CHECK(mesh.n_components() == 2);
  const MeshReport rep = check_mesh(mesh);
  CHECK(rep.n_components == 2);
  CHECK(rep.component_faces == std::vector<int>{a.n_faces(), b.n_faces()});
  const Operators o = check_operators(mesh);
  CHECK(o.L.S.bottomLeftCorner(b.n_vertices(), na).norm() == 0);
  // S 1 = 0 on each component separately.
  Eigen::VectorXd ind = Eigen::VectorXd::Zero(mesh.n_vertices());
  ind.head(na).setOnes();
  CHECK((o.L.S * ind).norm() <= 1e-12 * o.L.S.norm());
  std::vector<bool> reach(mesh.n_vertices(), false);
  std::fill(reach.begin(), reach.begin() + na, true);
  const HeatGeodesics heat(mesh);
  check_distances(heat.distance(0), reach);
  const std::vector<int> both = {0, na};
  const Eigen::VectorXd d = heat.distance(both);
  check_distances(d, std::vector<bool>(mesh.n_vertices(), true));
  CHECK(d[na] == 0);
}

TEST_CASE("policy: non-manifold vertices (bow ties) are accepted and reported", "[robust][degenerate]") {
  PolygonSoup s;
  s.positions.resize(5, 3);
  s.positions << 0, 0, 0, 1, -0.5, 0, 1, 0.5, 0, -1, 0.5, 0, -1, -0.4, 0.1;
  s.add_face(std::vector<int>{0, 1, 2});
  s.add_face(std::vector<int>{0, 3, 4});
  const Mesh mesh(s);
  const MeshReport rep = check_mesh(mesh);
  CHECK(rep.non_manifold_vertices == std::vector<int>{0});
  CHECK(rep.n_components == 1);
  check_operators(mesh);
  check_distances(HeatGeodesics(mesh).distance(1), std::vector<bool>(5, true));
}

TEST_CASE("check_mesh on clean generated meshes reports nothing", "[robust][degenerate]") {
  for (const Mesh& m : {quad_grid(4, 3), cube_sphere(3), hex_sphere(1), torus(8, 6)}) {
    const MeshReport rep = check_mesh(m);
    INFO(fmt::format("{}", fmt::join(rep.summary(), "; ")));
    CHECK(rep.clean());
  }
}

TEST_CASE("policy: extremes: empty mesh, no faces, a face whose corners coincide", "[robust][degenerate]") {
  SECTION("empty mesh: empty operators; no source exists") {
    const Mesh mesh{PolygonSoup{}};
    const Operators o = check_operators(mesh);
    CHECK(o.L.S.rows() == 0);
    CHECK(check_mesh(mesh).clean());
    const HeatGeodesics heat(mesh);
    CHECK_THROWS_AS(heat.distance(0), std::out_of_range);
  }
  SECTION("vertices without faces: all zero rows; none can be a source") {
    PolygonSoup s;
    s.positions = Eigen::MatrixX3d::Random(4, 3);
    const Mesh mesh(s);
    const Operators o = check_operators(mesh);
    CHECK(o.L.S.norm() == 0);
    CHECK(check_mesh(mesh).unreferenced_vertices.size() == 4);
    CHECK_THROWS_AS(HeatGeodesics(mesh).distance(1), std::out_of_range);
  }
  SECTION("a quad whose four corners coincide, beside a valid triangle") {
    PolygonSoup s;
    s.positions.resize(7, 3);
    s.positions << 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0, 0, 0, 1, 0, 0, 0, 1, 0;
    s.add_face(std::vector<int>{0, 1, 2, 3});
    s.add_face(std::vector<int>{4, 5, 6});
    const Mesh mesh(s);
    CHECK(check_mesh(mesh).zero_area_faces == std::vector<int>{0});
    const Operators o = check_operators(mesh);
    CHECK(o.r.quality.n_degenerate == 4);
    for (int h = 0; h < 4; ++h) CHECK(std::isfinite(o.r.weights[h]));
    std::vector<bool> reach = {false, false, false, false, true, true, true};
    check_distances(HeatGeodesics(mesh).distance(4), reach);
    PolygonSoup t = s;
    CHECK(drop_invalid_faces(t).n_zero_area == 1);
    CHECK(merge_duplicate_vertices(s, 0.0).n_merged == 3);  // then the quad repeats one vertex
    CHECK(drop_invalid_faces(s).n_too_few == 1);
  }
}

}  // namespace test_degenerate_meshes
