// tests/dec/io/test_volume_io_binary.cpp — VTK legacy BINARY unstructured grids (hand-built bytes in
// both cell layouts, float and double points, METADATA blocks, polyhedra), dataset FIELD data
// before POINTS as ParaView writes it (ASCII and BINARY), bit-exact ASCII <-> binary round trips,
// hostile binary files (truncations, lying counts, non-finite points) named by byte offset, the
// writers' int32 count limit, and the coordinate precision volume readers record and the
// refinement uses.
#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/detail/volume_io_common.h"
#include "polydec/dec/surface/virtual_vertex.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/refinement.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_io_binary {
namespace {

// Big-endian bytes of x (VTK's binary byte order), written independently of the library.
template <class T>
std::string be(T x) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &x, sizeof(T));
  if (std::endian::native == std::endian::little)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  return std::string(reinterpret_cast<const char*>(b), sizeof(T));
}

// A unit cube (VTK hexahedron order) with a pyramid of height 1 on its top face: volume 4/3.
const double kPoints[9][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},    {0, 0, 1},
                              {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {0.5, 0.5, 2}};
const std::vector<std::vector<int>> kCells = {{0, 1, 2, 3, 4, 5, 6, 7}, {4, 5, 6, 7, 8}};
const std::vector<int> kTypes = {12, 14};

// The hand-built binary file: points as float or double, classic CELLS (int32) or the version 5.1
// OFFSETS/CONNECTIVITY layout (vtktypeint64), a METADATA block after POINTS as VTK 8+ writes.
std::string hex_pyramid_file(bool float_points, bool v51, bool metadata = true) {
  std::string s = fmt::format(
      "# vtk DataFile Version {}\nhex and pyramid\nBINARY\nDATASET UNSTRUCTURED_GRID\n", v51 ? "5.1" : "4.2");
  s += fmt::format("POINTS 9 {}\n", float_points ? "float" : "double");
  for (const auto& p : kPoints)
    for (double x : p) s += float_points ? be(float(x)) : be(x);
  s += "\n";
  if (metadata) s += "METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 2.3 \n\n";
  if (v51) {
    s += "CELLS 3 13\nOFFSETS vtktypeint64\n";
    s += be<std::int64_t>(0) + be<std::int64_t>(8) + be<std::int64_t>(13);
    s += "\nCONNECTIVITY vtktypeint64\n";
    for (const auto& c : kCells)
      for (int v : c) s += be<std::int64_t>(v);
  } else {
    s += "CELLS 2 15\n";
    for (const auto& c : kCells) {
      s += be<std::int32_t>(int(c.size()));
      for (int v : c) s += be<std::int32_t>(v);
    }
  }
  s += "\nCELL_TYPES 2\n";
  for (int t : kTypes) s += be<std::int32_t>(t);
  s += "\nCELL_DATA 2\nSCALARS id int 1\nLOOKUP_TABLE default\n" + be<std::int32_t>(0) + be<std::int32_t>(1) +
       "\n";
  return s;
}

// The ASCII file of the same hexahedron and pyramid (classic CELLS).
std::string hex_pyramid_ascii() {
  std::string s = "# vtk DataFile Version 3.0\nhp\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 9 double\n";
  for (const auto& p : kPoints) s += fmt::format("{} {} {}\n", p[0], p[1], p[2]);
  return s + "CELLS 2 15\n8 0 1 2 3 4 5 6 7\n5 4 5 6 7 8\nCELL_TYPES 2\n12\n14\n";
}

// Same positions (bit-exact), same cells with the same faces in the same order.
void check_identical(const VolumeMesh& a, const VolumeMesh& b) {
  CHECK(a.positions() == b.positions());
  REQUIRE(a.n_cells() == b.n_cells());
  REQUIRE(a.n_faces() == b.n_faces());
  CHECK(a.face_indices() == b.face_indices());
  int differ = 0;
  for (int c = 0; c < a.n_cells(); ++c) {
    const auto ca = a.cell(c), cb = b.cell(c);
    differ += !std::equal(ca.begin(), ca.end(), cb.begin(), cb.end());
  }
  CHECK(differ == 0);
  CHECK(a.volume() == b.volume());
}

// The FileError of reading `bytes`; fails the test when it reads.
FileError read_error(const std::string& bytes) {
  try {
    read_volume_mesh_from_memory(bytes, "vtk", "bad.vtk");
  } catch (const FileError& e) {
    return e;
  }
  FAIL("accepted a bad file");
  return FileError("", 0, -1, "");
}

// Every truncation of the binary file `good` from after its BINARY line to the end of its cell
// types is a FileError naming a byte offset within the bytes it was given, never a crash.
void check_every_truncation(const std::string& good) {
  const size_t types_end = good.find("\nCELL_DATA");
  for (size_t n = good.find("BINARY") + 7; n < types_end; ++n) {
    INFO("truncated to " << n << " bytes");
    const FileError e = read_error(good.substr(0, n));
    CHECK(e.line == 0);
    CHECK(e.byte_offset >= 0);
    CHECK(e.byte_offset <= long(n));
  }
}

void expect_error(const std::string& bytes, long byte_offset, const std::string& reason) {
  const FileError e = read_error(bytes);
  INFO(e.what());
  CHECK(e.file == "bad.vtk");
  CHECK(e.line == 0);
  CHECK(e.byte_offset == byte_offset);
  CHECK(e.reason.find(reason) != std::string::npos);
  CHECK(std::string(e.what()).find(fmt::format("bad.vtk: byte {}: ", byte_offset)) == 0);
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  REQUIRE(p != std::string::npos);
  return s.replace(p, from.size(), to);
}

// Half a unit of the 6th significant digit of the largest |x| over the rms radius: what a file
// written with "{:.6g}" resolves (DigitCounter's rule, recomputed here from its definition).
double six_digit_noise(const Eigen::MatrixX3d& X) {
  const double largest = X.cwiseAbs().maxCoeff();
  const double absolute = 0.5 * std::pow(10.0, std::floor(std::log10(largest)) + 1 - 6);
  const Eigen::RowVector3d c = X.colwise().mean();
  return absolute / std::sqrt((X.rowwise() - c).rowwise().squaredNorm().mean());
}

// `file` with `block` inserted before its POINTS line.
std::string before_points(const std::string& file, const std::string& block) {
  std::string s = file;
  const auto p = s.find("POINTS ");
  REQUIRE(p != std::string::npos);
  return s.insert(p, block);
}

// A binary string with VTK's length header: 1 byte (top bits 11) below 64 bytes, else 2 bytes
// (top bits 10), big-endian.
std::string binary_string(const std::string& x) {
  REQUIRE(x.size() < (1u << 14));
  if (x.size() < 64) return std::string(1, char(0xC0 | x.size())) + x;
  return be<std::uint16_t>(std::uint16_t(0x8000 | x.size())) + x;
}

// A binary FIELD block shaped like ParaView's (TimeValue first), with the other kinds of
// arrays VTK writes: vtkIdType values whose bytes are newlines and spaces, bits, strings with
// both length headers (one holding the text "POINTS 9 double\n"), a NULL_ARRAY and a METADATA
// block.
std::string binary_field_block() {
  std::string f = "FIELD FieldData 5\nTimeValue 1 1 double\n" + be(0.25) + "\n";
  f += "Ids 2 3 vtkIdType\n";
  for (std::int32_t x : {0x0a0a0a0a, 0x20202020, 0x0a200a20, 7, -1, 0}) f += be(x);
  f += "\nMETADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1 \n\n";
  f += "Flags 1 11 bit\n" + std::string("\x0a\xff", 2) + "\n";
  f += "Names 1 2 string\n" + binary_string("POINTS 9 double\n") + binary_string(std::string(70, '\n')) + "\n";
  f += "NULL_ARRAY\n";
  return f;
}

}  // namespace

TEST_CASE("VTK: dataset FIELD data before POINTS (ParaView exports), ASCII and BINARY", "[volume][io]") {
  // ASCII: the same cells with and without the FIELD block read to identical meshes.
  const std::string ascii = hex_pyramid_ascii();
  const std::string ascii_field =
      "FIELD FieldData 5\nTimeValue 1 1 double\n0.25\nCYCLE 1 1 int\n7\n"
      "METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 7 7 \n\n"
      "Flags 2 3 bit\n0 1 1\n1 0 0\nNULL_ARRAY\nNames 1 2 string\nhex%20and%20pyramid\nPOINTS 5 float 1 2 3\n";
  const VolumeMesh plain = read_volume_mesh_from_memory(ascii, "vtk", "plain.vtk");
  REQUIRE(plain.n_cells() == 2);
  const std::string with_field = before_points(ascii, ascii_field);
  check_identical(read_volume_mesh_from_memory(with_field, "vtk", "field.vtk"), plain);
  // Two FIELD blocks, and an empty one.
  check_identical(
      read_volume_mesh_from_memory(before_points(ascii, ascii_field + "FIELD FieldData 0\n"), "vtk", "f2.vtk"),
      plain);

  // BINARY, both cell layouts: the FIELD block changes nothing.
  for (bool v51 : {false, true}) {
    INFO("version 5.1 " << v51);
    const std::string bin = hex_pyramid_file(false, v51);
    const VolumeMesh m = read_volume_mesh_from_memory(bin, "vtk", "hp.vtk");
    check_identical(read_volume_mesh_from_memory(before_points(bin, binary_field_block()), "vtk", "hpf.vtk"), m);
  }

  // Every truncation of the binary file with FIELD data is a FileError naming a byte offset
  // within the bytes it was given; every truncation of the ASCII one names a line.
  const std::string good = before_points(hex_pyramid_file(false, false, false), binary_field_block());
  check_every_truncation(good);
  for (size_t n = with_field.find("ASCII") + 6; n < with_field.find("CELL_TYPES 2\n12\n") + 16; ++n) {
    INFO("truncated to " << n << " bytes");
    try {
      read_volume_mesh_from_memory(with_field.substr(0, n), "vtk", "t.vtk");
      FAIL("accepted a truncated file");
    } catch (const FileError& e) {
      CHECK(e.line >= 1);
      CHECK(e.byte_offset == -1);
    }
  }

  // Lying counts and unreadable types, named by byte offset.
  const size_t time_at = good.find("TimeValue 1 1 double\n") + 21;
  expect_error(replace(good, "TimeValue 1 1 double", "TimeValue 1 100000 double"), long(time_at + 5),
               "truncated field array 'TimeValue': needs 100000 values of 8 bytes");
  expect_error(replace(good, "TimeValue 1 1 double", "TimeValue 1 1 long"), long(time_at - 7),
               "field array 'TimeValue' has type 'long', whose size in binary files depends on the writing platform");
  expect_error(replace(good, "TimeValue 1 1 double", "TimeValue 1 1 quaternion"), long(time_at - 7),
               "field array 'TimeValue' has the unsupported data type 'quaternion'");
  expect_error(replace(good, "FieldData 5", "FieldData -5"), long(good.find("FieldData 5") + 10),
               "negative field array count -5");
  expect_error(replace(good, "Flags 1 11 bit", "Flags 1 2000000000 bit"), long(good.find("Flags") + 8),
               "field array 'Flags' tuple count 2000000000 is too large");
  // A string whose length header claims more bytes than the file has.
  std::string lying = good;
  const size_t names_at = good.find("Names 1 2 string\n") + 17;
  lying.replace(names_at, 1, std::string(1, char(0x80)));  // a 2-byte header: 0x80 'P' = 80 bytes
  lying = lying.substr(0, names_at + 40);
  expect_error(lying, long(names_at + 2), "truncated field array 'Names': needs 80 bytes, the file ends after 38");
  expect_error(replace(good, "Names 1 2 string", "Names 1 200000 string"), long(names_at + 5),
               "truncated field array 'Names': 200000 strings need at least 200000 bytes");
  // The field arrays end where their payloads say: a count one tuple short leaves the reader in
  // the middle of the payload, which it reports as an error instead of reading on.
  CHECK_THROWS_AS(read_volume_mesh_from_memory(replace(good, "Ids 2 3", "Ids 2 2"), "vtk", "x"), FileError);

  // ASCII errors name the line.
  const auto ascii_error = [&](const std::string& text, long line, const std::string& reason) {
    try {
      read_volume_mesh_from_memory(text, "vtk", "a.vtk");
      FAIL("accepted a bad file (" << reason << ")");
    } catch (const FileError& e) {
      INFO(e.what());
      CHECK(e.line == line);
      CHECK(e.reason.find(reason) != std::string::npos);
      CHECK(std::string(e.what()).find(fmt::format("a.vtk:{}: ", line)) == 0);
    }
  };
  // TimeValue announces 3 values: the second is the next array's name.
  ascii_error(replace(with_field, "TimeValue 1 1", "TimeValue 1 3"), 8, "bad value 'CYCLE' in field array 'TimeValue'");
  ascii_error(replace(with_field, "Names 1 2 string", "Names 1 99 string"), 38,
              "field array 'Names' announces 99 strings, the file ends after 18");
  ascii_error(replace(with_field, "CYCLE 1 1 int", "CYCLE 1 1 variant"), 8,
              "field array 'CYCLE' has the unsupported data type 'variant'");
  ascii_error(replace(with_field, "TimeValue 1 1", "TimeValue 1 100000"), 6,
              "field array 'TimeValue' announces 100000 values but only");
}

TEST_CASE("VTK writers refuse counts beyond the format's int32 instead of writing corrupt files", "[volume][io]") {
  // The check the ASCII and BINARY writers apply to the CELLS list size after each cell, with plain
  // numbers: the largest int32 passes, one more and beyond throw.
  CHECK_NOTHROW(io_detail::check_vtk_int32("big.vtk", "the CELLS list size", 2147483647u));
  CHECK_NOTHROW(io_detail::check_vtk_int32("big.vtk", "the CELLS list size", 0));
  for (std::uint64_t value : {std::uint64_t(2147483648u), std::uint64_t(4294967296u), std::uint64_t(1) << 40}) {
    try {
      io_detail::check_vtk_int32("big.vtk", "the CELLS list size", value);
      FAIL("accepted " << value);
    } catch (const FileError& e) {
      INFO(e.what());
      CHECK(e.file == "big.vtk");
      CHECK(e.reason.find(fmt::format("the CELLS list size is {}", value)) == 0);
      CHECK(e.reason.find("(at most 2147483647)") != std::string::npos);
    }
  }
}

TEST_CASE("VTK BINARY: a hand-built hexahedron and pyramid, both layouts, float and double", "[volume][io]") {
  for (bool float_points : {false, true})
    for (bool v51 : {false, true}) {
      INFO("float " << float_points << ", version 5.1 " << v51);
      const VolumeMesh m = read_volume_mesh_from_memory(hex_pyramid_file(float_points, v51), "vtk", "hp.vtk");
      REQUIRE(m.n_vertices() == 9);
      REQUIRE(m.n_cells() == 2);
      CHECK(m.n_faces() == 10);  // 6 + 5 - the shared square
      for (int v = 0; v < 9; ++v)
        for (int d = 0; d < 3; ++d) CHECK(m.positions()(v, d) == kPoints[v][d]);
      CHECK(m.cell_volume(0) == Approx(1.0).epsilon(1e-15));
      CHECK(m.cell_volume(1) == Approx(1.0 / 3).epsilon(1e-15));
      CHECK(m.is_boundary_vertex(8));
      // float32 points resolve half an ulp of the largest coordinate, doubles only their round-off.
      const double expected = float_points ? 0x1p-24 * 2.0 / m.rms_radius() : 0.0;
      CHECK(m.precision().noise == Approx(expected).epsilon(1e-12));
      // The same mesh as the ASCII file of the same numbers.
      check_identical(read_volume_mesh_from_memory(hex_pyramid_ascii(), "vtk", "hp_ascii.vtk"), m);
    }
  // Without the METADATA block, and through the file-name route (format by the first word).
  CHECK(read_volume_mesh_from_memory(hex_pyramid_file(false, false, false), "vtk", "x").volume() ==
        Approx(4.0 / 3));
}

TEST_CASE("VTK BINARY: polyhedron cells (type 42) with their face streams", "[volume][io]") {
  // A tetrahedron as a polyhedron cell, outward faces: classic int32 and 5.1 int64 connectivity.
  const double P[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<int> stream = {4, 3, 0, 2, 1, 3, 0, 1, 3, 3, 1, 2, 3, 3, 0, 3, 2};
  for (bool v51 : {false, true}) {
    std::string s =
        fmt::format("# vtk DataFile Version {}\np\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n",
                    v51 ? "5.1" : "4.2");
    for (const auto& p : P)
      for (double x : p) s += be(x);
    if (v51) {
      s += fmt::format("\nCELLS 2 {}\nOFFSETS vtktypeint64\n", stream.size());
      s += be<std::int64_t>(0) + be<std::int64_t>(std::int64_t(stream.size()));
      s += "\nCONNECTIVITY vtktypeint64\n";
      for (int x : stream) s += be<std::int64_t>(x);
    } else {
      s += fmt::format("\nCELLS 1 {}\n", stream.size() + 1) + be<std::int32_t>(int(stream.size()));
      for (int x : stream) s += be<std::int32_t>(x);
    }
    s += "\nCELL_TYPES 1\n" + be<std::int32_t>(42) + "\n";
    const VolumeMesh m = read_volume_mesh_from_memory(s, "vtk", "poly.vtk");
    CHECK(m.n_faces() == 4);
    CHECK(m.volume() == Approx(1.0 / 6).epsilon(1e-15));
  }
}

TEST_CASE("VTK BINARY: ASCII <-> binary round trips are bit-exact", "[volume][io]") {
  const VolumeJitter j{0.3, 7};
  const std::vector<VolumeMesh> meshes = {hex_grid_volume(3, 2, 2, j), tet_grid_volume(2, 2, 2, j),
                                          pyramid_grid_volume(2, 1, 1, j), truncated_octahedra_volume(2, j)};
  for (const VolumeMesh& m : meshes) {
    const std::string bin = write_volume_mesh_to_string(m, "vtk", {.binary = true});
    const std::string ascii = write_volume_mesh_to_string(m, "vtk");
    REQUIRE(bin.find("\nBINARY\n") != std::string::npos);
    const VolumeMesh from_bin = read_volume_mesh_from_memory(bin, "vtk", "m_bin.vtk");
    const VolumeMesh from_ascii = read_volume_mesh_from_memory(ascii, "vtk", "m.vtk");
    check_identical(from_ascii, from_bin);
    // Read back, both forms carry exact doubles: the precision of the generated mesh (0).
    CHECK(from_bin.precision().noise == 0.0);
    CHECK(from_ascii.precision().noise == 0.0);
    // The generated doubles themselves, bit for bit, and the same volume (cells in the same order).
    CHECK(from_bin.positions() == m.positions());
    REQUIRE(from_bin.n_cells() == m.n_cells());
    int differ = 0;
    for (int c = 0; c < m.n_cells(); ++c)
      differ += std::abs(from_bin.cell_volume(c) - m.cell_volume(c)) > 1e-14 * std::abs(m.cell_volume(c));
    CHECK(differ == 0);
  }
  // The shared noisy cube (OVM, 6 significant digits) through binary VTK keeps every double.
  POLYDEC_SHARED_MESH(path, "volume/noisycube.ovm");
  const VolumeMesh noisy = read_volume_mesh(path);
  const VolumeMesh back = read_volume_mesh_from_memory(
      write_volume_mesh_to_string(noisy, "vtk", {.binary = true}), "vtk", "noisy.vtk");
  CHECK(back.positions() == noisy.positions());
  CHECK(back.volume() == Approx(noisy.volume()).epsilon(1e-14));
}

TEST_CASE("VTK BINARY: truncated files and lying counts name the byte offset", "[volume][io]") {
  const std::string good = hex_pyramid_file(false, false, false);
  const size_t points_at = good.find("POINTS 9 double\n") + 16;
  const size_t cells_at = good.find("CELLS 2 15\n");
  // Every truncation inside the header, the payloads or CELL_TYPES is a FileError, never a crash.
  check_every_truncation(good);
  expect_error(good.substr(0, points_at + 100), long(points_at),
               "truncated point coordinates: needs 216 bytes, the file ends after 100");
  // Counts larger than the file can hold are refused before anything is allocated.
  expect_error(replace(good, "POINTS 9", "POINTS 1000000000"), long(good.find("POINTS") + 7),
               "point count 1000000000 needs at least 12000000000 bytes");
  expect_error(replace(good, "POINTS 9", "POINTS 20"), long(points_at + 1),
               "truncated point coordinates: needs 480 bytes");
  expect_error(replace(good, "CELLS 2 15", "CELLS 2 400000"), long(cells_at + 8),
               "cell list size 400000 needs at least 1600000 bytes");
  expect_error(replace(good, "CELLS 2 15", "CELLS 2 16"), long(cells_at),
               "the cells hold 15 numbers but CELLS announced 16");
  expect_error(good.substr(0, cells_at + 11 + 50), long(cells_at + 8),
               "cell list size 15 needs at least 60 bytes but only 51 follow");
  expect_error(replace(good, "CELLS 2 15", "CELLS 2 14"), long(cells_at + 11 + 36),
               "cell 1 lists 5 numbers, beyond the announced list size 14");
  expect_error(replace(good, "CELLS 2 15", "CELLS 3 15"), long(cells_at),
               "CELLS announced 3 cells but its list of 15 numbers ends after cell 1");
  expect_error(replace(good, "CELL_TYPES 2", "CELL_TYPES 3"), long(good.find("CELL_TYPES") + 11),
               "CELL_TYPES lists 3 types for 2 cells");
  // A count word inside the binary cell list that lies (cell 0 says 9 points).
  std::string lying = good;
  lying.replace(cells_at + 11, 4, be<std::int32_t>(9));
  expect_error(lying, long(cells_at + 11), "cell 0 of type 12 needs 8 points, it lists 9");
  lying.replace(cells_at + 11, 4, be<std::int32_t>(-3));
  expect_error(lying, long(cells_at + 11), "cell 0 lists -3 numbers");
  // A point index beyond the points, a negative entry, an unknown cell type.
  std::string bad_index = good;
  bad_index.replace(cells_at + 11 + 4, 4, be<std::int32_t>(9));
  expect_error(bad_index, long(cells_at + 11), "point index 9 out of range [0, 9)");
  bad_index.replace(cells_at + 11 + 4, 4, be<std::int32_t>(-1));
  expect_error(bad_index, long(cells_at + 15), "cell entry -1 out of range");
  std::string bad_type = good;
  const size_t types_at = good.find("CELL_TYPES 2\n") + 13;
  bad_type.replace(types_at + 4, 4, be<std::int32_t>(24));
  expect_error(bad_type, long(types_at + 4), "unknown or unsupported cell type 24 of cell 1");
  // Non-finite coordinates are refused where they are, as are types the binary reader lacks.
  std::string nan_point = good;
  nan_point.replace(points_at + 8 * 13, 8, be(std::nan("")));
  expect_error(nan_point, long(points_at + 8 * 13), "point 4 has a non-finite coordinate");
  nan_point.replace(points_at + 8 * 13, 8, be(HUGE_VAL));
  expect_error(nan_point, long(points_at + 8 * 13), "point 4 has a non-finite coordinate (inf)");
  expect_error(replace(good, "POINTS 9 double", "POINTS 9 int"), long(good.find("double")),
               "point data type 'int' is not supported (float, double)");
  expect_error(replace(good, "POINTS 9 double\n", "POINTS 9 double x\n"), long(points_at),
               "expected the end of the line before the point coordinates");
  const std::string v51 = hex_pyramid_file(false, true, false);
  expect_error(replace(v51, "OFFSETS vtktypeint64", "OFFSETS vtktypeuint8"), long(v51.find("vtktypeint64")),
               "offset type 'vtktypeuint8' is not supported in binary files");
  std::string bad_offset = v51;
  const size_t offsets_at = v51.find("OFFSETS vtktypeint64\n") + 21;
  bad_offset.replace(offsets_at + 8, 8, be<std::int64_t>(14));
  expect_error(bad_offset, long(offsets_at + 8), "offset 14 out of order (offsets rise from 0 to 13)");
  std::string huge_entry = v51;
  const size_t conn_at = v51.find("CONNECTIVITY vtktypeint64\n") + 26;
  huge_entry.replace(conn_at, 8, be<std::int64_t>(std::int64_t(1) << 40));
  expect_error(huge_entry, long(conn_at), "connectivity entry 1099511627776 out of range");
  // Validation errors point at the bytes of the cell that holds the culprit: here the pyramid
  // turned inside out, whose base then has the orientation of the hexahedron's top.
  std::string inverted = good;
  const size_t pyramid_at = cells_at + 11 + 36;
  inverted.replace(pyramid_at + 4, 16,
                   be<std::int32_t>(4) + be<std::int32_t>(7) + be<std::int32_t>(6) + be<std::int32_t>(5));
  // (the shared face is named where it was first read: the hexahedron, as in ASCII files)
  expect_error(inverted, long(cells_at + 11), "inconsistent orientation");
}

TEST_CASE("volume readers record the coordinate precision of their files", "[volume][io]") {
  const VolumeMesh g = hex_grid_volume(2, 2, 1, {0.3, 3});
  CHECK(g.precision().noise == 0.0);  // generated: exact doubles
  // The mesh moved and scaled so that its coordinates need all their digits, then written with 6
  // significant digits in every text format.
  const VolumeMesh m =
      g.with_positions(0.7315926535 * g.positions() +
                       Eigen::RowVector3d(0.1234567, 0.2345678, 0.3456789).replicate(g.n_vertices(), 1));
  const auto six = [&](std::string s) {
    // Rewrites every 17-digit coordinate of the file with 6 significant digits.
    std::string out;
    size_t i = 0;
    while (i < s.size()) {
      size_t j = s.find('\n', i);
      if (j == std::string::npos) j = s.size();
      const std::string line = s.substr(i, j - i);
      std::string rewritten;
      size_t k = 0;
      bool changed = false;
      while (k < line.size()) {
        size_t e = line.find(' ', k);
        if (e == std::string::npos) e = line.size();
        const std::string tok = line.substr(k, e - k);
        if (tok.find('.') != std::string::npos) {
          rewritten += fmt::format("{:.6g}", std::stod(tok));
          changed = true;
        } else {
          rewritten += tok;
        }
        if (e < line.size()) rewritten += ' ';
        k = e + 1;
      }
      out += (changed ? rewritten : line) + "\n";
      i = j + 1;
    }
    return out;
  };
  for (const char* format : {"ovm", "vtk", "mesh"}) {
    INFO(format);
    const std::string text = six(write_volume_mesh_to_string(m, format));
    const VolumeMesh r = read_volume_mesh_from_memory(text, format, std::string("six.") + format);
    REQUIRE(r.n_cells() == m.n_cells());
    CHECK((r.positions() - m.positions()).cwiseAbs().maxCoeff() <= 5e-6 * 1.2);
    CHECK(r.precision().noise == Approx(six_digit_noise(r.positions())).epsilon(1e-9));
    // Kept by with_positions and passed to the boundary surface (same positions, same radius).
    CHECK(r.boundary_surface().precision() == r.precision());
    CHECK(r.boundary_surface().coordinate_noise() == Approx(r.coordinate_noise()).epsilon(1e-14));
    CHECK(r.with_positions(r.positions()).precision() == r.precision());
    // The exact doubles of the same mesh: 17 digits carry no noise.
    CHECK(
        read_volume_mesh_from_memory(write_volume_mesh_to_string(m, format), format, "m").precision().noise ==
        0.0);
  }
  // Binary VTK: float points half an ulp, double points none.
  CHECK(read_volume_mesh_from_memory(write_volume_mesh_to_string(m, "vtk", {.binary = true}), "vtk", "b")
            .precision()
            .noise == 0.0);
  CHECK_THROWS_AS(m.with_precision({.noise = 1.5}), InvalidMeshError);
}

TEST_CASE("face-point planarity follows the volume file's coordinate precision", "[volume][io]") {
  // A hexagonal prism (one polyhedron cell) whose top hexagon has one corner raised by one unit
  // of the 6th significant digit: planar to what a 6-digit file resolves, not to double round-off.
  std::vector<Eigen::RowVector3d> P;
  for (double z : {0.0, 1.0})
    for (int k = 0; k < 6; ++k) {
      const double a = 2 * M_PI * k / 6 + 0.3 * (k % 2);  // an irregular hexagon
      P.push_back({std::cos(a) * (1 + 0.2 * (k % 3)), std::sin(a) * (1 + 0.2 * (k % 3)), z});
    }
  std::string text =
      "# vtk DataFile Version 3.0\nprism\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 12 double\n";
  for (int v = 0; v < 12; ++v) {
    const double z = v == 8 ? 1.00001 : P[v].z();
    text += fmt::format("{:.6g} {:.6g} {:.6g}\n", P[v].x(), P[v].y(), z);
  }
  // 8 outward faces: the bottom (reversed), the top, 6 quads (k, k+1, k+7, k+6): 45 numbers.
  const std::string stream =
      "8 6 0 5 4 3 2 1 6 6 7 8 9 10 11 4 0 1 7 6 4 1 2 8 7 4 2 3 9 8 4 3 4 10 9 4 4 5 11 10 4 5 0 6 11";
  text += "CELLS 1 46\n45 " + stream + "\nCELL_TYPES 1\n42\n";
  const VolumeMesh m = read_volume_mesh_from_memory(text, "vtk", "prism.vtk");
  REQUIRE(m.n_cells() == 1);
  REQUIRE(m.precision().noise > 0);
  int top = -1;
  for (int f = 0; f < m.n_faces(); ++f)
    if (m.face_size(f) == 6 && m.position(m.face(f)[0]).z() > 0.5) top = f;
  REQUIRE(top >= 0);
  Eigen::Matrix<double, Eigen::Dynamic, 3> X(6, 3), Xflat(6, 3);
  for (int k = 0; k < 6; ++k) {
    X.row(k) = m.positions().row(m.face(top)[k]);
    Xflat.row(k) = X.row(k);
    Xflat(k, 2) = 1.0;
  }
  const Eigen::VectorXd planar = squared_area_weights(Xflat);
  const auto weights = [&](const VolumeMesh& mesh) {
    const VolumeRefinement R = refine_volume(mesh);
    const auto w = R.weights_of_face(mesh, top);
    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(w.data(), Eigen::Index(w.size())));
  };
  // With the file's precision the raised corner is noise: the weights are those of the flat
  // hexagon (to the size of the raise); with double round-off only, the face counts as non-planar
  // and its least-norm weights jump by much more than the raise.
  const double with_precision = (weights(m) - planar).cwiseAbs().maxCoeff();
  const double roundoff_only = (weights(m.with_precision({})) - planar).cwiseAbs().maxCoeff();
  INFO("with the file's precision " << with_precision << ", round-off only " << roundoff_only);
  CHECK(with_precision < 1e-4);
  CHECK(roundoff_only > 1e-2);
  // The refinement option overrides the mesh's decision as on surfaces.
  VolumeRefinementOptions o;
  o.planarity_tolerance = 1e-3;
  const VolumeRefinement R = refine_volume(m.with_precision({}), o);
  const auto w = R.weights_of_face(m, top);
  CHECK((Eigen::Map<const Eigen::VectorXd>(w.data(), 6) - planar).cwiseAbs().maxCoeff() < 1e-4);
}

}  // namespace test_volume_io_binary
