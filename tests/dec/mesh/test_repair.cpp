// tests/dec/mesh/test_repair.cpp — the opt-in repair steps of dec/mesh/repair.h: each does what it reports,
// its index maps are consistent, tolerances are relative to the mesh's scale, and what a step
// leaves behind passes validation.
#include <catch2/catch.hpp>
#include <random>

#include "polydec/dec/mesh/mesh_checks.h"
#include "polydec/dec/mesh/repair.h"

using namespace polydec;

namespace test_repair {

namespace {

PolygonSoup soup_of(const std::vector<Eigen::RowVector3d>& p, const std::vector<std::vector<int>>& faces) {
  PolygonSoup s;
  s.positions.resize(long(p.size()), 3);
  for (size_t i = 0; i < p.size(); ++i) s.positions.row(long(i)) = p[i];
  for (const auto& f : faces) s.add_face(f);
  return s;
}

std::vector<int> face_of(const PolygonSoup& s, int f) {
  return {s.face_indices.begin() + s.face_offsets[f], s.face_indices.begin() + s.face_offsets[f + 1]};
}

// Planar nx x ny quad grid as a soup where every face has its own 4 vertices (as STL-like
// exports produce), each perturbed by up to `noise` (absolute).
PolygonSoup exploded_grid(int nx, int ny, double noise, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PolygonSoup s;
  std::vector<Eigen::RowVector3d> p;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int b = int(p.size());
      const double c[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      for (auto& q : c)
        p.emplace_back((i + q[0]) / nx + noise * u(rng), (j + q[1]) / ny + noise * u(rng), noise * u(rng));
      s.add_face(std::vector<int>{b, b + 1, b + 2, b + 3});
    }
  s.positions.resize(long(p.size()), 3);
  for (size_t i = 0; i < p.size(); ++i) s.positions.row(long(i)) = p[i];
  return s;
}

}  // namespace

TEST_CASE("remove_unreferenced_vertices renumbers in order and reports the map", "[robust][repair]") {
  PolygonSoup s = soup_of({{0, 0, 0}, {9, 9, 9}, {1, 0, 0}, {8, 8, 8}, {0, 1, 0}}, {{0, 2, 4}});
  const VertexRemoval r = remove_unreferenced_vertices(s);
  CHECK(r.n_removed == 2);
  CHECK(r.vertex_map == std::vector<int>{0, -1, 1, -1, 2});
  REQUIRE(s.n_vertices() == 3);
  CHECK(face_of(s, 0) == std::vector<int>{0, 1, 2});
  CHECK(s.positions.row(1) == Eigen::RowVector3d(1, 0, 0));
  CHECK(Mesh(s).n_unreferenced_vertices() == 0);

  PolygonSoup bad = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 7}});
  CHECK_THROWS_AS(remove_unreferenced_vertices(bad), std::invalid_argument);
}

TEST_CASE("drop_invalid_faces counts each reason and leaves a valid mesh", "[robust][repair]") {
  // Vertices 0..3 a unit square, 4 on the line through 0 and 1.
  PolygonSoup s = soup_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}},
                          {
                              {0, 1},           // too few
                              {0, 1, 9},        // out of range
                              {0, 1, -1},       // out of range (negative)
                              {0, 1, 1, 2},     // consecutive repeat: collapsed to (0 1 2), kept
                              {2, 3, 0, 2},     // cyclic consecutive repeat: collapsed to (2 3 0), kept
                              {0, 1, 0, 1},     // 2 distinct vertices: too few
                              {0, 1, 3, 1, 2},  // non-consecutive repeat
                              {0, 1, 4},        // collinear: zero area
                              {1, 4, 2},        // valid
                          });
  const FaceDrop d = drop_invalid_faces(s);
  CHECK(d.n_too_few == 2);
  CHECK(d.n_out_of_range == 2);
  CHECK(d.n_repeated_vertex == 1);
  CHECK(d.n_zero_area == 1);
  CHECK(d.n_collapsed_corners == 2);  // (0 1 1 2) and (2 3 0 2); (0 1 0 1) has no consecutive repeat
  CHECK(d.n_dropped() == 6);
  CHECK(d.face_map == std::vector<int>{-1, -1, -1, 0, 1, -1, -1, -1, 2});
  REQUIRE(s.n_faces() == 3);
  CHECK(face_of(s, 0) == std::vector<int>{0, 1, 2});
  CHECK(face_of(s, 1) == std::vector<int>{2, 3, 0});
  CHECK(face_of(s, 2) == std::vector<int>{1, 4, 2});
  CHECK_NOTHROW(Mesh(s));

  SECTION("without collapsing, faces with consecutive repeats are dropped") {
    PolygonSoup t = soup_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 1, 1, 2}});
    FaceDropOptions o;
    o.collapse_consecutive_repeats = false;
    const FaceDrop e = drop_invalid_faces(t, o);
    CHECK(e.n_repeated_vertex == 1);
    CHECK(e.n_collapsed_corners == 0);
    CHECK(t.n_faces() == 0);
  }
}

TEST_CASE("zero area is decided relative to the face's own size", "[robust][repair]") {
  // A triangle of height h * length is zero-area for h = 1e-12 and kept for h = 1e-6, at any
  // scale and at a distance of 1e3 times its size.
  for (double scale : {1e-8, 1.0, 1e8})
    for (double offset : {0.0, 1e3 * scale}) {
      for (double h : {1e-12, 1e-6}) {
        const Eigen::RowVector3d o(offset, -offset, offset);
        PolygonSoup s =
            soup_of({o, o + scale * Eigen::RowVector3d(1, 0, 0), o + scale * Eigen::RowVector3d(0.5, h, 0)},
                    {{0, 1, 2}});
        const FaceDrop d = drop_invalid_faces(s);
        INFO("scale " << scale << " offset " << offset << " h " << h);
        CHECK(d.n_zero_area == (h < 1e-10 ? 1 : 0));
      }
    }
}

TEST_CASE("merge_duplicate_vertices welds an exploded grid, relative to its size", "[robust][repair]") {
  const int nx = 4, ny = 3;
  for (double scale : {1e-8, 1.0, 1e8}) {
    INFO("scale " << scale);
    PolygonSoup s = exploded_grid(nx, ny, 1e-9);
    s.positions *= scale;
    CHECK(Mesh(s).n_components() == nx * ny);  // valid, but every face on its own
    PolygonSoup exact = s;
    CHECK(merge_duplicate_vertices(exact, 0.0).n_merged == 0);  // noisy copies are not exactly equal

    const VertexMerge m = merge_duplicate_vertices(s, 1e-7);
    CHECK(m.distance == Approx(1e-7 * std::sqrt(2.0) * scale).epsilon(1e-6));
    CHECK(m.n_merged == 4 * nx * ny - (nx + 1) * (ny + 1));
    REQUIRE(s.n_vertices() == (nx + 1) * (ny + 1));
    const Mesh mesh(s);
    CHECK(mesh.n_components() == 1);
    CHECK(mesh.n_boundary_edges() == 2 * (nx + ny));
    // Each cluster keeps its lowest-numbered vertex's position.
    const PolygonSoup original = [&] {
      PolygonSoup o = exploded_grid(nx, ny, 1e-9);
      o.positions *= scale;
      return o;
    }();
    for (int v = 0; v < original.n_vertices(); ++v) {
      const int w = m.vertex_map[v];
      REQUIRE(w >= 0);
      CHECK((original.positions.row(v) - s.positions.row(w)).norm() <= m.distance * 3);
    }
  }
}

TEST_CASE("merge_duplicate_vertices agrees with a brute-force clustering", "[robust][repair]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PolygonSoup s;
  const int n = 400;
  s.positions.resize(n, 3);
  for (int v = 0; v < n; ++v) s.positions.row(v) << u(rng), u(rng), 0.05 * u(rng);
  for (int v = 0; v + 2 < n; v += 3) s.add_face(std::vector<int>{v, v + 1, v + 2});
  const double tol = 0.02;
  const double dist = tol * (s.positions.colwise().maxCoeff() - s.positions.colwise().minCoeff()).norm();
  // Brute force: transitive closure of "closer than dist", lowest index as representative.
  std::vector<int> rep(n);
  for (int v = 0; v < n; ++v) rep[v] = v;
  for (bool changed = true; changed;) {
    changed = false;
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b)
        if ((s.positions.row(a) - s.positions.row(b)).norm() <= dist && rep[a] != rep[b]) {
          const int m = std::min(rep[a], rep[b]), x = std::max(rep[a], rep[b]);
          for (int& r : rep)
            if (r == x) r = m;
          changed = true;
        }
  }
  const PolygonSoup before = s;
  const VertexMerge m = merge_duplicate_vertices(s, tol);
  CHECK(m.n_merged > 10);  // the test is not vacuous
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) REQUIRE((rep[a] == rep[b]) == (m.vertex_map[a] == m.vertex_map[b]));
  for (int v = 0; v < n; ++v) CHECK(s.positions.row(m.vertex_map[v]) == before.positions.row(rep[v]));
}

TEST_CASE("remove_duplicate_faces removes repeats in either orientation", "[robust][repair]") {
  // Two triangles sharing edge (1, 2), then a copy of the first (rotated), and a reversed copy
  // of the second: validation rejects it, deduplication makes it valid.
  PolygonSoup s =
      soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 2}, {1, 3, 2}, {2, 0, 1}, {2, 3, 1}});
  CHECK_THROWS_AS(Mesh(s), InvalidMeshError);
  const FaceDeduplication r = remove_duplicate_faces(s);
  CHECK(r.n_same_orientation == 1);
  CHECK(r.n_opposite_orientation == 1);
  CHECK(r.face_map == std::vector<int>{0, 1, -1, -1});
  CHECK(Mesh(s).n_faces() == 2);
}

TEST_CASE("repair composes the steps, and its maps describe the result", "[robust][repair]") {
  const int nx = 3, ny = 3;
  PolygonSoup s = exploded_grid(nx, ny, 1e-9);
  // Extras: an unreferenced vertex, a duplicated face, a face that becomes degenerate once
  // its corners are welded (1 and 4 are copies of one grid vertex, 7 of another), and a face
  // with an index out of range.
  const int nv0 = s.n_vertices();
  s.positions.conservativeResize(nv0 + 1, 3);
  s.positions.row(nv0) << 5, 5, 5;
  s.add_face(std::vector<int>{0, 1, 2, 3});     // duplicate of face 0
  s.add_face(std::vector<int>{1, 4, 7});        // 1 and 4 coincide: (1 7) after welding, too few
  s.add_face(std::vector<int>{0, 1, nv0 + 5});  // out of range
  const PolygonSoup input = s;

  RepairOptions o;
  o.merge_vertices = true;
  o.merge_tolerance = 1e-7;
  const RepairReport r = repair(s, o);
  CHECK(r.changed());
  CHECK(r.drop.n_out_of_range == 1);
  CHECK(r.drop.n_too_few == 1);
  CHECK(r.drop.n_collapsed_corners == 1);
  CHECK(r.dedup.n_same_orientation == 1);
  CHECK(r.merge.n_merged == 4 * nx * ny - (nx + 1) * (ny + 1));
  CHECK(r.unreferenced.n_removed == 1);
  CHECK(r.vertex_map[nv0] == -1);
  const Mesh mesh(s);
  CHECK(mesh.n_faces() == nx * ny);
  CHECK(mesh.n_vertices() == (nx + 1) * (ny + 1));
  CHECK(check_mesh(mesh).clean());
  // Every kept face is its input face with the vertex map applied; positions move by at most
  // the merge distance.
  for (int f = 0; f < input.n_faces(); ++f) {
    if (r.face_map[f] < 0) continue;
    const auto in = face_of(input, f), out = face_of(s, r.face_map[f]);
    REQUIRE(in.size() == out.size());
    for (size_t k = 0; k < in.size(); ++k) {
      CHECK(r.vertex_map[in[k]] == out[k]);
      CHECK((input.positions.row(in[k]) - s.positions.row(out[k])).norm() <= r.merge.distance);
    }
  }
  const auto lines = r.summary();
  CHECK(lines.size() == 5);  // merged, collapsed, dropped, duplicates, unreferenced

  PolygonSoup clean = exploded_grid(2, 2, 0.0);
  const RepairReport none = repair(clean);  // merging is opt-in: nothing to do without it
  CHECK_FALSE(none.changed());
  CHECK(none.summary() == std::vector<std::string>{"nothing changed"});
}

}  // namespace test_repair
