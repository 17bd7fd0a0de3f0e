// tests/dec/io/test_volume_io.cpp — VTK legacy and MEDIT volume files: round trips through OVM
// (same positions, same cells up to face numbering and order, same volume), VTK's own vertex
// orders for the linear cells, and hostile files rejected with the file:line of the culprit.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_cells.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "tests/support/support.h"
#include "tests/support/volume_meshes.h"

using namespace polydec;

namespace test_volume_io {

namespace {

using test::outward_faces;

// Same positions (bit-exact), the same cells in the same order with the same outward faces.
void check_same(const VolumeMesh& a, const VolumeMesh& b) {
  CHECK(a.positions() == b.positions());
  REQUIRE(a.n_cells() == b.n_cells());
  CHECK(a.n_faces() == b.n_faces());
  int differ = 0;
  for (int c = 0; c < a.n_cells(); ++c) differ += outward_faces(a, c) != outward_faces(b, c);
  CHECK(differ == 0);
  CHECK(b.volume() == Approx(a.volume()).epsilon(1e-14));
}

VolumeMesh round_trip(const VolumeMesh& m, const char* format) {
  return read_volume_mesh_from_memory(write_volume_mesh_to_string(m, format), format,
                                      std::string("mem.") + format);
}

void expect_file_error(const std::string& text, const char* format, long line, const std::string& reason) {
  INFO(text.substr(0, 400));
  try {
    read_volume_mesh_from_memory(text, format, "bad");
    FAIL("accepted a bad file (" << reason << ")");
  } catch (const FileError& e) {
    INFO(e.what());
    CHECK(e.file == "bad");
    CHECK(e.line == line);
    CHECK(e.reason.find(reason) != std::string::npos);
    CHECK(std::string(e.what()).find(line > 0 ? fmt::format("bad:{}: ", line) : std::string("bad: ")) == 0);
  }
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  REQUIRE(p != std::string::npos);
  return s.replace(p, from.size(), to);
}

// A unit cube split into two wedges (VTK order: base triangle normal away from the top).
const std::string kWedges =
    "# vtk DataFile Version 3.0\ntwo wedges\nASCII\nDATASET UNSTRUCTURED_GRID\n"
    "POINTS 8 float\n0 0 0 1 0 0 1 1 0 0 1 0\n0 0 1 1 0 1 1 1 1 0 1 1\n"
    "CELLS 2 14\n6 0 3 1 4 7 5\n6 1 3 2 5 7 6\nCELL_TYPES 2\n13\n13\n"
    "CELL_DATA 2\nSCALARS id int 1\nLOOKUP_TABLE default\n0\n1\n";

}  // namespace

TEST_CASE("VTK and MEDIT round trips of generated meshes", "[volume]") {
  const VolumeMesh hex = hex_grid_volume(3, 2, 2, {0.2, 4});
  const VolumeMesh tet = tet_grid_volume(2, 2, 3, {0.2, 5});
  const VolumeMesh pyr = pyramid_grid_volume(2, 2, 2, {0.2, 6});
  const VolumeMesh tro = truncated_octahedra_volume(2);
  for (const VolumeMesh* m : {&hex, &tet, &pyr, &tro}) {
    check_same(*m, round_trip(*m, "vtk"));
    check_same(*m, round_trip(round_trip(*m, "vtk"), "ovm"));
  }
  check_same(hex, round_trip(hex, "mesh"));
  check_same(tet, round_trip(tet, "mesh"));
  check_same(pyr, round_trip(pyr, "mesh"));
  // The VTK file uses the linear cell types where the face structure allows.
  const std::string v = write_volume_mesh_to_string(pyr, "vtk");
  CHECK(v.find("CELL_TYPES 48\n14\n") != std::string::npos);
  CHECK(write_volume_mesh_to_string(tro, "vtk").find("\n42\n") != std::string::npos);
  // MEDIT has no general polyhedron: the error names the cell and its number of faces.
  try {
    write_volume_mesh_to_string(tro, "mesh");
    FAIL("wrote truncated octahedra to MEDIT");
  } catch (const FileError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find(fmt::format("cell 0 is a general polyhedron with {} faces",
                                                 tro.cell_size(0))) != std::string::npos);
  }
}

TEST_CASE("the polyLaplace cubes go OVM -> VTK -> OVM and -> MEDIT unchanged", "[volume]") {
  for (const char* name : {"cube_hexahedron_2.ovm", "cube_tetrahedron_1.ovm", "cube_pyramids_2.ovm",
                           "cube_truncated_2.ovm", "noisycube.ovm"}) {
    POLYDEC_SHARED_MESH(path, std::string("volume/") + name);
    INFO(name);
    const VolumeMesh m = read_volume_mesh(path);
    const VolumeMesh v = round_trip(m, "vtk");
    check_same(m, v);
    check_same(m, round_trip(v, "ovm"));
    const std::string n(name);
    if (n.find("hexahedron") != std::string::npos || n.find("tetrahedron") != std::string::npos ||
        n.find("noisy") != std::string::npos)
      check_same(m, round_trip(m, "mesh"));
  }
}

TEST_CASE("VTK: the linear cells in VTK's vertex orders", "[volume]") {
  const VolumeMesh w = read_volume_mesh_from_memory(kWedges, "vtk", "wedges.vtk");
  CHECK(w.n_cells() == 2);
  CHECK(w.n_faces() == 9);
  CHECK(w.volume() == Approx(1.0));
  CHECK(w.cell_volume(0) == Approx(0.5));
  CHECK(cell_shape(w, 0) == CellShape::wedge);
  std::array<int, 8> o;
  REQUIRE(cell_shape(w, 1, &o) == CellShape::wedge);
  // The recovered order describes the same wedge (any of its equivalent numberings).
  std::set<int> verts(o.begin(), o.begin() + 6);
  CHECK(verts == std::set<int>{1, 2, 3, 5, 6, 7});
  check_same(w, round_trip(w, "vtk"));
  // A tetrahedron, a pyramid and a hexahedron in VTK's orientation have positive volume.
  const std::string mixed =
      "# vtk DataFile Version 2.0\nmixed\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 13 double\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0.5 -1\n2 0 0\n2 1 0\n2 0 1\n0.5 0.5 2\n"
      "CELLS 4 26\n8 0 1 2 3 4 5 6 7\n5 3 2 1 0 8\n4 1 9 10 5\n5 4 5 6 7 12\nCELL_TYPES 4\n12\n14\n10\n14\n";
  // Cell 1: the pyramid below the cube has its base (3 2 1 0) pointing up, toward the apex 8.
  const VolumeMesh m = read_volume_mesh_from_memory(mixed, "vtk", "mixed.vtk");
  CHECK(m.volume() == Approx(1.0 + 1.0 / 3 + 1.0 / 6 + 1.0 / 3).epsilon(1e-14));
  for (int c = 0; c < m.n_cells(); ++c) CHECK(m.cell_volume(c) > 0);
  CHECK(cell_shape(m, 0) == CellShape::hexahedron);
  CHECK(cell_shape(m, 1) == CellShape::pyramid);
  CHECK(cell_shape(m, 2) == CellShape::tetrahedron);
  CHECK(cell_shape(m, 3) == CellShape::pyramid);
  CHECK(m.cell_volume(0) == Approx(1.0));
  CHECK(m.cell_volume(1) == Approx(1.0 / 3));
  CHECK(m.cell_volume(3) == Approx(1.0 / 3));
  check_same(m, round_trip(m, "vtk"));
}

TEST_CASE("VTK version 5 OFFSETS/CONNECTIVITY layout", "[volume]") {
  const std::string v5 =
      "# vtk DataFile Version 5.1\nv5\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n"
      "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\nCELLS 3 8\nOFFSETS vtktypeint64\n0 4 8\n"
      "CONNECTIVITY vtktypeint64\n0 1 2 3\n1 2 3 4\nCELL_TYPES 2\n10\n10\n";
  const VolumeMesh m = read_volume_mesh_from_memory(v5, "vtk", "v5.vtk");
  CHECK(m.n_cells() == 2);
  CHECK(m.n_faces() == 7);
  for (int c = 0; c < m.n_cells(); ++c) CHECK(m.cell_volume(c) > 0);
  CHECK(m.volume() == Approx(1.0 / 6 + 1.0 / 3));
}

TEST_CASE("VTK: hostile files name the line", "[volume]") {
  const std::string& g = kWedges;
  expect_file_error("", "vtk", 0, "empty file");
  expect_file_error("# vtk DataFile Version 3.0\nt\nBINARI\n", "vtk", 3, "expected 'ASCII' or 'BINARY'");
  expect_file_error(replace(g, "UNSTRUCTURED_GRID", "POLYDATA"), "vtk", 4,
                    "dataset 'POLYDATA' is not supported");
  expect_file_error(replace(g, "POINTS 8", "POINTS 2000000000"), "vtk", 5, "is too large");
  expect_file_error(replace(g, "POINTS 8", "POINTS 900000"), "vtk", 5, "point count 900000 needs at least");
  expect_file_error(replace(g, "POINTS 8", "POINTS -8"), "vtk", 5, "negative point count");
  expect_file_error(replace(g, "1 1 0 0 1 0\n", "1 1 0 0 nan 0\n"), "vtk", 6,
                    "vertex 3 has a non-finite coordinate");
  expect_file_error(replace(g, "1 1 0 0 1 0\n", "1 1 0 0 1e999 0\n"), "vtk", 6,
                    "bad point coordinate '1e999'");
  expect_file_error(replace(g, "CELLS 2 14", "CELLS 2 15"), "vtk", 10,
                    "the cells hold 14 numbers but CELLS announced 15");
  expect_file_error(replace(g, "CELLS 2 14", "CELLS 2 13"), "vtk", 10, "cell 1 lists 6 numbers, beyond");
  expect_file_error(replace(g, "CELLS 2 14", "CELLS 2000000000 2000000000"), "vtk", 8, "is too large");
  expect_file_error(replace(g, "6 1 3 2 5 7 6", "6 1 3 2 5 7 8"), "vtk", 10,
                    "point index 8 out of range [0, 8)");
  expect_file_error(replace(g, "CELL_TYPES 2\n13\n13", "CELL_TYPES 2\n13\n5"), "vtk", 10,
                    "cell 1 of type 5 (triangle) cannot have 6 points");
  expect_file_error(replace(g, "CELL_TYPES 2\n13\n13", "CELL_TYPES 2\n13\n21"), "vtk", 13,
                    "unknown or unsupported cell type 21 of cell 1");
  expect_file_error(replace(g, "CELL_TYPES 2\n13\n13", "CELL_TYPES 2\n13\n99"), "vtk", 13, "cell type 99");
  expect_file_error(replace(g, "CELL_TYPES 2\n", "CELL_TYPES 3\n"), "vtk", 11,
                    "CELL_TYPES lists 3 types for 2 cells");
  expect_file_error(g.substr(0, g.find("CELL_TYPES") + 16), "vtk", 13,
                    "unexpected end of file: expected cell type");
  expect_file_error(g.substr(0, g.find("CELLS") + 14), "vtk", 8, "cell list size 14 needs at least 28 bytes");
  expect_file_error(replace(g, "CELL_TYPES 2\n13\n13", "CELL_TYPES 2\n12\n13"), "vtk", 9,
                    "cell 0 of type 12 needs 8 points, it lists 6");
  // A wedge turned inside out (its two triangles swapped) disagrees with its neighbour.
  expect_file_error(replace(g, "6 1 3 2 5 7 6", "6 5 7 6 1 3 2"), "vtk", 9, "inconsistent orientation");
  // Polyhedron cells: a face list that overruns the cell.
  const std::string poly =
      "# vtk DataFile Version 4.2\np\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0 1 0 0 0 1 0 0 "
      "0 1\n"
      "CELLS 1 18\n17 4 3 0 2 1 3 0 1 3 3 1 2 3 3 0 3 2\nCELL_TYPES 1\n42\n";
  CHECK(read_volume_mesh_from_memory(poly, "vtk", "p.vtk").volume() == Approx(1.0 / 6));
  expect_file_error(replace(poly, "17 4 3 0 2 1", "17 5 3 0 2 1"), "vtk", 8, "face 4 lies beyond");
  expect_file_error(replace(poly, "17 4 3 0 2 1", "17 4 30 0 2 1"), "vtk", 8, "face 0 lists 30 points");
  expect_file_error(replace(poly, "3 0 3 2\n", "3 0 3 7\n"), "vtk", 8, "point index 7 out of range");
  expect_file_error(replace(poly, "17 4 3 0 2 1", "17 4 0 0 2 1"), "vtk", 8,
                    "face 0 has 0 points (at least 3 needed)");
  expect_file_error(replace(poly, "3 0 3 2\n", "3 0 2 3\n"), "vtk", 8, "same direction");
}

TEST_CASE("MEDIT: tetrahedra and hexahedra, hostile files", "[volume]") {
  const std::string g =
      "MeshVersionFormatted 2\n# a comment\nDimension 3\nVertices\n5\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n1 "
      "1 1 7\n"
      "Triangles\n1\n1 2 3 5\nTetrahedra\n2\n1 2 3 4 0\n2 3 4 5 3\nEnd\n";
  const VolumeMesh m = read_volume_mesh_from_memory(g, "mesh", "t.mesh");
  CHECK(m.n_cells() == 2);
  CHECK(m.volume() == Approx(1.0 / 6 + 1.0 / 3));
  for (int c = 0; c < m.n_cells(); ++c) CHECK(m.cell_volume(c) > 0);
  expect_file_error("", "mesh", 0, "empty file");
  expect_file_error(replace(g, "Dimension 3", "Dimension 2"), "mesh", 3, "dimension 2 is not supported");
  expect_file_error(replace(g, "Vertices\n5", "Vertices\n1500000000"), "mesh", 5, "is too large");
  expect_file_error(replace(g, "Vertices\n5", "Vertices\n50000"), "mesh", 5,
                    "Vertices count 50000 needs at least");
  expect_file_error(replace(g, "0 1 0 1\n", "0 nan 0 1\n"), "mesh", 8,
                    "vertex 2 has a non-finite coordinate");
  expect_file_error(replace(g, "2 3 4 5 3", "2 3 4 6 3"), "mesh", 17, "vertex index 6 out of range [1, 5]");
  expect_file_error(replace(g, "2 3 4 5 3", "2 3 4 0 3"), "mesh", 17, "vertex index 0 out of range");
  expect_file_error(replace(g, "Tetrahedra\n2", "Tetrahedra\n3"), "mesh", 15,
                    "Tetrahedra count 3 needs at least 30 bytes");
  expect_file_error(replace(g, "2 3 4 5 3\nEnd", "2 3 4 5 End"), "mesh", 17, "bad element reference 'End'");
  expect_file_error(replace(g, "Tetrahedra\n2", "Tetrahedra\n4000"), "mesh", 15,
                    "Tetrahedra count 4000 needs");
  expect_file_error(replace(g, "Triangles", "Bananas"), "mesh", 11, "unknown MEDIT keyword 'Bananas'");
  expect_file_error(
      g.substr(0, g.find("2 3 4 5 3")) + "# cut here, after a comment long enough for the size check\n",
      "mesh", 18, "unexpected end of file: expected vertex index");
  expect_file_error(replace(g, "2 3 4 5 3", "2 4 3 5 3"), "mesh", 16, "inconsistent orientation");
  expect_file_error(replace(g, "MeshVersionFormatted 2", "MeshVersion 2"), "mesh", 1,
                    "expected 'MeshVersionFormatted'");
}

}  // namespace test_volume_io

namespace test_volume_io {

TEST_CASE("volume files without cells are refused, in every format", "[volume]") {
  const std::string ovm = "OVM ASCII\nVertices\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nEdges\n0\nFaces\n0\nPolyhedra\n0\n";
  const std::string vtk =
      "# vtk DataFile Version 4.2\np\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\n"
      "CELLS 0 0\nCELL_TYPES 0\n";
  const std::string medit = "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 0 1\nEnd\n";
  for (const auto& [bytes, format] : {std::pair{ovm, "ovm"}, std::pair{vtk, "vtk"}, std::pair{medit, "mesh"}}) {
    CAPTURE(format);
    CHECK_THROWS_WITH(read_volume_mesh_from_memory(bytes, format, "empty"),
                      Catch::Contains("empty") && Catch::Contains("no volume cells"));
  }
}

}  // namespace test_volume_io
