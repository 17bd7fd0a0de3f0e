// tests/dec/io/test_mesh_io_bad.cpp — the hostile-file corpus tests/data/bad/ (written by
// make_corpus.py there): for every file the exact outcome — which stage rejects it (the
// reader, or Mesh validation reached through read_mesh), the line or byte offset, and the
// reason — or, for the accepted variants, that it reads as the intended square. docs/io.md
// tabulates the same cases.
#include <filesystem>
#include <fstream>
#include <set>

#include "polydec/dec/io/mesh_io.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_io_bad {

namespace {

enum class Stage { Reader, Validation };

struct Case {
  const char* file;  // under tests/data/bad/
  Stage stage;
  long line;           // expected FileError::line
  long byte;           // expected FileError::byte_offset (-1: none); for PLY relative to the data start
  const char* reason;  // substring of FileError::reason
};

const std::string kDir = std::string(POLYDEC_TEST_DATA) + "/bad/";

// Binary offsets in PLY files are given relative to the first byte after "end_header\n".
long ply_data_start(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return long(s.find("end_header\n") + 11);
}

constexpr Stage R = Stage::Reader, V = Stage::Validation;

// Offsets in binary OFF files: 11 header bytes, 12 count bytes, 12 per vertex, 4 + 4 n per face.
const Case kCases[] = {
    // OBJ
    {"obj/empty.obj", R, 0, -1, "no vertices ('v' lines): empty or not an OBJ file"},
    {"obj/header_only.obj", R, 0, -1, "no vertices"},
    {"obj/nan.obj", V, 5, -1, "vertex 4 has a non-finite coordinate"},
    {"obj/inf.obj", V, 2, -1, "vertex 1 has a non-finite coordinate"},
    {"obj/huge_coordinate.obj", V, 1, -1, "vertex 0 has a coordinate of magnitude 1e+308, above the limit 1e+75"},
    {"obj/overflow.obj", R, 2, -1, "bad vertex coordinate '1e999'"},
    {"obj/face_1.obj", V, 6, -1, "face 1 has 1 vertices (at least 3 needed)"},
    {"obj/face_2.obj", V, 6, -1, "face 1 has 2 vertices (at least 3 needed)"},
    {"obj/index_out_of_range.obj", R, 5, -1, "face index 5 out of range (the file has 4 vertices)"},
    {"obj/index_negative_out_of_range.obj", R, 5, -1,
     "relative face index -5 reaches before the first vertex"},
    {"obj/index_zero.obj", R, 5, -1, "face index 0 (OBJ indices start at 1)"},
    {"obj/index_llong_min.obj", R, 5, -1,
     "relative face index -9223372036854775808 reaches before the first"},
    {"obj/index_overflow.obj", R, 5, -1, "bad face entry '99999999999999999999'"},
    {"obj/index_huge.obj", R, 5, -1, "face index 3000000000 out of range"},
    {"obj/repeated_vertex.obj", V, 5, -1, "face 0 repeats vertex 1"},
    {"obj/bad_number.obj", R, 2, -1, "bad vertex coordinate 'zero'"},
    {"obj/short_vertex.obj", R, 2, -1, "vertex needs 3 coordinates, found 2"},
    {"obj/bad_face_entry.obj", R, 5, -1, "bad face entry '1/1/1/1'"},
    {"obj/png.obj", R, 0, 8, "NUL byte: binary data, not an OBJ text file"},
    {"obj/random.obj", R, 0, 24, "NUL byte"},
    // OFF ascii
    {"off/empty.off", R, 0, -1, "empty file (no OFF header)"},
    {"off/header_only.off", R, 1, -1, "header only: no counts"},
    {"off/counts_too_large.off", R, 6, -1, "unexpected end of file after 4 of 8 vertices"},
    {"off/negative_counts.off", R, 2, -1, "negative vertex count -4"},
    {"off/claims_1e12.off", R, 2, -1, "vertex count 1000000000000 is too large"},
    {"off/claims_1e9.off", R, 2, -1,
     "header claims 1000000000 vertices and 1 faces (at least 6000000002 bytes)"},
    {"off/nan.off", V, 5, -1, "vertex 2 has a non-finite coordinate"},
    {"off/inf.off", V, 6, -1, "vertex 3 has a non-finite coordinate"},
    {"off/face_2.off", V, 8, -1, "face 1 has 2 vertices"},
    {"off/index_out_of_range.off", R, 7, -1, "face vertex index 4 out of range [0, 4)"},
    {"off/index_negative.off", R, 7, -1, "face vertex index -1 out of range [0, 4)"},
    {"off/repeated_vertex.off", V, 7, -1, "face 0 repeats vertex 1"},
    {"off/valence_too_large.off", R, 7, -1, "face lists 5 vertices but the line has 4 more numbers"},
    {"off/four_d.off", R, 1, -1, "'4OFF' (non-3D vertices) is not supported"},
    {"off/png.off", R, 1, -1, "expected an OFF header, found '?PNG'"},
    {"off/random.off", R, 1, -1, "expected an OFF header"},
    {"off/bad_number.off", R, 5, -1, "bad vertex coordinate '1,5'"},
    // OFF binary (pmp-library layout)
    {"offb/header_only.off", R, 0, 11, "truncated header counts: needs 4 bytes, the file ends after 0"},
    {"offb/counts_too_large.off", R, 0, 11,
     "header claims 8 vertices and 1 faces (at least 100 bytes) but only 68"},
    {"offb/negative_counts.off", R, 0, 11, "negative counts -4 vertices, 1 faces"},
    {"offb/claims_2e9.off", R, 0, 11, "header claims 2000000000 vertices"},
    {"offb/truncated_face.off", R, 0, 23 + 48, "face 0 claims 4 vertices but only 12 bytes follow"},
    {"offb/nan.off", V, 0, 23 + 24, "vertex 2 has a non-finite coordinate"},
    {"offb/inf.off", V, 0, 23 + 36, "vertex 3 has a non-finite coordinate"},
    {"offb/face_2.off", V, 0, 23 + 48 + 20, "face 1 has 2 vertices"},
    {"offb/index_out_of_range.off", R, 0, 23 + 48 + 16, "face 0 vertex index 7 out of range [0, 4)"},
    {"offb/index_negative.off", R, 0, 23 + 48 + 16, "face 0 vertex index -1 out of range"},
    {"offb/repeated_vertex.off", V, 0, 23 + 48, "face 0 repeats vertex 2"},
    {"offb/negative_valence.off", R, 0, 23 + 48, "face 0 claims -4 vertices"},
    {"offb/big_endian.off", R, 0, 11,
     "(read big-endian they would be 4 and 1: polydec reads OFF BINARY as little"},
    {"offb/png_after_header.off", R, 0, 11, "header claims 1196314761 vertices"},
    // PLY
    {"ply/empty.ply", R, 0, -1, "empty file (no 'ply' header)"},
    {"ply/header_only.ply", R, 4, -1,
     "element 'vertex' claims 4 records (at least 6 bytes each) but only 0 bytes"},
    {"ply/no_end_header.ply", R, 4, -1, "header has no 'end_header'"},
    {"ply/no_format.ply", R, 6, -1, "header has no 'format' line"},
    {"ply/counts_too_large.ply", R, 14, -1, "unexpected end of file in vertex 4 of 8"},
    {"ply/negative_count.ply", R, 4, -1, "negative element count -4"},
    {"ply/claims_1e12.ply", R, 4, -1, "1000000000000 vertices: too many"},
    {"ply/nan.ply", V, 14, -1, "vertex 3 has a non-finite coordinate"},
    {"ply/inf_binary.ply", V, 0, 12, "vertex 1 has a non-finite coordinate"},
    {"ply/face_1.ply", V, 16, -1, "face 1 has 1 vertices"},
    {"ply/index_out_of_range.ply", R, 15, -1, "face 0 vertex index 4 out of range [0, 4)"},
    {"ply/index_negative.ply", R, 0, 48 + 1 + 8, "face 0 vertex index -2 out of range"},
    {"ply/repeated_vertex.ply", V, 15, -1, "face 0 repeats vertex 1"},
    {"ply/truncated_binary.ply", R, 0, 48, "face 0: list of 4 items but only 10 bytes follow"},
    {"ply/truncated_big_endian.ply", R, 4, -1, "element 'vertex' claims 4 records (at least 12 bytes each)"},
    {"ply/truncated_mid_record.ply", R, 0, 26 + 100 + 13,
     "truncated face record: needs 4 bytes, the file ends after 2"},
    {"ply/wrong_endianness.ply", R, 0, 48 + 1 + 4, "face 0 vertex index 16777216 out of range"},
    {"ply/list_count_huge.ply", R, 0, 48, "face 0: list of 4294967295 items but only 16 bytes follow"},
    {"ply/float_indices.ply", R, 8, -1, "vertex_indices must be a list of an integer type"},
    {"ply/unknown_format.ply", R, 2, -1, "unknown PLY format 'binary_middle_endian'"},
    {"ply/no_xyz.ply", R, 4, -1, "vertex element lacks an x, y or z property"},
    {"ply/png.ply", R, 1, -1, "not a PLY file (first line is not 'ply')"},
    {"ply/random.ply", R, 1, -1, "not a PLY file"},
    {"ply/bad_number.ply", R, 13, -1, "bad number '0x3'"},
};

// Matrix Market files: all rejected by the reader.
const Case kMatrixCases[] = {
    {"mtx/claims_1e12.mtx", R, 2, -1, "claims 1000000000000 entries but only 6 bytes follow"},
    {"mtx/out_of_range.mtx", R, 4, -1, "entry (4, 1) outside the 3 x 3 matrix"},
    {"mtx/truncated.mtx", R, 3, -1, "claims 3 entries but only 12 bytes follow"},
    {"mtx/vector_format.mtx", R, 1, -1, "format 'vector' not supported (coordinate or array)"},
    {"mtx/array_two_per_line.mtx", R, 3, -1, "expected one VALUE per line"},
    {"mtx/array_truncated.mtx", R, 2, -1, "claims a 3 x 3 array but only 4 bytes follow"},
    {"mtx/png.mtx", R, 1, -1, "expected '%%MatrixMarket matrix coordinate|array FIELD SYMMETRY'"},
    {"mtx/huge_columns.mtx", R, 2, -1, "claims a 3 x 723221734 matrix in a file of 68 bytes"},  // found by fuzz_mtx
    {"mtx/symmetric_not_square.mtx", R, 2, -1,
     "symmetric matrix must be square, is 4 x 1"},  // found by fuzz_mtx
};

// Read as the unit square (checked in test_io.cpp) instead of rejected.
const char* const kAccepted[] = {
    "obj/bom_crlf_tabs.obj", "off/bom.off",           "off/crlf_tabs_comments.off",    "off/coff.off",
    "off/noff.off",          "ply/bom_crlf_tabs.ply", "ply/mixed_types_big_endian.ply"};

void check_error(const FileError& e, const Case& c, const std::string& path) {
  long byte = c.byte;
  if (byte >= 0 && std::string(c.file).ends_with(".ply")) byte += ply_data_start(path);
  CHECK(e.file == path);
  CHECK(std::string(e.what()).starts_with(path));
  CHECK(e.line == c.line);
  CHECK(e.byte_offset == byte);
  CHECK_THAT(e.reason, Catch::Contains(c.reason));
}

}  // namespace

TEST_CASE("hostile mesh files: each rejected with its line or byte offset and reason", "[io]") {
  for (const Case& c : kCases) {
    const std::string path = kDir + c.file;
    INFO(c.file);
    REQUIRE(std::filesystem::exists(path));
    if (c.stage == Stage::Reader) {
      try {
        read_polygon_soup(path);
        FAIL("accepted by the reader");
      } catch (const FileError& e) {
        check_error(e, c, path);
      }
    } else {
      // The reader passes it on; validation (through read_mesh) rejects it, naming the file position.
      PolygonSoup soup;
      REQUIRE_NOTHROW(soup = read_polygon_soup(path));
      CHECK_THROWS_AS(Mesh(soup), InvalidMeshError);
    }
    try {
      read_mesh(path);
      FAIL("accepted by read_mesh");
    } catch (const FileError& e) {
      check_error(e, c, path);
    }
  }
}

TEST_CASE("hostile Matrix Market files are rejected with line and reason", "[io]") {
  for (const Case& c : kMatrixCases) {
    const std::string path = kDir + c.file;
    INFO(c.file);
    try {
      read_matrix_market(path);
      FAIL("accepted");
    } catch (const FileError& e) {
      check_error(e, c, path);
    }
  }
}

TEST_CASE("the corpus and the expectations list the same files", "[io]") {
  std::set<std::string> listed;
  for (const Case& c : kCases) listed.insert(c.file);
  for (const Case& c : kMatrixCases) listed.insert(c.file);
  for (const char* f : kAccepted) listed.insert(f);
  std::set<std::string> present;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kDir)) {
    const std::string rel = std::filesystem::relative(entry.path(), kDir).generic_string();
    if (entry.is_regular_file() && !rel.ends_with(".py")) present.insert(rel);
  }
  CHECK(present == listed);
  for (const char* f : kAccepted) CHECK_NOTHROW(read_mesh(kDir + f));
}

TEST_CASE("a claimed 10^12 or 10^9 elements fail before any proportional allocation", "[io]") {
  // The claim is refused from the header alone: the same outcome with 10 bytes of data
  // or none, i.e. nothing was read or reserved for the claimed count.
  for (const std::string tail : {"", "0 0 0\n"}) {
    CHECK_THROWS_WITH(read_polygon_soup_from_memory("OFF\n1000000000 0 0\n" + tail, "off", "m.off"),
                      Catch::Contains("m.off:2: header claims 1000000000 vertices"));
    CHECK_THROWS_WITH(read_polygon_soup_from_memory(
                          "ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n" +
                              tail,
                          "ply", "m.ply"),
                      Catch::Contains("m.ply:3: 1000000000000 vertices: too many"));
    CHECK_THROWS_WITH(read_polygon_soup_from_memory(
                          "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
                          "property float y\nproperty float z\nelement junk 100000000000\n"
                          "property double a\nend_header\n" +
                              tail,
                          "ply", "m.ply"),
                      Catch::Contains("m.ply:7: element 'junk' claims 100000000000 records"));
  }
}

}  // namespace test_io_bad
