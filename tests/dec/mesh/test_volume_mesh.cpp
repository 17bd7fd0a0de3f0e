// tests/dec/mesh/test_volume_mesh.cpp — VolumeMesh: the polyLaplace cubes (counts, volume,
// orientation, boundary surface), validation of bad soups (which element is named), the hex
// grid generator, the OVM reader/writer and the soup builder's face matching.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <random>

#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/polyhedron_builder.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/mesh/volume_mesh.h"
#include "tests/support/renumbered.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_mesh {

namespace {

// The soup of a validated mesh (positions, faces, cells as stored).
PolyhedronSoup to_soup(const VolumeMesh& m) {
  PolyhedronSoup s;
  s.positions = m.positions();
  for (int f = 0; f < m.n_faces(); ++f) s.add_face(m.face(f));
  for (int c = 0; c < m.n_cells(); ++c) s.add_cell(m.cell(c));
  return s;
}

// Signed volume of a soup's cell computed independently of VolumeMesh: tetrahedra from the
// cell's vertex centroid over fan triangles of its half-faces.
double soup_cell_volume(const PolyhedronSoup& s, int c) {
  Eigen::Vector3d o = Eigen::Vector3d::Zero();
  int n = 0;
  for (int k = s.cell_offsets[c]; k < s.cell_offsets[c + 1]; ++k) {
    const int f = s.cell_halffaces[k] / 2;
    for (int i = s.face_offsets[f]; i < s.face_offsets[f + 1]; ++i, ++n)
      o += s.positions.row(s.face_indices[i]).transpose();
  }
  o /= n;
  double v = 0;
  for (int k = s.cell_offsets[c]; k < s.cell_offsets[c + 1]; ++k) {
    const int h = s.cell_halffaces[k], f = h / 2, b = s.face_offsets[f], m = s.face_offsets[f + 1] - b;
    std::vector<Eigen::Vector3d> p;
    for (int i = 0; i < m; ++i) p.push_back(s.positions.row(s.face_indices[b + i]).transpose() - o);
    if (h & 1) std::reverse(p.begin(), p.end());
    for (int i = 1; i + 1 < m; ++i) v += p[0].dot(p[i].cross(p[i + 1])) / 6;
  }
  return v;
}

struct SharedCube {
  const char* file;
  int vertices, cells;
  double volume;
  double tolerance = 1e-12;  // relative
};

const SharedCube kShared[] = {
    {"cube_hexahedron_1.ovm", 27, 8, 1},    {"cube_hexahedron_2.ovm", 125, 64, 1},
    {"cube_hexahedron_3.ovm", 729, 512, 1}, {"cube_hexahedron_4.ovm", 4913, 4096, 1},
    {"cube_pyramids_1.ovm", 21, 14, 1},     {"cube_pyramids_2.ovm", 89, 112, 1},
    {"cube_pyramids_3.ovm", 489, 896, 1},   {"cube_pyramids_4.ovm", 3185, 7168, 1},
    {"cube_truncated_1.ovm", 20, 9, 1},     {"cube_truncated_2.ovm", 81, 72, 1},
    {"cube_truncated_3.ovm", 425, 576, 1},  {"cube_truncated_4.ovm", 2673, 4608, 1},
    {"cube_tetrahedron_1.ovm", 87, 304, 8}, {"cube_tetrahedron_2.ovm", 646, 3194, 8},
    {"noisycube.ovm", 125, 64, 1, 1e-2},  // its boundary is jittered too
};

// Catches the InvalidMeshError of validating `s` and checks its element and index.
void expect_invalid(PolyhedronSoup s, const std::string& element, long index, const std::string& reason) {
  try {
    VolumeMesh m(std::move(s));
    FAIL("accepted a bad soup (" << reason << ")");
  } catch (const InvalidMeshError& e) {
    INFO(e.what());
    CHECK(e.element == element);
    CHECK(e.index == index);
    CHECK(std::string(e.what()).find(reason) != std::string::npos);
  }
}

// Two unit cubes side by side (hex_grid_volume(2, 1, 1)) and their shared face.
struct TwoCubes {
  PolyhedronSoup soup;
  int shared = -1;
  TwoCubes() {
    const VolumeMesh m = hex_grid_volume(2, 1, 1);
    soup = to_soup(m);
    for (int f = 0; f < m.n_faces(); ++f)
      if (!m.is_boundary_face(f)) shared = f;
  }
  // Index in cell_halffaces of the shared face in cell c.
  int slot(int c) const {
    for (int k = soup.cell_offsets[c]; k < soup.cell_offsets[c + 1]; ++k)
      if (soup.cell_halffaces[k] / 2 == shared) return k;
    return -1;
  }
};

}  // namespace

TEST_CASE("the polyLaplace cubes read with their counts, volume and a closed boundary", "[volume]") {
  for (const auto& cube : kShared) {
    POLYDEC_SHARED_MESH(path, std::string("volume/") + cube.file);
    INFO(cube.file);
    const VolumeMesh m = read_volume_mesh(path);
    CHECK(m.n_vertices() == cube.vertices);
    CHECK(m.n_cells() == cube.cells);
    CHECK(m.n_unreferenced_vertices() == 0);
    CHECK(m.volume() == Approx(cube.volume).epsilon(cube.tolerance));
    double min_volume = 1e300;
    for (int c = 0; c < m.n_cells(); ++c) min_volume = std::min(min_volume, m.cell_volume(c));
    CHECK(min_volume > 0);
    CHECK(m.n_vertices() - m.n_edges() + m.n_faces() - m.n_cells() == 1);
    const Mesh b = m.boundary_surface();
    CHECK(b.n_boundary_edges() == 0);
    CHECK(b.n_components() == 1);
    CHECK(b.n_vertices() - b.n_unreferenced_vertices() - b.n_edges() + b.n_faces() == 2);
    // Boundary vertices of the volume are exactly the referenced vertices of the surface.
    int n_boundary = 0;
    for (int v = 0; v < m.n_vertices(); ++v) n_boundary += m.is_boundary_vertex(v);
    CHECK(n_boundary == b.n_vertices() - b.n_unreferenced_vertices());
    // cell_vertices: ascending, unique, the union of the cell's faces.
    for (int c = 0; c < std::min(m.n_cells(), 50); ++c) {
      const auto cv = m.cell_vertices(c);
      CHECK(std::adjacent_find(cv.begin(), cv.end(), std::greater_equal<int>()) == cv.end());
      for (int h : m.cell(c))
        for (int v : m.face(h / 2)) CHECK(std::binary_search(cv.begin(), cv.end(), v));
    }
  }
}

TEST_CASE("the OVM files' inward cells are flipped once to outward", "[volume]") {
  POLYDEC_SHARED_MESH(path, "volume/cube_truncated_2.ovm");
  const PolyhedronSoup s = read_polyhedron_soup(path);
  for (int c = 0; c < s.n_cells(); ++c) REQUIRE(soup_cell_volume(s, c) < 0);  // as the data README says
  const VolumeMesh m(s);
  for (int c = 0; c < m.n_cells(); ++c) {
    CHECK(m.cell_volume(c) == Approx(-soup_cell_volume(s, c)).epsilon(1e-12));
    const auto hf = m.cell(c);
    for (size_t k = 0; k < hf.size(); ++k) CHECK(hf[k] == (s.cell_halffaces[s.cell_offsets[c] + k] ^ 1));
  }
  // face_cells: [0] holds 2f after the flip.
  for (int f = 0; f < m.n_faces(); ++f) {
    const auto fc = m.face_cells(f);
    for (int side = 0; side < 2; ++side)
      if (fc[side] >= 0) {
        const auto hf = m.cell(fc[side]);
        CHECK(std::find(hf.begin(), hf.end(), 2 * f + side) != hf.end());
      }
  }
  // An outward soup is left as it is.
  const VolumeMesh again(to_soup(m));
  for (int c = 0; c < m.n_cells(); ++c)
    CHECK(std::equal(again.cell(c).begin(), again.cell(c).end(), m.cell(c).begin()));
}

TEST_CASE("bad polyhedron soups are rejected naming the element", "[volume]") {
  SECTION("the two cubes are valid") {
    TwoCubes t;
    REQUIRE(t.shared >= 0);
    const VolumeMesh m(t.soup);
    CHECK(m.volume() == Approx(1.0));
    CHECK(m.n_faces() == 11);
  }
  SECTION("open cell") {
    // Cell 1 loses a side: its face is removed from the face list (faces renumbered).
    TwoCubes t;
    const int dropped =
        t.soup.cell_halffaces[t.soup.cell_offsets[1] + (t.slot(1) == t.soup.cell_offsets[1] ? 1 : 0)] / 2;
    PolyhedronSoup s;
    s.positions = t.soup.positions;
    std::vector<int> renumber(t.soup.n_faces(), -1);
    for (int f = 0; f < t.soup.n_faces(); ++f)
      if (f != dropped)
        renumber[f] = s.add_face({t.soup.face_indices.data() + t.soup.face_offsets[f],
                                  size_t(t.soup.face_offsets[f + 1] - t.soup.face_offsets[f])});
    for (int c = 0; c < t.soup.n_cells(); ++c) {
      std::vector<int> hf;
      for (int k = t.soup.cell_offsets[c]; k < t.soup.cell_offsets[c + 1]; ++k) {
        const int h = t.soup.cell_halffaces[k];
        if (h / 2 != dropped) hf.push_back(2 * renumber[h / 2] + (h & 1));
      }
      s.add_cell(hf);
    }
    expect_invalid(s, "cell", 1, "cell 1 is not closed");
    // The face kept in the list but used by no cell.
    PolyhedronSoup u = t.soup;
    u.cell_halffaces.erase(u.cell_halffaces.begin() + u.cell_offsets[1] +
                           (t.slot(1) == u.cell_offsets[1] ? 1 : 0));
    u.cell_offsets[2] -= 1;
    expect_invalid(u, "face", dropped, "belongs to no cell");
  }
  SECTION("a face in three cells") {
    TwoCubes t;
    PolyhedronSoup s = t.soup;
    std::vector<int> copy(s.cell_halffaces.begin() + s.cell_offsets[1],
                          s.cell_halffaces.begin() + s.cell_offsets[2]);
    std::swap(copy[0], copy[t.slot(1) - s.cell_offsets[1]]);  // the shared face first
    s.add_cell(copy);
    expect_invalid(s, "face", t.shared, "used by three or more cells");
  }
  SECTION("inconsistent orientation: one cell turned inside out") {
    TwoCubes t;
    PolyhedronSoup s = t.soup;
    for (int k = s.cell_offsets[1]; k < s.cell_offsets[2]; ++k) s.cell_halffaces[k] ^= 1;
    expect_invalid(s, "face", t.shared, "inconsistent orientation");
  }
  SECTION("inconsistent orientation within a cell") {
    TwoCubes t;
    PolyhedronSoup s = t.soup;
    const int k = s.cell_offsets[0] == t.slot(0) ? s.cell_offsets[0] + 1 : s.cell_offsets[0];
    s.cell_halffaces[k] ^= 1;  // a boundary face of cell 0 reversed
    expect_invalid(s, "cell", 0, "same direction");
  }
  SECTION("NaN and huge coordinates") {
    TwoCubes t;
    PolyhedronSoup s = t.soup;
    s.positions(5, 1) = std::nan("");
    expect_invalid(s, "vertex", 5, "vertex 5 has a non-finite coordinate");
    s = t.soup;
    s.positions(2, 0) = 2e300;
    expect_invalid(s, "vertex", 2, "above the limit");
  }
  SECTION("indices out of range") {
    TwoCubes t;
    PolyhedronSoup s = t.soup;
    s.face_indices[s.face_offsets[3] + 1] = 99;
    expect_invalid(s, "face", 3, "face 3 refers to vertex 99, out of range [0, 12)");
    s = t.soup;
    s.cell_halffaces[s.cell_offsets[1] + 1] = 22;
    expect_invalid(s, "cell", 1, "half-face 22, out of range [0, 22)");
    s = t.soup;
    s.cell_halffaces[s.cell_offsets[1] + 1] = -1;
    expect_invalid(s, "cell", 1, "half-face -1");
  }
  SECTION("short and repeated faces, duplicates, a face used twice in a cell") {
    TwoCubes t;
    PolyhedronSoup s = t.soup;
    s.face_indices[s.face_offsets[4] + 2] = s.face_indices[s.face_offsets[4]];
    expect_invalid(s, "face", 4, "repeats vertex");
    s = t.soup;
    const std::vector<int> copy(s.face_indices.begin() + s.face_offsets[2],
                                s.face_indices.begin() + s.face_offsets[3]);
    const int f = s.add_face(copy);
    expect_invalid(s, "face", f, "same vertices as face 2");
    s = t.soup;
    s.cell_halffaces[s.cell_offsets[0] + 1] = s.cell_halffaces[s.cell_offsets[0]] ^ 1;
    expect_invalid(s, "cell", 0, "uses face");
    s = t.soup;
    s.face_offsets.back() += 1;
    expect_invalid(s, "face", 0, "offsets");
  }
  SECTION("a disconnected cell") {
    // Two separate cubes (no shared face) listed as one cell.
    const VolumeMesh a = hex_grid_volume(1, 1, 1);
    PolyhedronSoup s;
    s.positions.resize(16, 3);
    s.positions.topRows(8) = a.positions();
    s.positions.bottomRows(8) = a.positions().rowwise() + Eigen::RowVector3d(3, 0, 0);
    std::vector<int> hf;
    for (int copy = 0; copy < 2; ++copy)
      for (int h : a.cell(0)) {
        std::vector<int> poly(a.face(h / 2).begin(), a.face(h / 2).end());
        for (int& v : poly) v += 8 * copy;
        hf.push_back(2 * s.add_face(poly) + (h & 1));
      }
    s.add_cell(hf);
    expect_invalid(s, "cell", 0, "not connected");
  }
}

TEST_CASE("hex_grid_volume: counts, exact volumes, Euler characteristic, jitter", "[volume]") {
  const VolumeMesh m = hex_grid_volume(3, 2, 4);
  CHECK(m.n_vertices() == 4 * 3 * 5);
  CHECK(m.n_cells() == 24);
  CHECK(m.n_faces() == 4 * 2 * 4 + 3 * 3 * 4 + 3 * 2 * 5);
  CHECK(m.n_vertices() - m.n_edges() + m.n_faces() - m.n_cells() == 1);
  for (int c = 0; c < m.n_cells(); ++c) CHECK(m.cell_volume(c) == Approx(1.0 / 24).epsilon(1e-14));
  CHECK(m.volume() == Approx(1.0).epsilon(1e-14));
  CHECK(m.bounding_box_diagonal() == Approx(std::sqrt(3.0)));
  const Mesh b = m.boundary_surface();
  CHECK(b.n_boundary_edges() == 0);
  CHECK(b.n_faces() == 2 * (3 * 2 + 2 * 4 + 3 * 4));
  CHECK(b.n_vertices() - b.n_unreferenced_vertices() - b.n_edges() + b.n_faces() == 2);

  const VolumeMesh j = hex_grid_volume(3, 2, 4, {0.3, 7});
  const VolumeMesh j2 = hex_grid_volume(3, 2, 4, {0.3, 7});
  CHECK(j.positions() == j2.positions());
  CHECK(j.volume() == Approx(1.0).epsilon(1e-12));  // boundary fixed: the total volume stays
  int moved = 0;
  for (int v = 0; v < m.n_vertices(); ++v) {
    const double d = (j.position(v) - m.position(v)).norm();
    if (m.is_boundary_vertex(v))
      CHECK(d == 0.0);
    else {
      CHECK(d <= 0.3 * 0.25 + 1e-15);  // shortest incident edge 1/4
      moved += d > 0;
    }
  }
  CHECK(moved == 2 * 1 * 3);
  for (int c = 0; c < j.n_cells(); ++c) CHECK(j.cell_volume(c) > 0);
}

TEST_CASE("OVM: write and read back the same mesh", "[volume]") {
  const VolumeMesh m = hex_grid_volume(2, 3, 2, {0.2, 3});
  const std::string text = write_volume_mesh_to_string(m, "ovm");
  const VolumeMesh r = read_volume_mesh_from_memory(text, "ovm", "mem.ovm");
  CHECK(r.positions() == m.positions());
  REQUIRE(r.n_faces() == m.n_faces());
  REQUIRE(r.n_cells() == m.n_cells());
  for (int f = 0; f < m.n_faces(); ++f)
    CHECK(std::equal(r.face(f).begin(), r.face(f).end(), m.face(f).begin()));
  for (int c = 0; c < m.n_cells(); ++c)
    CHECK(std::equal(r.cell(c).begin(), r.cell(c).end(), m.cell(c).begin()));
  CHECK(r.volume() == m.volume());
  // Through a file, too.
  const test::ScratchDir scratch("test_volume_mesh");
  const std::string path = scratch.path("m.ovm");
  write_volume_mesh(m, path);
  CHECK(read_volume_mesh(path).positions() == m.positions());
  CHECK(is_volume_mesh_path("a/b.OVM"));
  CHECK(is_volume_mesh_path("x.vtk"));
  CHECK(is_volume_mesh_path("x.mesh"));
  CHECK_FALSE(is_volume_mesh_path("x.off"));
}

TEST_CASE("OVM: bad files name the line", "[volume]") {
  const std::string good =
      "OVM ASCII\nVertices\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nEdges\n6\n0 1\n1 2\n2 0\n0 3\n1 3\n2 3\n"
      "Faces\n4\n3 0 2 4\n3 6 9 1\n3 8 11 3\n3 5 10 7\nPolyhedra\n1\n4 0 2 4 6\n";
  // Faces (0 1 2), (0 3 1), (1 3 2), (0 2 3): every normal points into the tetrahedron.
  const VolumeMesh m = read_volume_mesh_from_memory(good, "ovm", "t.ovm");
  CHECK(m.volume() == Approx(1.0 / 6));
  struct Bad {
    std::string text;
    long line;
    const char* reason;
  };
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto p = s.find(from);
    REQUIRE(p != std::string::npos);
    return s.replace(p, from.size(), to);
  };
  const Bad cases[] = {
      {"", 0, "empty file"},
      {"OVM BINARY\n", 1, "OVM BINARY is not supported"},
      {"PLY\n", 1, "expected the header 'OVM ASCII'"},
      {replace("Vertices\n4\n", "Vertices\n40000000\n"), 3, "Vertices count 40000000 needs at least"},
      {replace("Vertices\n4\n", "Vertices\n-4\n"), 3, "negative Vertices count"},
      {replace("Vertices\n4\n", "Vertices\n99999999999\n"), 3, "is too large"},
      {replace("0 1 0\n", "0 nan 0\n"), 6, "vertex 2 has a non-finite coordinate"},
      {replace("0 1 0\n", "0 1\n"), 6, "a vertex needs 3 coordinates"},
      {replace("0 1 0\n", "0 x 0\n"), 6, "bad vertex coordinate 'x'"},
      {replace("2 3\nFaces", "2 4\nFaces"), 15, "edge vertex index 4 out of range [0, 4)"},
      {replace("3 0 2 4\n", "3 0 2 12\n"), 18, "halfedge 12 out of range [0, 12)"},
      {replace("3 0 2 4\n", "3 0 3 4\n"), 18,
       "halfedge 3 starts at vertex 2 but the previous one ends at vertex 1"},
      {replace("3 0 2 4\n", "4 0 2 4\n"), 18, "the record lists 4 halfedges but the line has 3 more numbers"},
      {replace("4 0 2 4 6\n", "4 0 2 4 8\n"), 24, "half-face 8 out of range [0, 8)"},
      {replace("4 0 2 4 6\n", "3 0 2 4\n"), 24, "cell 0 has 3 faces"},
      {replace("4 0 2 4 6\n", "4 0 2 4 7\n"), 24, "cell 0: two of its half-faces traverse edge"},
      {replace("Polyhedra\n1\n4 0 2 4 6\n", "Polyhedra\n2\n4 0 2 4 6\n"), 24,
       "unexpected end of file after 1 of 2 polyhedra"},
      {replace("Edges", "Edgez"), 8, "expected the section 'Edges'"},
  };
  for (const auto& b : cases) {
    INFO(b.text);
    try {
      read_volume_mesh_from_memory(b.text, "ovm", "t.ovm");
      FAIL("accepted");
    } catch (const FileError& e) {
      INFO(e.what());
      CHECK(e.file == "t.ovm");
      if (b.line > 0) CHECK(e.line == b.line);
      CHECK(e.reason.find(b.reason) != std::string::npos);
    }
  }
  CHECK_THROWS_AS(read_volume_mesh("/nonexistent/x.ovm"), FileError);
  CHECK_THROWS_AS(read_volume_mesh("x.stl"), FileError);
}

TEST_CASE("VolumeMesh edges equal the sorted distinct sides of its faces", "[volume]") {
  // Mixed polyhedra (cuboctahedra and octahedra) with the vertices renumbered at random, so that
  // sides are met out of order; the oracle is a comparison sort of all sides.
  const VolumeMesh base = cuboctahedra_volume(2);
  const VolumeMesh m = test::renumbered(base, test::random_permutation(base.n_vertices(), 5));
  std::vector<std::pair<int, int>> sides;
  for (int f = 0; f < m.n_faces(); ++f) {
    const auto face = m.face(f);
    for (size_t i = 0; i < face.size(); ++i) {
      const int p = face[i], q = face[(i + 1) % face.size()];
      sides.emplace_back(std::min(p, q), std::max(p, q));
    }
  }
  std::sort(sides.begin(), sides.end());
  sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
  REQUIRE(m.edges().rows() == long(sides.size()));
  for (size_t e = 0; e < sides.size(); ++e)
    CHECK(std::pair(m.edges()(long(e), 0), m.edges()(long(e), 1)) == sides[e]);
  CHECK(m.n_vertices() - long(sides.size()) + m.n_faces() - m.n_cells() == 1);  // a ball
}

TEST_CASE("PolyhedronSoupBuilder matches faces by vertex set as a brute-force search does", "[volume]") {
  // Polygons drawn from a few vertices, so that vertex sets repeat in the same, the reversed and
  // other cyclic orders; thousands of faces, so that the builder's table grows several times.
  // The oracle: a map from each sorted vertex set to the first polygon (face) with it.
  std::mt19937 rng(7);
  PolyhedronSoupBuilder builder(Eigen::MatrixX3d::Zero(40, 3));
  std::map<std::vector<int>, int> first;  // sorted vertex set -> face
  std::vector<std::vector<int>> faces;
  int n_same = 0, n_reversed = 0, n_rejected = 0;
  for (int k = 0; k < 20000; ++k) {
    const int n = 3 + int(rng() % 3);
    std::vector<int> poly;
    while (int(poly.size()) < n) {
      const int v = int(rng() % 14);
      if (std::find(poly.begin(), poly.end(), v) == poly.end()) poly.push_back(v);
    }
    if (k % 3 == 1 && !faces.empty()) {  // an earlier face, rotated and perhaps reversed or shuffled
      poly = faces[rng() % faces.size()];
      std::rotate(poly.begin(), poly.begin() + long(rng() % poly.size()), poly.end());
      if (rng() % 2) std::reverse(poly.begin(), poly.end());
      if (rng() % 4 == 0) std::swap(poly[0], poly[1]);
    }
    std::vector<int> key = poly;
    std::sort(key.begin(), key.end());
    int expected;
    if (const auto it = first.find(key); it == first.end()) {
      expected = 2 * int(faces.size());
      first.emplace(key, int(faces.size()));
      faces.push_back(poly);
    } else {
      const std::vector<int>& f = faces[size_t(it->second)];
      const size_t m = f.size(), p = size_t(std::find(f.begin(), f.end(), poly[0]) - f.begin());
      bool same = true, reversed = true;
      for (size_t i = 0; i < m; ++i) {
        same = same && poly[i] == f[(p + i) % m];
        reversed = reversed && poly[i] == f[(p + m - i) % m];
      }
      expected = same ? 2 * it->second : reversed ? 2 * it->second + 1 : -1;
    }
    n_same += expected >= 0 && expected % 2 == 0 && expected / 2 < int(faces.size()) - 1;
    n_reversed += expected >= 0 && expected % 2 == 1;
    n_rejected += expected < 0;
    REQUIRE(builder.add_polygon(poly) == expected);
    REQUIRE(builder.n_faces() == int(faces.size()));
  }
  // Every case occurred often (the oracle's counts, not the builder's).
  CHECK(n_same > 500);
  CHECK(n_reversed > 500);
  CHECK(n_rejected > 500);
  CHECK(faces.size() > 2000);
  const PolyhedronSoup soup = builder.take();
  for (size_t f = 0; f < faces.size(); ++f)
    CHECK(std::equal(faces[f].begin(), faces[f].end(), soup.face_indices.begin() + soup.face_offsets[f],
                     soup.face_indices.begin() + soup.face_offsets[f + 1]));
}

}  // namespace test_volume_mesh
