// tests/dec/mesh/test_volume_generators.cpp — the generated volume meshes: exact volumes where they
// are analytic, Euler characteristics (1 for balls, 0 for the solid torus), positive cells,
// closed manifold boundaries, recognized cell shapes, planar faces, jitter.
#include <cmath>

#include "polydec/dec/mesh/volume_cells.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_generators {

namespace {

int euler(const VolumeMesh& m) { return m.n_vertices() - m.n_edges() + m.n_faces() - m.n_cells(); }

// Checks every cell positive, the boundary closed, connected and with Euler characteristic chi.
void check_solid(const VolumeMesh& m, int boundary_chi) {
  for (int c = 0; c < m.n_cells(); ++c) CHECK(m.cell_volume(c) > 0);
  const Mesh b = m.boundary_surface();  // throws on a non-manifold boundary edge
  CHECK(b.n_boundary_edges() == 0);
  CHECK(b.n_components() == 1);
  CHECK(b.n_vertices() - b.n_unreferenced_vertices() - b.n_edges() + b.n_faces() == boundary_chi);
  // Manifold boundary vertices: the faces around each vertex form a single cycle, so the
  // number of boundary faces at v equals the number of boundary edges at v.
  std::vector<int> faces_at(b.n_vertices(), 0), edges_at(b.n_vertices(), 0);
  for (int f = 0; f < b.n_faces(); ++f)
    for (int v : b.face(f)) ++faces_at[v];
  for (int e = 0; e < b.n_edges(); ++e) ++edges_at[b.edges()(e, 0)], ++edges_at[b.edges()(e, 1)];
  int bad = 0;
  for (int v = 0; v < b.n_vertices(); ++v) bad += faces_at[v] != edges_at[v];
  CHECK(bad == 0);
}

double max_nonplanarity(const VolumeMesh& m) {
  double worst = 0;
  for (int f = 0; f < m.n_faces(); ++f) {
    const auto vs = m.face(f);
    const Eigen::Vector3d a = m.position(vs[0]), b = m.position(vs[1]);
    // Newell normal, then the largest distance from the plane through the centroid.
    Eigen::Vector3d n = Eigen::Vector3d::Zero(), c = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < vs.size(); ++i) {
      const Eigen::Vector3d p = m.position(vs[i]), q = m.position(vs[(i + 1) % vs.size()]);
      n += p.cross(q);
      c += p;
    }
    c /= double(vs.size());
    n.normalize();
    for (int v : vs) worst = std::max(worst, std::abs((m.position(v) - c).dot(n)) / (b - a).norm());
  }
  return worst;
}

int count_shape(const VolumeMesh& m, CellShape s) {
  int n = 0;
  for (int c = 0; c < m.n_cells(); ++c) n += cell_shape(m, c) == s;
  return n;
}

}  // namespace

TEST_CASE("tet_grid_volume: 6 conforming tetrahedra per cube", "[volume]") {
  const VolumeMesh m = tet_grid_volume(2, 3, 2);
  CHECK(m.n_vertices() == 3 * 4 * 3);
  CHECK(m.n_cells() == 6 * 12);
  CHECK(count_shape(m, CellShape::tetrahedron) == 72);
  for (int c = 0; c < m.n_cells(); ++c) CHECK(m.cell_volume(c) == Approx(1.0 / 72).epsilon(1e-13));
  CHECK(m.volume() == Approx(1.0).epsilon(1e-14));
  CHECK(euler(m) == 1);
  check_solid(m, 2);
  // Every boundary square is split into two triangles.
  CHECK(m.boundary_surface().n_faces() == 2 * 2 * (2 * 3 + 3 * 2 + 2 * 2));
}

TEST_CASE("pyramid_grid_volume: 6 pyramids per cube around its centre", "[volume]") {
  const VolumeMesh m = pyramid_grid_volume(2, 2, 3);
  CHECK(m.n_vertices() == 3 * 3 * 4 + 12);
  CHECK(m.n_cells() == 6 * 12);
  CHECK(count_shape(m, CellShape::pyramid) == 72);
  for (int c = 0; c < m.n_cells(); ++c) CHECK(m.cell_volume(c) > 0);
  CHECK(m.volume() == Approx(1.0).epsilon(1e-14));
  CHECK(euler(m) == 1);
  check_solid(m, 2);
  CHECK(max_nonplanarity(m) < 1e-14);
}

TEST_CASE("truncated_octahedra_volume: the bitruncated cubic honeycomb clipped to the box", "[volume]") {
  for (int n : {1, 2, 3}) {
    INFO("n = " << n);
    const VolumeMesh m = truncated_octahedra_volume(n);
    CHECK(m.n_cells() == n * n * n + (n + 1) * (n + 1) * (n + 1));
    CHECK(m.volume() == Approx(1.0).epsilon(1e-13));
    CHECK(euler(m) == 1);
    check_solid(m, 2);
    CHECK(max_nonplanarity(m) < 1e-13);
    // Whole truncated octahedra: every centre cell and the interior corner cells, with 6 squares
    // and 8 hexagons each and volume (cube side h = 1/n) h^3 / 2.
    int whole = 0;
    for (int c = 0; c < m.n_cells(); ++c) {
      int squares = 0, hexagons = 0;
      for (int h : m.cell(c)) {
        squares += m.face_size(h / 2) == 4;
        hexagons += m.face_size(h / 2) == 6;
      }
      if (m.cell_size(c) == 14 && squares == 6 && hexagons == 8) {
        ++whole;
        CHECK(m.cell_volume(c) == Approx(0.5 / (n * n * n)).epsilon(1e-12));
      }
    }
    CHECK(whole == n * n * n + (n - 1) * (n - 1) * (n - 1));
  }
  const VolumeMesh j = truncated_octahedra_volume(2, {0.2, 5});
  CHECK(j.volume() == Approx(1.0).epsilon(1e-13));
  for (int c = 0; c < j.n_cells(); ++c) CHECK(j.cell_volume(c) > 0);
}

TEST_CASE("hex_torus_volume: a solid torus with first Betti number 1", "[volume]") {
  const int na = 12, nc = 3;
  const double R = 1.0, r = 0.4;
  const VolumeMesh m = hex_torus_volume(na, nc, R, r);
  CHECK(m.n_vertices() == na * (nc + 1) * (nc + 1));
  CHECK(m.n_cells() == na * nc * nc);
  CHECK(count_shape(m, CellShape::hexahedron) == na * nc * nc);
  CHECK(euler(m) == 0);
  check_solid(m, 0);
  CHECK(max_nonplanarity(m) < 1e-13);
  // The polygonal torus: n_around sectors with vertical faces; each sector's cross-section at
  // any height is (1/2) sin(2 pi / n) ((R + r)^2 - (R - r)^2), its height 2 r.
  const double exact = na * 0.5 * std::sin(2 * M_PI / na) * 4 * R * r * 2 * r;
  CHECK(m.volume() == Approx(exact).epsilon(1e-13));
  const VolumeMesh j = hex_torus_volume(na, nc, R, r, {0.3, 2});
  CHECK(j.volume() == Approx(exact).epsilon(1e-12));
  for (int c = 0; c < j.n_cells(); ++c) CHECK(j.cell_volume(c) > 0);
  CHECK_THROWS_AS(hex_torus_volume(2, 1), std::invalid_argument);
  CHECK_THROWS_AS(hex_torus_volume(8, 1, 1.0, 1.5), std::invalid_argument);
}

TEST_CASE("hex_ball_volume: a hexahedral unit ball", "[volume]") {
  for (int n : {2, 4, 8}) {
    INFO("n = " << n);
    const VolumeMesh m = hex_ball_volume(n);
    CHECK(m.n_cells() == n * n * n);
    CHECK(euler(m) == 1);
    check_solid(m, 2);
    for (int v = 0; v < m.n_vertices(); ++v)
      if (m.is_boundary_vertex(v))
        CHECK(m.position(v).norm() == Approx(1.0).epsilon(1e-15));
      else
        CHECK(m.position(v).norm() < 1.0);
    // Inside the unit ball, and closer to it as n grows.
    CHECK(m.volume() < 4 * M_PI / 3);
    CHECK(m.volume() > 4 * M_PI / 3 * (n >= 8 ? 0.95 : 0.6));
  }
  const VolumeMesh j = hex_ball_volume(6, {0.25, 9});
  for (int c = 0; c < j.n_cells(); ++c) CHECK(j.cell_volume(c) > 0);
  CHECK(j.volume() == Approx(hex_ball_volume(6).volume()).epsilon(1e-12));
}

TEST_CASE("jitter: interior vertices only, reproducible, the box volume kept", "[volume]") {
  const VolumeMesh t = tet_grid_volume(3, 3, 3), p = pyramid_grid_volume(3, 3, 3);
  for (const VolumeMesh* m : {&t, &p}) {
    const VolumeMesh a = jitter_interior(*m, {0.3, 11}), b = jitter_interior(*m, {0.3, 11}),
                     c = jitter_interior(*m, {0.3, 12});
    CHECK(a.positions() == b.positions());
    CHECK(a.positions() != c.positions());
    CHECK(a.volume() == Approx(1.0).epsilon(1e-13));
    for (int v = 0; v < m->n_vertices(); ++v)
      if (m->is_boundary_vertex(v)) CHECK(a.position(v) == m->position(v));
    for (int k = 0; k < a.n_cells(); ++k) CHECK(a.cell_volume(k) > 0);
  }
  CHECK_THROWS_AS(jitter_interior(t, {-1.0, 1}), std::invalid_argument);
  CHECK_THROWS_AS(hex_grid_volume(0, 1, 1), std::invalid_argument);
}

}  // namespace test_volume_generators
