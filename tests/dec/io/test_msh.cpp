// tests/dec/io/test_msh.cpp — gmsh .msh (2.2 and 4.1, ASCII and binary) and MEDIT .mesh/.meshb
// files written by gmsh 4.8.4 and meshio 5.0 (tests/data/msh/make_fixtures.sh): exact counts,
// groups and skipped elements checked against the geometry, volumes and areas against the
// analytic values, ASCII and binary identical; the .msh writer's round trips; hostile files
// refused with their line or byte offset.
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <regex>
#include <set>

#include "polydec/dec/io/mesh_groups.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_cells.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/mesh/generators.h"
#include "tests/support/support.h"
#include "tests/support/volume_meshes.h"

using namespace polydec;

namespace test_msh {
namespace {

std::string fixture(const std::string& name) { return std::string(POLYDEC_TEST_DATA) + "/msh/" + name; }

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The vertices whose coordinates satisfy `pred`, sorted.
template <class Pred>
std::vector<int> where(const Eigen::MatrixX3d& X, Pred pred) {
  std::vector<int> out;
  for (int v = 0; v < X.rows(); ++v)
    if (pred(X.row(v))) out.push_back(v);
  return out;
}

using test::outward_faces;

// The same cells with the same outward faces; positions equal to `tolerance` relative.
void check_same(const VolumeMesh& a, const VolumeMesh& b, double tolerance = 0) {
  REQUIRE(a.n_vertices() == b.n_vertices());
  CHECK((a.positions() - b.positions()).cwiseAbs().maxCoeff() <= tolerance * a.positions().cwiseAbs().maxCoeff());
  REQUIRE(a.n_cells() == b.n_cells());
  int differ = 0;
  for (int c = 0; c < a.n_cells(); ++c) differ += outward_faces(a, c) != outward_faces(b, c);
  CHECK(differ == 0);
}

void check_same(const Mesh& a, const Mesh& b, double tolerance = 0) {
  REQUIRE(a.n_vertices() == b.n_vertices());
  CHECK((a.positions() - b.positions()).cwiseAbs().maxCoeff() <= tolerance * a.positions().cwiseAbs().maxCoeff());
  REQUIRE(a.n_faces() == b.n_faces());
  int differ = 0;
  for (int f = 0; f < a.n_faces(); ++f) {
    const auto x = a.face(f), y = b.face(f);
    differ += !std::equal(x.begin(), x.end(), y.begin(), y.end());
  }
  CHECK(differ == 0);
}

// A gmsh file's text read as a volume (or surface) must fail at `at` (a line, or a byte offset
// with `binary`) with `reason` in the message.
void expect_error(const std::string& text, bool volume, long at, const std::string& reason, bool binary = false) {
  INFO(text.substr(0, 300));
  try {
    if (volume)
      read_volume_mesh_from_memory(text, "msh", "bad");
    else
      read_mesh_from_memory(text, "msh", "bad");
    FAIL("accepted a bad file (" << reason << ")");
  } catch (const FileError& e) {
    INFO(e.what());
    CHECK(e.file == "bad");
    CHECK((binary ? e.byte_offset : e.line) == at);
    CHECK(e.reason.find(reason) != std::string::npos);
  }
}

// Appends the bytes of x in little- or big-endian order.
template <class T>
void put(std::string& out, T x, bool big) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &x, sizeof(T));
  if (big != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  REQUIRE(p != std::string::npos);
  return s.replace(p, from.size(), to);
}

const char* kEncodings[] = {"22_ascii", "22_binary", "41_ascii", "41_binary"};

// Sum of the areas of a planar surface's faces (fan triangulation; the faces are convex).
double area(const Mesh& m) {
  double a = 0;
  for (int f = 0; f < m.n_faces(); ++f) {
    const auto vs = m.face(f);
    for (size_t k = 1; k + 1 < vs.size(); ++k)
      a += 0.5 * (m.position(vs[k]) - m.position(vs[0])).cross(m.position(vs[k + 1]) - m.position(vs[0])).norm();
  }
  return a;
}

}  // namespace

TEST_CASE("gmsh surfaces: triangles and quadrangles, groups, skipped points and lines", "[io][msh]") {
  for (const std::string kind : {"tri", "quad"}) {
    const Mesh ref = read_mesh(fixture(kind + "_41_ascii.msh"));
    for (const char* encoding : kEncodings) {
      const std::string path = fixture(kind + "_" + encoding + ".msh");
      INFO(path);
      CHECK(!is_volume_mesh_path(path));
      MeshGroups g;
      const Mesh m = read_mesh_with_groups(path, g);
      CHECK(m.n_vertices() == (kind == "tri" ? 13 : 18));
      CHECK(m.n_faces() == (kind == "tri" ? 14 : 11));
      for (int f = 0; f < m.n_faces(); ++f) CHECK(m.face_size(f) == (kind == "tri" ? 3 : 4));
      CHECK(area(m) == Approx(2.0).epsilon(1e-14));
      // Oriented: every face's normal is the same (the rectangle lies in z = 0).
      CHECK(m.n_unreferenced_vertices() == 0);
      CHECK(g.skipped == std::map<std::string, long>{{"lines", 2}, {"points", 1}});
      REQUIRE(g.vertices.size() == 3);
      CHECK(g.vertices["plate"].size() == size_t(m.n_vertices()));
      CHECK(g.vertices["left"] == where(m.positions(), [](auto x) { return x[0] == 0; }));
      CHECK(g.vertices["left"].size() == 3);
      CHECK(g.vertices["origin"] == where(m.positions(), [](auto x) { return x.norm() == 0; }));
      REQUIRE(g.elements.size() == 1);
      CHECK(g.elements["plate"].size() == size_t(m.n_faces()));
      CHECK(read_mesh_groups(path).vertices == g.vertices);
      // ASCII (16 significant digits) and binary files describe the same mesh.
      check_same(ref, m, 1e-15);
    }
  }
}

TEST_CASE("gmsh volumes: each cell kind in 2.2 and 4.1, ASCII and binary", "[io][msh][volume]") {
  struct Kind {
    const char* name;
    int vertices, cells;
    std::map<std::string, long> skipped;
    std::map<CellShape, int> shapes;
  };
  const Kind kinds[] = {
      {"tet", 44, 90, {{"lines", 2}, {"points", 1}, {"triangles", 14}}, {{CellShape::tetrahedron, 90}}},
      {"hex", 27, 8, {{"quadrangles", 4}}, {{CellShape::hexahedron, 8}}},
      {"prism", 39, 28, {{"triangles", 14}}, {{CellShape::wedge, 28}}},
      {"pyramid", 13, 12, {}, {{CellShape::tetrahedron, 10}, {CellShape::hexahedron, 1}, {CellShape::pyramid, 1}}}};
  for (const Kind& k : kinds) {
    for (const char* encoding : kEncodings) {
      const std::string path = fixture(std::string(k.name) + "_" + encoding + ".msh");
      // gmsh 2.2 orders the elements by type: the ASCII file of the same version is the reference.
      const VolumeMesh ref = read_volume_mesh(fixture(std::string(k.name) + "_" + std::string(encoding).substr(0, 2) + "_ascii.msh"));
      INFO(path);
      CHECK(is_volume_mesh_path(path));
      MeshGroups g;
      const VolumeMesh m = read_volume_mesh_with_groups(path, g);
      CHECK(m.n_vertices() == k.vertices);
      CHECK(m.n_cells() == k.cells);
      std::map<CellShape, int> shapes;
      int nonpositive = 0;
      for (int c = 0; c < m.n_cells(); ++c) {
        ++shapes[cell_shape(m, c)];
        nonpositive += !(m.cell_volume(c) > 0);
      }
      CHECK(shapes == k.shapes);
      CHECK(nonpositive == 0);  // gmsh's node orders (the prism's reversed from VTK's) map right
      CHECK(m.volume() == Approx(2.0).epsilon(1e-13));
      CHECK(g.skipped == k.skipped);
      check_same(ref, m, 1e-15);
      const Eigen::MatrixX3d& X = m.positions();
      const std::string kind = k.name;
      if (kind == "tet") {
        CHECK(g.vertices.size() == 4);
        CHECK(g.vertices["solid"].size() == 44);
        CHECK(g.vertices["left"] == where(X, [](auto x) { return x[0] == 0; }));
        CHECK(g.vertices["edge"] == where(X, [](auto x) { return x[0] == 0 && x[1] == 0; }));
        CHECK(g.vertices["edge"].size() == 3);
        CHECK(g.vertices["corner"] == where(X, [](auto x) { return x[0] == 0 && x[1] == 0 && x[2] == 1; }));
        // The 14 skipped triangles are the boundary faces on x = 0.
        int left_faces = 0;
        for (int f = 0; f < m.n_faces(); ++f) {
          bool on = m.is_boundary_face(f);
          for (int v : m.face(f)) on = on && X(v, 0) == 0;
          left_faces += on;
        }
        CHECK(left_faces == 14);
        CHECK(g.elements.size() == 1);
        CHECK(g.elements["solid"].size() == 90);
      } else if (kind == "hex") {
        CHECK(g.vertices["left"] == where(X, [](auto x) { return x[0] == 0; }));
        CHECK(g.vertices["left"].size() == 9);
      } else if (kind == "prism") {
        CHECK(g.vertices["bottom"] == where(X, [](auto x) { return x[2] == 0; }));
        CHECK(g.vertices["bottom"].size() == 13);
      } else {
        CHECK(g.vertices["hexes"] == where(X, [](auto x) { return x[0] <= 1; }));
        CHECK(g.vertices["tets"] == where(X, [](auto x) { return x[0] >= 1; }));
        REQUIRE(g.elements["hexes"].size() == 1);
        CHECK(cell_shape(m, g.elements["hexes"][0]) == CellShape::hexahedron);
        CHECK(g.elements["tets"].size() == 11);
      }
    }
  }
}

TEST_CASE("MEDIT prisms and pyramids and binary .meshb of GMF versions 3 and 4", "[io][msh][volume]") {
  for (const std::string kind : {"tet", "hex", "prism", "pyramid"}) {
    INFO(kind);
    const VolumeMesh ref = read_volume_mesh(fixture(kind + "_41_ascii.msh"));
    const VolumeMesh ascii = read_volume_mesh(fixture(kind + ".mesh"));
    MeshGroups g;
    const VolumeMesh binary = read_volume_mesh_with_groups(fixture(kind + ".meshb"), g);
    // meshio wrote the doubles it read from the 4.1 file: the same numbers.
    check_same(ref, ascii);
    check_same(ref, binary);
    CHECK(binary.volume() == Approx(2.0).epsilon(1e-13));
    if (kind == "tet") CHECK(g.skipped == std::map<std::string, long>{{"lines", 2}, {"triangles", 14}});
    if (kind == "prism") CHECK(g.skipped == std::map<std::string, long>{{"triangles", 14}});
  }
}

TEST_CASE("meshb: versions 1 and 2 (float and double, 32-bit), both byte orders, hostile files", "[io][msh][volume]") {
  // One tetrahedron, written by hand: code, version, Dimension, Vertices, Tetrahedra, End.
  auto make = [](int version, bool big) {
    std::string s;
    auto i32 = [&](std::int32_t x) { put(s, x, big); };
    auto pos = [&](long long x) { version >= 3 ? put(s, std::int64_t(x), big) : i32(std::int32_t(x)); };
    auto integer = [&](long long x) { version == 4 ? put(s, std::int64_t(x), big) : i32(std::int32_t(x)); };
    auto real = [&](double x) { version == 1 ? put(s, float(x), big) : put(s, x, big); };
    i32(1);
    i32(version);
    i32(3);
    pos(0);
    i32(3);
    i32(4);
    pos(0);
    integer(4);
    const double X[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const auto& x : X) {
      for (double c : x) real(c);
      integer(0);
    }
    i32(99);  // an unknown keyword, skipped by its next position
    pos(s.size() + (version >= 3 ? 8 : 4) + 12);
    s.append(12, '\0');
    i32(8);
    pos(0);
    integer(1);
    for (int v : {1, 2, 3, 4, 0}) integer(v);
    i32(54);
    return s;
  };
  for (int version = 1; version <= 4; ++version)
    for (bool big : {false, true}) {
      INFO(version << (big ? " big-endian" : " little-endian"));
      const VolumeMesh m = read_volume_mesh_from_memory(make(version, big), "meshb", "t.meshb");
      CHECK(m.n_cells() == 1);
      CHECK(m.volume() == Approx(1.0 / 6).epsilon(1e-15));
    }
  const std::string good = make(2, false);
  {
    // Recognized by its code word where the extension says nothing.
    test::ScratchDir dir("meshb");
    std::ofstream(dir.path("t.bin"), std::ios::binary) << make(3, true);
    CHECK(read_volume_mesh(dir.path("t.bin")).n_cells() == 1);
  }
  auto expect = [](const std::string& bytes, long at, const std::string& reason) {
    try {
      read_volume_mesh_from_memory(bytes, "meshb", "bad");
      FAIL("accepted " << reason);
    } catch (const FileError& e) {
      INFO(e.what());
      CHECK(e.byte_offset == at);
      CHECK(e.reason.find(reason) != std::string::npos);
    }
  };
  expect(std::string("\2\0\0\0\2\0\0\0", 8), 0, "not a binary MEDIT file");
  expect(replace(good, std::string("\2\0\0\0", 4), std::string("\7\0\0\0", 4)), 4, "unknown MEDIT version 7");
  // The vertex count 4 at byte 28 becomes 1000: more than the file holds.
  std::string lying = good;
  lying[28] = char(0xe8), lying[29] = char(0x03);
  expect(lying, 28, "vertex count 1000 needs");
  // A vertex index 5 (of 4) in the tetrahedron: its first index follows the vertex count and the 4
  // vertices (28 bytes each), the skipped keyword (code, position, 12 bytes) and the Tetrahedra
  // keyword's code, position and count.
  std::string out_of_range = good;
  const size_t first_index = 28 + 4 + 4 * 28 + 8 + 12 + 12;
  out_of_range[first_index] = 5;
  expect(out_of_range, long(first_index), "vertex index 5 out of range [1, 4]");
  // Every truncation is refused with a reason (no crash, no silent success before the cell).
  for (size_t n = 0; n + 4 < good.size(); ++n) {
    INFO(n);
    CHECK_THROWS_AS(read_volume_mesh_from_memory(good.substr(0, n), "meshb", "bad"), FileError);
  }
}

TEST_CASE("MEDIT references as groups in .mesh and .meshb files", "[io][msh][volume]") {
  // Two tetrahedra (references 0 and 3), a triangle (5) and an edge (3) beside them; vertices 0 and
  // 4 carry references 1 and 7, the others 0 (none).
  const std::string text =
      "MeshVersionFormatted 2\nDimension 3\nVertices\n5\n0 0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n1 1 1 7\n"
      "Triangles\n1\n1 2 3 5\nEdges\n1\n4 5 3\nTetrahedra\n2\n1 2 3 4 0\n2 3 4 5 3\nEnd\n";
  // The same in GMF version 2 (and 4: 64-bit integers and positions), written by hand.
  auto binary = [](int version) {
    std::string s;
    auto i32 = [&](std::int32_t x) { put(s, x, false); };
    auto integer = [&](long long x) { version == 4 ? put(s, std::int64_t(x), false) : i32(std::int32_t(x)); };
    auto keyword = [&](int code) {
      i32(code);
      version >= 3 ? put(s, std::int64_t(0), false) : i32(0);
    };
    i32(1), i32(version);
    keyword(3), i32(3);
    keyword(4), integer(5);
    const double X[5][4] = {{0, 0, 0, 1}, {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {1, 1, 1, 7}};
    for (const auto& x : X) {
      for (int c = 0; c < 3; ++c) put(s, x[c], false);
      integer((long long)x[3]);
    }
    keyword(6), integer(1);
    for (int v : {1, 2, 3, 5}) integer(v);
    keyword(5), integer(1);
    for (int v : {4, 5, 3}) integer(v);
    keyword(8), integer(2);
    for (int v : {1, 2, 3, 4, 0, 2, 3, 4, 5, 3}) integer(v);
    i32(54);
    return s;
  };
  test::ScratchDir dir("medit_refs");
  std::ofstream(dir.path("t.mesh")) << text;
  std::ofstream(dir.path("t2.meshb"), std::ios::binary) << binary(2);
  std::ofstream(dir.path("t4.meshb"), std::ios::binary) << binary(4);
  const std::map<std::string, std::vector<int>> vertices{
      {"ref 3", {1, 2, 3, 4}}, {"ref 5", {0, 1, 2}}, {"vertex ref 1", {0}}, {"vertex ref 7", {4}}};
  const std::map<std::string, std::vector<int>> elements{{"ref 3", {1}}};
  const std::map<std::string, long> skipped{{"lines", 1}, {"triangles", 1}};
  for (const char* name : {"t.mesh", "t2.meshb", "t4.meshb"}) {
    INFO(name);
    MeshGroups g;
    const VolumeMesh m = read_volume_mesh_with_groups(dir.path(name), g);
    CHECK(m.n_cells() == 2);
    CHECK(g.vertices == vertices);
    CHECK(g.elements == elements);
    CHECK(g.skipped == skipped);
    const MeshGroups alone = read_mesh_groups(dir.path(name));
    CHECK(alone.vertices == vertices);
    CHECK(alone.elements == elements);
    CHECK(alone.skipped == skipped);
  }
  // meshio's fixtures give every vertex and element the reference 1: the whole mesh.
  MeshGroups g;
  const VolumeMesh tet = read_volume_mesh_with_groups(fixture("tet.mesh"), g);
  CHECK(g.vertices.at("ref 1").size() == size_t(tet.n_vertices()));
  CHECK(g.vertices.at("vertex ref 1").size() == size_t(tet.n_vertices()));
  CHECK(g.elements.at("ref 1").size() == 90);
  CHECK(g.skipped == std::map<std::string, long>{{"lines", 2}, {"triangles", 14}});
  // The skipped elements' indices are checked too, and they must follow Vertices.
  auto expect_medit = [](const std::string& bytes, long line, const std::string& reason) {
    try {
      read_volume_mesh_from_memory(bytes, "mesh", "bad.mesh");
      FAIL("accepted " << reason);
    } catch (const FileError& e) {
      INFO(e.what());
      CHECK(e.line == line);
      CHECK(e.reason.find(reason) != std::string::npos);
    }
  };
  expect_medit(replace(text, "1 2 3 5", "1 2 6 5"), 12, "vertex index 6 out of range [1, 5]");
  expect_medit(replace(text, "4 5 3", "4 0 3"), 15, "vertex index 0 out of range");
  expect_medit(replace(text, "Dimension 3\n", "Dimension 3\nEdges\n0\n"), 3, "Edges before Vertices");
  std::string lying = binary(2);
  const size_t triangle = 8 + 12 + 12 + 5 * 28 + 12;  // the triangle's first vertex index
  lying[triangle] = 9;
  CHECK_THROWS_WITH(read_volume_mesh_from_memory(lying, "meshb", "bad"), Catch::Contains("vertex index 9 out of range"));
}

TEST_CASE("MEDIT writers (.meshb GMF version 2, ASCII .mesh): the same cells and bit-exact positions", "[io][msh][volume]") {
  test::ScratchDir dir("meshb_write");
  std::vector<VolumeMesh> meshes;
  for (const char* kind : {"tet", "hex", "prism", "pyramid"})
    meshes.push_back(read_volume_mesh(fixture(std::string(kind) + "_41_binary.msh")));
  meshes.push_back(hex_grid_volume(3, 2, 2, {0.1, 3}));
  meshes.push_back(pyramid_grid_volume(2, 2, 1, {0.2, 5}));
  for (size_t k = 0; k < 2 * meshes.size(); ++k) {
    const std::string ext = k < meshes.size() ? "meshb" : "mesh";
    INFO(k << " " << ext);
    const VolumeMesh& m = meshes[k % meshes.size()];
    const std::string path = dir.path(fmt::format("m{}.{}", k, ext));
    write_volume_mesh(m, path);
    const std::string bytes = bytes_of(path);
    CHECK(bytes == write_volume_mesh_to_string(m, ext));
    if (ext == "meshb") CHECK(bytes.substr(0, 8) == std::string("\1\0\0\0\2\0\0\0", 8));  // code 1, version 2
    if (ext == "mesh") CHECK(bytes.rfind("MeshVersionFormatted 2\nDimension 3\nVertices\n", 0) == 0);
    const VolumeMesh back = read_volume_mesh(path);
    CHECK(back.positions() == m.positions());
    CHECK(back.volume() == Approx(m.volume()).epsilon(1e-14));  // the cells summed in another order
    // Cells are written by kind (tetrahedra, prisms, hexahedra, pyramids): the same outward faces,
    // in that order.
    REQUIRE(back.n_cells() == m.n_cells());
    std::multiset<std::vector<std::vector<int>>> a, b;
    for (int c = 0; c < m.n_cells(); ++c) a.insert(outward_faces(m, c)), b.insert(outward_faces(back, c));
    CHECK(a == b);
    bool one_kind = true;
    for (int c = 1; c < m.n_cells(); ++c) one_kind = one_kind && cell_shape(m, c) == cell_shape(m, 0);
    if (one_kind) check_same(m, back);
  }
  // polydec convert's path: from .vtk to .meshb and back to the same mesh.
  const std::string vtk = dir.path("p.vtk");
  write_volume_mesh(meshes[3], vtk);
  write_volume_mesh(read_volume_mesh(vtk), dir.path("p.meshb"));
  CHECK(read_volume_mesh(dir.path("p.meshb")).positions() == meshes[3].positions());
  // A general polyhedron has no MEDIT element.
  CHECK_THROWS_WITH(write_volume_mesh(truncated_octahedra_volume(1), dir.path("t.meshb")),
                    Catch::Contains("general polyhedron") && Catch::Contains("t.meshb"));
  CHECK_THROWS_WITH(write_volume_mesh(truncated_octahedra_volume(1), dir.path("t.mesh")),
                    Catch::Contains("general polyhedron") && Catch::Contains("t.mesh"));
}

TEST_CASE("gmsh hostile files: the line or byte offset and the reason", "[io][msh]") {
  const std::string v2 =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n10 0 0 0\n3 1 0 0\n7 0 1 0\n2 0 0 1\n$EndNodes\n"
      "$Elements\n2\n1 15 2 0 1 10\n2 4 2 5 1 10 3 7 2\n$EndElements\n";
  const VolumeMesh m = read_volume_mesh_from_memory(v2, "msh", "ok");
  CHECK(m.n_cells() == 1);
  CHECK(m.volume() == Approx(1.0 / 6));
  expect_error(replace(v2, "10 0 0 0", "3 0 0 0"), true, 7, "node tag 3 is defined twice (first at line 6)");
  expect_error(replace(v2, "1 10 3 7 2", "1 10 3 8 2"), true, 14, "node tag 8, which $Nodes does not define");
  expect_error(replace(v2, "10 0 0 0", "0 0 0 0"), true, 6, "bad node tag 0");
  expect_error(replace(v2, "7 0 1 0", "7 0 nan 0"), true, 8, "non-finite coordinate");
  expect_error(replace(v2, "7 0 1 0", "7 0 x 0"), true, 8, "bad node coordinate 'x'");
  expect_error(replace(v2, "$Nodes\n4", "$Nodes\n400"), true, 5, "node count 400 needs at least");
  expect_error(replace(v2, "2 4 2 5 1 10 3 7 2", "2 11 2 5 1 10 3 7 2 1 1 1 1 1 1"), true, 14,
               "element type 11 (10-node second-order tetrahedron) is not supported");
  expect_error(replace(v2, "2.2 0 8", "2.2 0 4"), true, 2, "data size 4 is not supported");
  expect_error(replace(v2, "2.2 0 8", "4.0 0 8"), true, 2, "version '4.0' is not supported");
  expect_error(v2.substr(0, v2.find("$EndElements")), true, 15, "unexpected end of file");
  expect_error(v2.substr(0, v2.find("3 7 2")), true, 14, "unexpected end of file: expected node tag");
  expect_error(replace(v2, "$Elements\n2", "$Elements\n3"), true, 15, "bad element number '$EndElements'");
  expect_error(v2, false, 0, "holds 3-D elements (1 tetrahedra): read it as a volume mesh");
  expect_error(replace(v2, "2 4 2 5 1 10 3 7 2", "2 1 2 5 1 10 3"), true, 0, "holds no 3-D elements");
  // Unknown sections are skipped.
  CHECK(read_volume_mesh_from_memory(replace(v2, "$Nodes", "$Comments\nhello\n$EndComments\n$Nodes"), "msh", "c")
            .n_cells() == 1);
  expect_error(replace(v2, "$EndNodes", "$EndNode"), true, 10, "expected '$EndNodes'");
  expect_error("", true, 0, "empty file");

  const std::string v4 =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 5 \"the solid\"\n$EndPhysicalNames\n"
      "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 1 5 0\n$EndEntities\n"
      "$Nodes\n1 4 2 10\n3 1 0 4\n10\n3\n7\n2\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n"
      "$Elements\n1 1 1 1\n3 1 4 1\n1 10 3 7 2\n$EndElements\n";
  MeshGroups g;
  {
    test::ScratchDir dir("msh");
    std::ofstream(dir.path("x.dat")) << v4;  // by content: the extension says nothing
    const VolumeMesh m4 = read_volume_mesh_with_groups(dir.path("x.dat"), g);
    CHECK(m4.volume() == Approx(1.0 / 6));
    CHECK(g.vertices == std::map<std::string, std::vector<int>>{{"the solid", {0, 1, 2, 3}}});
    CHECK(g.elements == std::map<std::string, std::vector<int>>{{"the solid", {0}}});
  }
  expect_error(replace(v4, "3 1 0 4\n10", "3 1 0 5\n10"), true, 14, "the node blocks hold more than the 4 nodes");
  expect_error(replace(v4, "1 4 2 10", "2 4 2 10"), true, 23, "bad entity dimension '$EndNodes'");
  expect_error(replace(v4, "1 4 2 10", "1 5 2 10"), true, 22, "the node blocks hold 4 nodes, the header announces 5");
  expect_error(replace(v4, "3 1 4 1\n", "2 1 4 1\n"), true, 26, "entity dimension 2 holds elements of type 4");
  expect_error(replace(v4, "3 1 4 1\n", "3 1 4 100\n"), true, 26, "element count of the block 100 needs");
  expect_error(replace(v4, "1 10 3 7 2", "1 10 3 7 4"), true, 27, "node tag 4, which $Nodes does not define");
  expect_error(replace(v4, "\n7\n", "\n10\n"), true, 21, "node tag 10 is defined twice (first at line 19)");
  expect_error(replace(v4, "$MeshFormat\n4.1", "$MeshFormat\n3"), true, 2, "version '3' is not supported");
  expect_error(replace(v4, "1 0 0 0 1 1 1 1 5 0", "1 0 0 0 1 1 1 1 5"), true, 11, "bad bounding entity count");
}

TEST_CASE("gmsh binary: the endianness marker, truncations, lying counts", "[io][msh]") {
  const std::string good = bytes_of(fixture("tet_41_binary.msh"));
  const size_t marker = good.find("4.1 1 8\n") + 8;
  std::string swapped = good;
  std::reverse(swapped.begin() + long(marker), swapped.begin() + long(marker) + 4);
  expect_error(swapped, true, long(marker), "written on a machine of the other byte order", true);
  // The count of nodes (after the block count, 8 bytes into $Nodes' data) made larger than the file.
  const size_t nodes = good.find("$Nodes\n") + 7 + 8;
  std::string lying = good;
  lying[nodes + 6] = 1;
  expect_error(lying, true, long(nodes), "node count", true);
  // Every truncation inside the data is a FileError with a byte offset within the file.
  const size_t data = good.find("$Nodes\n");
  for (size_t n = data; n < good.find("$EndElements"); n += 7) {
    INFO(n);
    try {
      read_volume_mesh_from_memory(good.substr(0, n), "msh", "cut");
      FAIL("accepted a truncated file");
    } catch (const FileError& e) {
      CHECK(e.byte_offset >= 0);
      CHECK(e.byte_offset <= long(n));
    }
  }
  // 2.2 binary: a coordinate made NaN is refused at its node's byte offset.
  const std::string b2 = bytes_of(fixture("tet_22_binary.msh"));
  const size_t first_node = b2.find("$Nodes\n44\n") + 10;
  std::string nan = b2;
  const double q = std::nan("");
  std::memcpy(&nan[first_node + 4 + 8], &q, 8);
  expect_error(nan, true, long(first_node), "non-finite coordinate", true);
}

TEST_CASE("the .msh writer: surfaces and volumes round trip, other cells refused", "[io][msh]") {
  const VolumeMesh hex = hex_grid_volume(3, 2, 2, {0.2, 4});
  const VolumeMesh tet = tet_grid_volume(2, 2, 3, {0.2, 5});
  const VolumeMesh pyr = pyramid_grid_volume(2, 2, 2, {0.2, 6});
  const VolumeMesh gmsh = read_volume_mesh(fixture("pyramid_41_ascii.msh"));
  const VolumeMesh prisms = read_volume_mesh(fixture("prism_41_binary.msh"));
  for (const VolumeMesh* m : {&hex, &tet, &pyr, &gmsh, &prisms}) {
    const VolumeMesh r = read_volume_mesh_from_memory(write_volume_mesh_to_string(*m, "msh"), "msh", "mem.msh");
    check_same(*m, r);
    CHECK(r.volume() == Approx(m->volume()).epsilon(1e-14));
  }
  CHECK_THROWS_WITH(write_volume_mesh_to_string(truncated_octahedra_volume(2), "msh"),
                    Catch::Contains("cell 0 is a general polyhedron"));
  test::ScratchDir dir("msh_write");
  for (const Mesh& m : {quad_grid(3, 2), triangle_grid(2, 3)}) {
    write_mesh(dir.path("s.msh"), m);
    check_same(m, read_mesh(dir.path("s.msh")));
    CHECK(!is_volume_mesh_path(dir.path("s.msh")));
  }
  CHECK_THROWS_WITH(write_mesh(dir.path("h.msh"), hex_grid(2, 2)), Catch::Contains("vertices: gmsh .msh holds triangles and quadrangles only"));
  write_volume_mesh(prisms, dir.path("p.msh"));
  CHECK(is_volume_mesh_path(dir.path("p.msh")));
  check_same(prisms, read_volume_mesh(dir.path("p.msh")));
}

TEST_CASE("unknown formats: both messages list every format", "[io][msh]") {
  test::ScratchDir dir("msh_unknown");
  std::ofstream(dir.path("x.stl")) << "solid x\n";
  for (int volume = 0; volume < 2; ++volume) {
    try {
      volume ? (void)read_volume_mesh(dir.path("x.stl")) : (void)read_mesh(dir.path("x.stl"));
      FAIL("read an STL file");
    } catch (const FileError& e) {
      INFO(e.what());
      for (const char* f : {"obj", "off", "ply", "msh", "ovm", "vtk", "mesh", "meshb"})
        CHECK(std::regex_search(e.reason, std::regex(std::string("[ (]") + f + "[,;)]")));
    }
  }
}

TEST_CASE("read_mesh_file: one parse, the kind by content, the two readers' meshes, groups and errors", "[io][msh]") {
  // The same message from both routes (file, line or byte offset, reason).
  auto same_error = [](auto&& reference, const std::string& path, MeshFileOptions options = {}) {
    std::string expected;
    try {
      reference();
    } catch (const FileError& e) {
      expected = e.what();
    }
    REQUIRE(!expected.empty());
    CHECK_THROWS_WITH(read_mesh_file(path, options), expected);
  };
  MeshFileOptions with_groups;
  with_groups.groups = true;
  for (const char* encoding : kEncodings) {
    for (const std::string kind : {"tri", "quad", "tet", "hex", "prism", "pyramid"}) {
      const std::string path = fixture(kind + "_" + encoding + ".msh");
      INFO(path);
      const MeshFile f = read_mesh_file(path, with_groups);
      REQUIRE(f.is_volume() == is_volume_mesh_path(path));
      CHECK(f.is_volume() == (kind != "tri" && kind != "quad"));
      MeshGroups g;
      if (f.is_volume()) {
        check_same(read_volume_mesh_with_groups(path, g), *f.volume);
        CHECK(!f.surface);
      } else {
        check_same(read_mesh_with_groups(path, g), *f.surface);
        CHECK(!f.volume);
      }
      CHECK(f.groups.vertices == g.vertices);
      CHECK(f.groups.elements == g.elements);
      CHECK(f.groups.skipped == g.skipped);
      CHECK(read_mesh_file(path).groups.vertices.empty());  // groups only when asked for
    }
  }
  test::ScratchDir dir("mesh_file");
  // .vtu of both kinds, by content; the other extensions by name.
  const VolumeMesh hex = hex_grid_volume(2, 2, 3, {0.2, 3});
  const Mesh quads = quad_grid(3, 2);
  write_volume_mesh(hex, dir.path("v.vtu"));
  write_mesh(dir.path("s.vtu"), quads);
  write_volume_mesh(hex, dir.path("v.vtk"));
  write_mesh(dir.path("s.off"), quads);
  for (const char* name : {"v.vtu", "v.vtk"}) {
    const MeshFile f = read_mesh_file(dir.path(name));
    REQUIRE(f.is_volume());
    check_same(read_volume_mesh(dir.path(name)), *f.volume);
  }
  for (const char* name : {"s.vtu", "s.off"}) {
    const MeshFile f = read_mesh_file(dir.path(name));
    REQUIRE(f.surface);
    check_same(read_mesh(dir.path(name)), *f.surface);
  }
  // Unvalidated surfaces (for --repair) and a surface read as a volume on request.
  MeshFileOptions soup;
  soup.validate_surface = false;
  const MeshFile s = read_mesh_file(fixture("quad_41_binary.msh"), soup);
  REQUIRE(s.soup);
  CHECK(s.soup->n_faces() == 11);
  CHECK(!s.surface);
  MeshFileOptions volume;
  volume.volume = true;
  same_error([&] { read_volume_mesh(dir.path("s.vtu")); }, dir.path("s.vtu"), volume);
  same_error([&] { read_volume_mesh(fixture("tri_41_ascii.msh")); }, fixture("tri_41_ascii.msh"), volume);
  // Broken files: the message of the reader of the kind is_volume_mesh_path chose.
  const std::string tri = bytes_of(fixture("tri_41_ascii.msh"));
  std::ofstream(dir.path("bad_token.msh"), std::ios::binary) << replace(tri, "\n2 0 0\n", "\n2 x 0\n");
  CHECK(!is_volume_mesh_path(dir.path("bad_token.msh")));
  same_error([&] { read_mesh(dir.path("bad_token.msh")); }, dir.path("bad_token.msh"));
  CHECK_THROWS_WITH(read_mesh_file(dir.path("bad_token.msh")),
                    Catch::Matches(".*bad_token\\.msh:[0-9]+: bad node coordinate 'x'.*"));
  std::ofstream(dir.path("not_gmsh.msh")) << "hello\n";
  same_error([&] { read_volume_mesh(dir.path("not_gmsh.msh")); }, dir.path("not_gmsh.msh"));
  same_error([&] { read_volume_mesh(dir.path("missing.msh")); }, dir.path("missing.msh"));
  std::ofstream(dir.path("empty.vtu")) << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\">\n";
  same_error([&] { read_volume_mesh(dir.path("empty.vtu")); }, dir.path("empty.vtu"));
}

}  // namespace test_msh
