// tests/dec/io/test_vtu.cpp — VTK XML unstructured grids: the fixtures of tests/data/vtu (written by
// VTK 9.1 and meshio in every encoding: ASCII, inline base64 with UInt32 and UInt64 headers,
// appended raw and base64, zlib, LZ4 and LZMA blocks, big-endian, Float32 points, Int32 and Int64 ids,
// several pieces) read to the
// same mesh with exact counts, the analytic volume and their point and cell data; bit-exact write ->
// read round trips of volumes (polyhedra included) and surfaces with fields; hostile variants
// refused with FileError; the legacy VTK reader's boundary cells, voxels, byte order and point type.
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "polydec/dec/detail/io_common.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/io/vtu.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/volume_cells.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_vtu {
namespace {

std::string fixture(const std::string& name) { return std::string(POLYDEC_TEST_DATA) + "/vtu/" + name; }

const std::vector<std::string> kVtkVolumes = {"vtk_ascii.vtu",
                                              "vtk_binary_u32_int32.vtu",
                                              "vtk_binary_u64.vtu",
                                              "vtk_appended_raw.vtu",
                                              "vtk_appended_base64.vtu",
                                              "vtk_zlib_appended_raw.vtu",
                                              "vtk_zlib_binary_u64.vtu",
                                              "vtk_bigendian_binary.vtu",
                                              "vtk_bigendian_zlib_appended.vtu",
                                              "vtk_float32_appended_base64.vtu",
                                              "vtk_lz4_appended_raw.vtu",
                                              "vtk_lz4_bigendian_binary.vtu",
                                              "vtk_lzma_binary_u64.vtu",
                                              "vtk_lzma_appended_base64.vtu"};
const std::vector<std::string> kMeshioVolumes = {"meshio_ascii.vtu", "meshio_binary.vtu", "meshio_zlib.vtu"};

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  REQUIRE(p != std::string::npos);
  return s.replace(p, from.size(), to);
}

void expect_error(const std::string& bytes, const std::string& reason) {
  try {
    read_volume_mesh_from_memory(bytes, "vtu", "bad.vtu");
    FAIL("accepted a bad file (" << reason << ")");
  } catch (const FileError& e) {
    INFO(e.what());
    CHECK(e.file == "bad.vtu");
    CHECK(e.reason.find(reason) != std::string::npos);
  }
}

// The area of a planar surface: per face half the norm of its fan's summed cross products.
double area(const Mesh& m) {
  double a = 0;
  for (int f = 0; f < m.n_faces(); ++f) {
    const auto v = m.face(f);
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (size_t i = 1; i + 1 < v.size(); ++i)
      n += (m.position(v[i]) - m.position(v[0])).cross(m.position(v[i + 1]) - m.position(v[0]));
    a += 0.5 * n.norm();
  }
  return a;
}

// Same positions (bit-exact), faces and cells in the same order.
void check_same(const VolumeMesh& a, const VolumeMesh& b) {
  CHECK(a.positions() == b.positions());
  REQUIRE(a.n_cells() == b.n_cells());
  REQUIRE(a.n_faces() == b.n_faces());
  int differ = 0;
  for (int f = 0; f < a.n_faces(); ++f) {
    const auto fa = a.face(f), fb = b.face(f);
    differ += !std::equal(fa.begin(), fa.end(), fb.begin(), fb.end());
  }
  CHECK(differ == 0);
  CHECK(b.volume() == a.volume());
}

}  // namespace

TEST_CASE("VTU: VTK 9.1's files in every encoding read the same mesh, volume and data", "[vtu][io]") {
  const VolumeMesh reference = read_volume_mesh(fixture("vtk_ascii.vtu"));
  for (const std::string& name : kVtkVolumes) {
    INFO(name);
    VolumeReadNotes notes;
    const VolumeMesh m = read_volume_mesh(fixture(name), &notes);
    CHECK(m.n_vertices() == 33);
    CHECK(m.n_cells() == 17);  // hexahedron, voxel, 2 wedges, polyhedron, 6 pyramids, 6 tetrahedra
    CHECK(std::abs(m.volume() - 0.75) <= 1e-15);
    std::map<std::string, int> shapes;
    for (int c = 0; c < m.n_cells(); ++c) ++shapes[cell_shape_name(cell_shape(m, c))];
    CHECK(shapes == std::map<std::string, int>{
                        {"hexahedron", 2}, {"wedge", 2}, {"other", 1}, {"pyramid", 6}, {"tetrahedron", 6}});
    CHECK(notes.skipped_cells ==
          std::map<std::string, long>{
              {"vertex", 1}, {"line", 1}, {"triangle", 2}, {"quad", 1}, {"polygon", 1}});
    check_same(reference, m);
    // The point data: f = x + 2y + 3z, v = (z, -y, x); the cell data: the cell's number.
    const VtuFields fields = read_vtu_fields(fixture(name));
    REQUIRE(fields.point_scalars.count("f"));
    REQUIRE(fields.point_vectors.count("v"));
    REQUIRE(fields.cell_scalars.count("cell_id"));
    const Eigen::MatrixX3d& X = m.positions();
    CHECK((fields.point_scalars.at("f") - (X.col(0) + 2 * X.col(1) + 3 * X.col(2))).cwiseAbs().maxCoeff() ==
          0);
    const Eigen::MatrixX3d& v = fields.point_vectors.at("v");
    CHECK(v.col(0) == X.col(2));
    CHECK(v.col(1) == -X.col(1));
    CHECK(v.col(2) == X.col(0));
    CHECK(fields.cell_scalars.at("cell_id") == Eigen::VectorXd::LinSpaced(23, 0, 22));
  }
}

TEST_CASE("VTU: meshio's ASCII, binary and zlib files read the same mesh", "[vtu][io]") {
  const VolumeMesh reference = read_volume_mesh(fixture("meshio_ascii.vtu"));
  for (const std::string& name : kMeshioVolumes) {
    INFO(name);
    VolumeReadNotes notes;
    const VolumeMesh m = read_volume_mesh(fixture(name), &notes);
    CHECK(m.n_vertices() == 33);
    CHECK(m.n_cells() == 15);  // no voxel, no polyhedron: 2 cubes of 0.125 fewer
    CHECK(std::abs(m.volume() - 0.5) <= 1e-15);
    CHECK(notes.skipped_cells ==
          std::map<std::string, long>{{"vertex", 1}, {"line", 1}, {"triangle", 2}, {"quad", 1}});
    CHECK(m.positions() == reference.positions());
    CHECK(m.n_faces() == reference.n_faces());
    const VtuFields fields = read_vtu_fields(fixture(name));
    REQUIRE(fields.point_vectors.count("v"));
    CHECK(fields.point_vectors.at("v").col(0) == m.positions().col(2));
  }
}

TEST_CASE("VTU: surfaces (triangles, quads, polygons) when the file has no volume cells", "[vtu][io]") {
  for (const char* name : {"vtk_surface_ascii.vtu", "vtk_surface_zlib_binary.vtu", "vtk_surface_lzma_appended_raw.vtu"}) {
    INFO(name);
    const Mesh m = read_mesh(fixture(name));
    CHECK(m.n_vertices() == 8);
    REQUIRE(m.n_faces() == 4);  // the line cell is skipped
    CHECK(m.face_size(0) == 4);
    CHECK(m.face_size(1) == 3);
    CHECK(m.face_size(3) == 5);
    CHECK(std::abs(area(m) - 1.0) <= 1e-15);  // the square [0, 1]^2, tiled
    // A surface is not a volume: the volume reader says so.
    try {
      read_volume_mesh(fixture(name));
      FAIL("a surface read as a volume");
    } catch (const FileError& e) {
      CHECK(e.reason.find("no volume cells") != std::string::npos);
      CHECK(e.reason.find("read as a surface mesh") != std::string::npos);
    }
  }
  const PolygonSoup s = read_polygon_soup(fixture("meshio_surface_zlib.vtu"));
  CHECK(s.n_vertices() == 8);
  CHECK(s.n_faces() == 3);
  // And a volume file is not a surface.
  CHECK_THROWS_WITH(read_mesh(fixture("vtk_ascii.vtu")), Catch::Contains("holds a volume mesh"));
}

TEST_CASE("VTU: the pieces of a partitioned file are concatenated, points, cells and data", "[vtu][io]") {
  const VolumeMesh reference = read_volume_mesh(fixture("vtk_ascii.vtu"));
  for (const char* name : {"vtk_pieces_ascii.vtu", "vtk_pieces_binary_zlib.vtu"}) {
    INFO(name);
    VolumeReadNotes notes;
    const VolumeMesh m = read_volume_mesh(fixture(name), &notes);
    // Piece 1 holds points 0-24 and the row of cubes, piece 2 points 25-32 and the tetrahedra: the
    // second piece's point ids are offset by 25, so the mesh is the one-piece file's.
    check_same(reference, m);
    CHECK(std::abs(m.volume() - 0.75) <= 1e-15);
    CHECK(notes.skipped_cells ==
          std::map<std::string, long>{
              {"vertex", 1}, {"line", 1}, {"triangle", 2}, {"quad", 1}, {"polygon", 1}});
    const VtuFields fields = read_vtu_fields(fixture(name));
    const Eigen::MatrixX3d& X = m.positions();
    CHECK(fields.point_scalars.at("f") == X.col(0) + 2 * X.col(1) + 3 * X.col(2));
    CHECK(fields.point_vectors.at("v").col(0) == X.col(2));
    // Each piece numbers its own cells: 15 in the first, 8 in the second.
    Eigen::VectorXd ids(23);
    ids << Eigen::VectorXd::LinSpaced(15, 0, 14), Eigen::VectorXd::LinSpaced(8, 0, 7);
    CHECK(fields.cell_scalars.at("cell_id") == ids);
  }
  // Surfaces: the square and a copy moved by 3 in x, 8 points each.
  const Mesh one = read_mesh(fixture("vtk_surface_ascii.vtu"));
  const Mesh two = read_mesh(fixture("vtk_surface_pieces_binary.vtu"));
  REQUIRE(two.n_vertices() == 16);
  CHECK(two.n_faces() == 8);
  CHECK(two.positions().topRows(8) == one.positions());
  CHECK(two.positions().bottomRows(8).col(0) == (one.positions().col(0).array() + 3.0).matrix());
  CHECK(std::abs(area(two) - 2.0) <= 1e-15);
  CHECK(read_vtu_fields(fixture("vtk_surface_pieces_binary.vtu")).point_scalars.at("f").size() == 16);

  const std::string ascii = io_detail::slurp(fixture("vtk_pieces_ascii.vtu"));
  // An array missing from one piece is dropped; the mesh reads.
  {
    const size_t second = ascii.find("<Piece", ascii.find("</Piece>"));
    const std::string bad = replace(ascii.substr(0, second), "Name=\"f\"", "Name=\"g\"") + ascii.substr(second);
    const VtuFields fields = read_vtu_fields_from_memory(bad, "p.vtu");
    CHECK(fields.point_scalars.count("f") == 0);
    CHECK(fields.point_scalars.count("g") == 0);
    CHECK(fields.point_vectors.count("v") == 1);
  }
  // A cell of the second piece naming a point beyond its own 8 (ids are per piece).
  {
    const size_t second = ascii.find("<Piece", ascii.find("</Piece>"));
    const size_t c = ascii.find("Name=\"connectivity\"", second);
    const size_t v = ascii.find_first_of("0123456789", ascii.find('>', c));
    std::string bad = ascii;
    bad.replace(v, 1, "8");
    expect_error(bad, "cell 15: point index 8 out of range [0, 8)");
  }
  expect_error(replace(ascii, "NumberOfPoints=\"8\"", "NumberOfPoints=\"9\""), "");
  {
    std::string none = ascii;
    none.erase(none.find("    <Piece"), none.rfind("</Piece>") + 9 - none.find("    <Piece"));
    expect_error(none, "no Piece element");
  }
}

TEST_CASE("VTU: VTK 9.4's polyhedron arrays read the same polyhedron", "[vtu][io]") {
  const VolumeMesh reference = read_volume_mesh(fixture("vtk_ascii.vtu"));
  for (const char* name : {"vtk94_polyhedra_ascii.vtu", "vtk94_polyhedra_binary.vtu"}) {
    INFO(name);
    const VolumeMesh m = read_volume_mesh(fixture(name));
    check_same(reference, m);
    CHECK(cell_shape(m, 4) == CellShape::other);  // the 7-faced polyhedron
    CHECK(m.cell_size(4) == 7);
  }
  const std::string ascii = io_detail::slurp(fixture("vtk94_polyhedra_ascii.vtu"));
  // Its seven faces end at 4 7 10 14 18 22 26 in face_connectivity; the cell lists faces 0-6.
  expect_error(replace(ascii, "0 1 2 3 4 5 6", "0 1 2 3 4 5 7"), "polyhedron cell 4: face 7 out of range [0, 7)");
  expect_error(replace(ascii, "4 7 10 14 18 22 26", "4 7 10 9 18 22 26"), "face_offset 9 of face 3 is below");
  expect_error(replace(ascii, "4 7 10 14 18 22 26", "4 7 10 14 18 22 27"), "face_connectivity holds 26 values, 27");
  expect_error(replace(ascii, "3 9 10 4 15", "3 9 10 4 99"), "polyhedron cell 4: point index 99 out of range [0, 33)");
  expect_error(replace(ascii, "0 0 0 0 7 7 7", "0 0 0 0 7 6 7"), "polyhedron_offset 6 of cell 5 is below");
  expect_error(replace(ascii, "Name=\"face_offsets\"", "Name=\"face_offset\""), "face_connectivity, face_offsets");
  // Faces shared by more than two polyhedra cannot bound a volume mesh.
  {
    std::string three = replace(ascii, "0 0 0 0 7 7 7 7 7 7 7 7 7 7 7 7 7 7 7 7 7 7 7",
                                "0 0 0 0 7 14 21 21 21 21 21 21 21 21 21 21 21 21 21 21 21 21 21");
    three = replace(three, ">\n          0 1 2 3 4 5 6\n", ">\n          0 1 2 3 4 5 6 0 1 2 3 4 5 6 0 1 2 3 4 5 6\n");
    three = replace(three, "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\" RangeMin=\"1\" RangeMax=\"42\">\n          12 11 13 13 42 14",
                    "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\" RangeMin=\"1\" RangeMax=\"42\">\n          12 11 13 13 42 42");
    three = replace(three, "14 14 14 14 14 10", "42 14 14 14 14 10");
    expect_error(three, "face 0 bounds more than two polyhedra");
  }
}

TEST_CASE("VTU: written volumes and surfaces read back bit-exactly with their fields", "[vtu][io]") {
  const VolumeMesh hex = hex_grid_volume(3, 2, 2, {0.2, 4});
  const VolumeMesh tro = truncated_octahedra_volume(2);  // polyhedra: type 42
  const VolumeMesh pyr = pyramid_grid_volume(2, 2, 2, {0.2, 6});
  for (const VolumeMesh* m : {&hex, &tro, &pyr}) {
    VtuFields fields;
    fields.point_scalars["u"] = m->positions().col(0).array().sin().matrix() / 3.0;
    fields.point_vectors["grad u"] = m->positions() * (1.0 / 7.0);
    fields.cell_scalars["volume"] = Eigen::VectorXd::LinSpaced(m->n_cells(), 0.1, 1.0 / 3.0);
    for (bool binary : {true, false}) {
      INFO("binary " << binary);
      const std::string bytes = write_vtu_to_string(*m, fields, binary);
      check_same(*m, read_volume_mesh_from_memory(bytes, "vtu", "mem.vtu"));
      const VtuFields back = read_vtu_fields_from_memory(bytes, "mem.vtu");
      CHECK(back.point_scalars.at("u") == fields.point_scalars.at("u"));
      CHECK(back.point_vectors.at("grad u") == fields.point_vectors.at("grad u"));
      CHECK(back.cell_scalars.at("volume") == fields.cell_scalars.at("volume"));
    }
  }
  // The truncated octahedra are written as polyhedra, the hexahedra as hexahedra.
  CHECK(write_vtu_to_string(tro, {}, false).find("faceoffsets") != std::string::npos);
  CHECK(write_vtu_to_string(hex, {}, false).find("faceoffsets") == std::string::npos);

  const Mesh quads = quad_grid(3, 2);
  test::ScratchDir dir("vtu");
  const Eigen::VectorXd u = quads.positions().col(0) * 0.3;
  write_mesh(dir.path("s.vtu"), quads, {{"u", u}});
  const Mesh back = read_mesh(dir.path("s.vtu"));
  CHECK(back.positions() == quads.positions());
  CHECK(back.n_faces() == quads.n_faces());
  CHECK(read_vtu_fields(dir.path("s.vtu")).point_scalars.at("u") == u);
  VtuFields vectors;
  vectors.point_vectors["n"] = quads.positions().rowwise().reverse();
  write_vtu(dir.path("v.vtu"), quads, vectors);
  CHECK(read_vtu_fields(dir.path("v.vtu")).point_vectors.at("n") == vectors.point_vectors.at("n"));
  // Names are escaped; sizes are checked.
  vectors.point_vectors["a<b & \"c\""] = vectors.point_vectors["n"];
  CHECK(read_vtu_fields_from_memory(write_vtu_to_string(quads, vectors), "m")
            .point_vectors.count("a<b & \"c\"") == 1);
  VtuFields wrong;
  wrong.point_scalars["w"] = Eigen::VectorXd::Zero(3);
  CHECK_THROWS_AS(write_vtu_to_string(quads, wrong), std::invalid_argument);
}

TEST_CASE("VTU: the compressed writer (appended zlib blocks) round-trips bit-exactly", "[vtu][io]") {
  // 13 x 11 x 11 points: 37752 bytes of coordinates, two blocks of 32 KiB.
  const VolumeMesh hex = hex_grid_volume(12, 10, 10, {0.2, 4});
  const VolumeMesh tro = truncated_octahedra_volume(2);
  for (const VolumeMesh* m : {&hex, &tro}) {
    VtuFields fields;
    fields.point_scalars["u"] = m->positions().col(1).array().cos().matrix();
    fields.point_vectors["x"] = m->positions() * (1.0 / 3.0);
    fields.cell_scalars["c"] = Eigen::VectorXd::LinSpaced(m->n_cells(), -1.0, 1.0 / 7.0);
    const std::string bytes = write_vtu_to_string(*m, fields, false, true);
    CHECK(bytes.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos);
    CHECK(bytes.find("<AppendedData encoding=\"raw\">") != std::string::npos);
    CHECK(bytes.find("format=\"binary\"") == std::string::npos);
    CHECK(bytes.find("format=\"ascii\"") == std::string::npos);
    CHECK(bytes.size() < write_vtu_to_string(*m, fields, true).size());
    check_same(*m, read_volume_mesh_from_memory(bytes, "vtu", "z.vtu"));
    const VtuFields back = read_vtu_fields_from_memory(bytes, "z.vtu");
    CHECK(back.point_scalars.at("u") == fields.point_scalars.at("u"));
    CHECK(back.point_vectors.at("x") == fields.point_vectors.at("x"));
    CHECK(back.cell_scalars.at("c") == fields.cell_scalars.at("c"));
  }
  // The points' header: 2 blocks of 32768 bytes, the last one 37752 - 32768 = 4984 bytes.
  {
    const std::string bytes = write_vtu_to_string(hex, {}, true, true);
    const size_t data = bytes.find('_', bytes.find("<AppendedData")) + 1;
    const size_t offset = std::stoul(bytes.substr(bytes.find("offset=\"", bytes.find("Name=\"Points\"")) + 8, 12));
    std::uint64_t header[3];
    std::memcpy(header, bytes.data() + data + offset, sizeof header);
    CHECK(header[0] == 2);
    CHECK(header[1] == 32768);
    CHECK(header[2] == 4984);
  }
  const Mesh quads = quad_grid(30, 20);
  test::ScratchDir dir("vtu_zlib");
  VtuFields fields;
  fields.point_scalars["h"] = quads.positions().col(0) * 0.7;
  write_vtu(dir.path("s.vtu"), quads, fields, true, true);
  const Mesh back = read_mesh(dir.path("s.vtu"));
  CHECK(back.positions() == quads.positions());
  CHECK(back.n_faces() == quads.n_faces());
  CHECK(read_vtu_fields(dir.path("s.vtu")).point_scalars.at("h") == fields.point_scalars.at("h"));
}

TEST_CASE("OBJ and OFF refuse vertex scalars instead of dropping them", "[vtu][io]") {
  const Mesh m = quad_grid(2, 2);
  test::ScratchDir dir("vtu_scalars");
  const VertexScalars s{{"u", Eigen::VectorXd::Zero(m.n_vertices())}};
  for (const char* ext : {"obj", "off"}) {
    const std::string path = dir.path(std::string("m.") + ext);
    CHECK_THROWS_WITH(write_mesh(path, m, s),
                      Catch::Contains("cannot hold the vertex scalars") && Catch::Contains(".ply or .vtu"));
    CHECK_FALSE(std::filesystem::exists(path));
    CHECK_NOTHROW(write_mesh(path, m));
  }
}

TEST_CASE("VTU: hostile files are refused with FileError", "[vtu][io]") {
  const std::string raw = io_detail::slurp(fixture("vtk_appended_raw.vtu"));
  const std::string b64 = io_detail::slurp(fixture("vtk_binary_u64.vtu"));
  const std::string zlib = io_detail::slurp(fixture("vtk_zlib_appended_raw.vtu"));
  const std::string ascii = io_detail::slurp(fixture("vtk_ascii.vtu"));
  // Truncated anywhere after the XML: appended data that ends early.
  for (size_t keep : {raw.rfind("</AppendedData>") - 6, raw.size() - 100})
    expect_error(raw.substr(0, keep), "truncated");
  expect_error(raw.substr(0, raw.find("_", raw.find("<AppendedData")) + 3), "out-of-range appended offset");
  expect_error(raw.substr(0, raw.find("<AppendedData")), "not well-formed XML");
  // Inline base64: cut short, or a character that is not base64.
  const size_t points = b64.find("Name=\"Points\"");
  const size_t data = b64.find('>', points) + 20;
  {
    std::string bad = b64;
    bad[data] = '*';
    expect_error(bad, "invalid base64 character");
  }
  {
    std::string cut = b64;
    const size_t end = cut.find("</DataArray>", data);
    cut.erase(data, end - data - 20);
    expect_error(cut, "");
  }
  // zlib: a corrupted stream, a block size that cannot be inflated from its bytes.
  {
    // The points' 792 bytes in 13 blocks: a header of 16 UInt32, then the compressed blocks.
    std::string bad = zlib;
    const size_t offset = bad.find("offset=\"", bad.find("Name=\"Points\"")) + 8;
    const size_t at = bad.find('_', bad.find("<AppendedData")) + 1 + std::stoul(bad.substr(offset, 12));
    for (size_t k = 70; k < 80; ++k) bad[at + k] = char(bad[at + k] ^ 0x5a);
    expect_error(bad, "compressed block");
    // Point data is skipped unread: a corrupted scalar field does not stop the mesh.
    std::string field = zlib;
    const size_t f = field.find('_', field.find("<AppendedData")) + 1;
    for (size_t k = 70; k < 80; ++k) field[f + k] = char(field[f + k] ^ 0x5a);
    CHECK(read_volume_mesh_from_memory(field, "vtu", "f.vtu").n_cells() == 17);
    CHECK_THROWS_AS(read_vtu_fields_from_memory(field, "f.vtu"), FileError);
  }
  // Offsets out of range, sizes that disagree with the headers, counts beyond the file.
  expect_error(replace(raw, "offset=\"1160\"", "offset=\"99999999\""), "out-of-range appended offset");
  expect_error(replace(raw, "NumberOfPoints=\"33\"", "NumberOfPoints=\"34\""), "the header announces");
  expect_error(replace(raw, "NumberOfPoints=\"33\"", "NumberOfPoints=\"1000000000\""), "");
  expect_error(replace(zlib, "NumberOfPoints=\"33\"", "NumberOfPoints=\"1000000000\""), "");
  expect_error(replace(ascii, "NumberOfPoints=\"33\"", "NumberOfPoints=\"32\""), "holds more than");
  expect_error(replace(ascii, "NumberOfPoints=\"33\"", "NumberOfPoints=\"-1\""), "NumberOfPoints as a count");
  expect_error(replace(ascii, "NumberOfCells=\"23\"", "NumberOfCells=\"24\""), "");
  expect_error(replace(ascii, "type=\"UnstructuredGrid\"", "type=\"PolyData\""), "'PolyData' is not read");
  expect_error(replace(ascii, "byte_order=\"LittleEndian\"", "byte_order=\"Middle\""), "byte_order");
  expect_error(replace(raw, "header_type=\"UInt32\"", "header_type=\"UInt32\" compressor=\"vtkBZ2DataCompressor\""),
               "compressor 'vtkBZ2DataCompressor' is not supported");
  expect_error(replace(ascii, "<VTKFile", "<!DOCTYPE x [<!ENTITY a \"aaaa\">]>\n<VTKFile"), "DOCTYPE");
  // A connectivity entry beyond the points.
  {
    const size_t c = ascii.find("Name=\"connectivity\"");
    const size_t v = ascii.find_first_of("0123456789", ascii.find('>', c));
    std::string bad = ascii;
    bad.replace(v, 1, "99");
    expect_error(bad, "out of range");
  }
}

TEST_CASE("VTU: LZ4 and LZMA blocks, corrupted or lying, are refused with FileError", "[vtu][io]") {
  for (const char* name : {"vtk_lz4_appended_raw.vtu", "vtk_lzma_appended_base64.vtu"}) {
    INFO(name);
    const std::string good = io_detail::slurp(fixture(name));
    const bool lz4 = std::string(name).find("lz4") != std::string::npos;
    // The points' compressed blocks, damaged after their header (base64: whole groups of 4).
    std::string bad = good;
    const size_t offset = bad.find("offset=\"", bad.find("Name=\"Points\"")) + 8;
    const size_t at = bad.find('_', bad.find("<AppendedData")) + 1 + std::stoul(bad.substr(offset, 12));
    for (size_t k = 120; k < 160; ++k) bad[at + k] = lz4 ? char(bad[at + k] ^ 0x5a) : "QUJD"[k % 4];
    expect_error(bad, lz4 ? "is not a LZ4 stream" : "is not a LZMA stream");
    // A compressor other than the one that wrote the blocks.
    expect_error(replace(good, lz4 ? "vtkLZ4DataCompressor" : "vtkLZMADataCompressor",
                         lz4 ? "vtkLZMADataCompressor" : "vtkLZ4DataCompressor"),
                 "compressed block 0");
    // Truncated, and a count the blocks cannot hold.
    expect_error(good.substr(0, good.size() - 200), "");
    expect_error(replace(good, "NumberOfPoints=\"33\"", "NumberOfPoints=\"1000000000\""), "");
  }
}

TEST_CASE("VTU: dispatch by extension and by content and messages that list every format", "[vtu][io]") {
  test::ScratchDir dir("vtu_dispatch");
  const std::string path = dir.path("grid.dat");
  std::filesystem::copy_file(fixture("vtk_zlib_binary_u64.vtu"), path);
  CHECK(read_volume_mesh(path).n_cells() == 17);
  CHECK(is_volume_mesh_path("x.VTU"));
  CHECK_THROWS_WITH(read_volume_mesh(dir.path("none.xyz")), Catch::Contains("cannot open"));
  {
    std::ofstream(dir.path("t.xyz")) << "hello\n";
    CHECK_THROWS_WITH(read_volume_mesh(dir.path("t.xyz")),
                      Catch::Contains("ovm, vtk, vtu, mesh, meshb, msh") && Catch::Contains("obj, off, ply, msh, vtu"));
    CHECK_THROWS_WITH(read_mesh(dir.path("t.xyz")),
                      Catch::Contains("obj, off, ply, msh, vtu") && Catch::Contains("ovm, vtk, vtu, mesh, meshb, msh"));
  }
  // write_volume_mesh and the point-data writer take .vtu.
  const VolumeMesh m = hex_grid_volume(2, 2, 2);
  write_volume_mesh(m, dir.path("m.vtu"));
  check_same(m, read_volume_mesh(dir.path("m.vtu")));
  const Eigen::VectorXd d = m.positions().col(2);
  write_volume_vtk_with_point_data(m, dir.path("d.vtu"), {{"distance", d}});
  CHECK(read_vtu_fields(dir.path("d.vtu")).point_scalars.at("distance") == d);
}

TEST_CASE("VTK legacy: boundary cells beside volume cells are skipped and counted and voxels read",
          "[vtu][io]") {
  // Two unit cubes along x: a hexahedron and a voxel; a vertex, a line, a triangle, a quad and a
  // polygon on the boundary.
  const std::string cells =
      "POINTS 12 double\n0 0 0 1 0 0 2 0 0 0 1 0 1 1 0 2 1 0\n0 0 1 1 0 1 2 0 1 0 1 1 1 1 1 2 1 1\n"
      "CELLS 7 37\n8 0 1 4 3 6 7 10 9\n8 1 2 4 5 7 8 10 11\n1 0\n2 0 1\n3 0 1 4\n4 0 3 4 1\n4 2 5 11 8\n"
      "CELL_TYPES 7\n12\n11\n1\n3\n5\n9\n7\n";
  const std::string file =
      "# vtk DataFile Version 3.0\ngmsh-like\nASCII\nDATASET UNSTRUCTURED_GRID\n" + cells;
  test::ScratchDir dir("vtk_legacy");
  const std::string path = dir.path("m.vtk");
  std::ofstream(path) << file;
  VolumeReadNotes notes;
  const VolumeMesh m = read_volume_mesh(path, &notes);
  CHECK(m.n_cells() == 2);
  CHECK(m.n_faces() == 11);  // the cubes share a face
  CHECK(std::abs(m.volume() - 2.0) <= 1e-15);
  CHECK(cell_shape(m, 1) == CellShape::hexahedron);
  CHECK(notes.skipped_cells == std::map<std::string, long>{
                                   {"vertex", 1}, {"line", 1}, {"triangle", 1}, {"quad", 1}, {"polygon", 1}});
  // Only boundary cells: no volume, said so.
  const std::string only =
      "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 float\n0 0 0 1 "
      "0 0 0 1 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n";
  CHECK_THROWS_WITH(read_volume_mesh_from_memory(only, "vtk", "t.vtk"),
                    Catch::Contains("no volume cells") && Catch::Contains("1 triangle"));
  // POINTS needs float or double.
  CHECK_THROWS_WITH(
      read_volume_mesh_from_memory(
          "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 27 bogus\n" + std::string(200, '0'), "vtk", "t"),
      Catch::Contains("point data type 'bogus' is not supported"));
}

TEST_CASE("VTK legacy BINARY: little-endian data (the format is big-endian) is refused as such",
          "[vtu][io]") {
  const VolumeMesh m = hex_grid_volume(2, 2, 2, {0.2, 3});
  WriteOptions binary;
  binary.binary = true;
  const std::string good = write_volume_mesh_to_string(m, "vtk", binary);
  CHECK(read_volume_mesh_from_memory(good, "vtk", "good").positions() == m.positions());
  // Swap every coordinate's bytes, as a little-endian writer would have written them.
  std::string little = good;
  const size_t at = good.find("double\n") + 7;
  for (int k = 0; k < 3 * m.n_vertices(); ++k)
    std::reverse(little.begin() + long(at) + 8 * k, little.begin() + long(at) + 8 * k + 8);
  CHECK_THROWS_WITH(read_volume_mesh_from_memory(little, "vtk", "le"),
                    Catch::Contains("little-endian") && Catch::Contains("big-endian"));
}

}  // namespace test_vtu
