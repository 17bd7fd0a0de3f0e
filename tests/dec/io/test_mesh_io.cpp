// tests/dec/io/test_mesh_io.cpp — mesh and matrix readers/writers: round trips in every format
// (positions bit-exact, faces identical), the paper's meshes (including pmp-library's binary
// OFF), accepted format variants, PLY scalar properties, Matrix Market, error messages.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <thread>

#if defined(__unix__)
#include <sys/stat.h>
#endif

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "polydec/dec/io/mesh_io.h"
#include "tests/support/support.h"

using namespace polydec;

namespace fs = std::filesystem;

namespace test_io {

namespace {

// The process's scratch folder polydec_test_io_PID, removed when the test process exits.
const fs::path& temp_dir() {
  static const test::ScratchDir d("test_io");
  return d.dir;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A small mesh of a triangle, a quad, a pentagon and a non-convex hexagon with coordinates
// that are not short decimals (1/3, 1e-7, ...), so that printing with fewer than 17 digits
// would not round-trip.
Mesh mixed_mesh() {
  PolygonSoup s;
  s.positions.resize(10, 3);
  s.positions << 0, 0, 0, 1.0 / 3, 0, 1e-7, 1, 0.1, 0, 1, 1, 0.2, 0, 1, 0, -0.7, 0.5, 1e-300, 2.0 / 3, 2,
      -0.1, -1, 2, 0, 1.6, 1.9, 0.3, 0.4, 2.5, 3.14159265358979;
  s.add_face(std::vector<int>{0, 1, 2, 3, 4});
  s.add_face(std::vector<int>{0, 4, 5});
  s.add_face(std::vector<int>{4, 3, 8, 9, 6, 7});
  s.add_face(std::vector<int>{5, 4, 7});
  return Mesh(std::move(s));
}

void require_same(const Mesh& a, const Mesh& b) {
  REQUIRE(a.n_vertices() == b.n_vertices());
  REQUIRE(a.n_faces() == b.n_faces());
  CHECK((a.positions().array() == b.positions().array()).all());
  CHECK(a.face_offsets() == b.face_offsets());
  CHECK(a.face_indices() == b.face_indices());
}

// The square (0,0,0) (1,0,0) (1,1,0) (0,1,0) with one face (0 1 2 3) that several accepted
// corpus files spell in different ways.
void require_square(const PolygonSoup& s) {
  Eigen::MatrixX3d X(4, 3);
  X << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  REQUIRE(s.n_vertices() == 4);
  CHECK((s.positions.array() == X.array()).all());
  CHECK(s.face_offsets == std::vector<int>{0, 4});
  CHECK(s.face_indices == std::vector<int>{0, 1, 2, 3});
}

}  // namespace

TEST_CASE("every writer round-trips bit-exactly through its reader", "[io]") {
  const Mesh m = mixed_mesh();
  const fs::path d = temp_dir();
  for (const auto& [file, binary] : std::vector<std::pair<std::string, bool>>{
           {"m.obj", false}, {"m.off", false}, {"m.ply", false}, {"mb.ply", true}}) {
    INFO(file);
    const std::string p = (d / file).string();
    write_mesh(p, m, {}, {.binary = binary});
    require_same(read_mesh(p), m);
    const std::string bytes = slurp(p);
    require_same(read_mesh_from_memory(bytes, fs::path(file).extension().string().substr(1), "memory"), m);
  }
}

TEST_CASE("a file whose size is not known in advance (a named pipe) reads as the regular file does", "[io]") {
  // Regular files are read in one piece of their size; a pipe has no size and takes the chunked
  // path. The text is larger than the 64 KB chunks, so that many are appended.
#if defined(__unix__)
  const Mesh m = mixed_mesh();
  std::string text = fmt::format("OFF\n{} {} 0\n", m.n_vertices(), 20000 * m.n_faces());
  for (int v = 0; v < m.n_vertices(); ++v)
    text += fmt::format("{} {} {}\n", m.positions()(v, 0), m.positions()(v, 1), m.positions()(v, 2));
  for (int k = 0; k < 20000; ++k)
    for (int f = 0; f < m.n_faces(); ++f) text += fmt::format("{} {}\n", m.face(f).size(), fmt::join(m.face(f), " "));
  REQUIRE(text.size() > (1u << 19));
  const fs::path d = temp_dir();
  const std::string regular = (d / "big.off").string(), pipe = (d / "pipe.off").string();
  std::ofstream(regular, std::ios::binary) << text;
  REQUIRE(mkfifo(pipe.c_str(), 0600) == 0);
  std::thread writer([&] { std::ofstream(pipe, std::ios::binary) << text; });
  const PolygonSoup from_pipe = read_polygon_soup(pipe);
  writer.join();
  fs::remove(pipe);
  const PolygonSoup from_file = read_polygon_soup(regular);
  CHECK(from_file.n_faces() == 20000 * m.n_faces());
  CHECK((from_file.positions.array() == m.positions().array()).all());
  CHECK((from_pipe.positions.array() == from_file.positions.array()).all());
  CHECK(from_pipe.face_offsets == from_file.face_offsets);
  CHECK(from_pipe.face_indices == from_file.face_indices);
#else
  WARN("skipped: named pipes are POSIX");
#endif
}

TEST_CASE("binary OFF (float32) round-trips meshes whose positions are floats", "[io]") {
  Mesh m = mixed_mesh();
  m = m.with_positions(m.positions().cast<float>().cast<double>());
  const std::string p = (temp_dir() / "f.off").string();
  write_mesh(p, m, {}, {.binary = true});
  REQUIRE(slurp(p).substr(0, 11) == "OFF BINARY\n");
  require_same(read_mesh(p), m);
}

TEST_CASE("faces with more than 255 vertices round-trip in PLY (int list counts)", "[io]") {
  const int n = 300;
  PolygonSoup s;
  s.positions.resize(n, 3);
  std::vector<int> f(n);
  for (int i = 0; i < n; ++i) {
    s.positions.row(i) << std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0;
    f[i] = i;
  }
  s.add_face(f);
  const Mesh m(std::move(s));
  for (bool binary : {false, true}) {
    const std::string p = (temp_dir() / (binary ? "big_b.ply" : "big_a.ply")).string();
    write_mesh(p, m, {}, {.binary = binary});
    require_same(read_mesh(p), m);
  }
}

TEST_CASE("the paper's meshes load and round-trip through OBJ, OFF and PLY", "[io]") {
  const fs::path d = temp_dir();
  for (const char* name :
       {"L-plane.obj", "quad-plane.obj", "tetris.obj", "tetris_2.obj", "suzanne-half.obj", "amo_quad.off",
        "quad-sphere.off", "noisy-sphere.off", "unit-sphere-low.off", "bunny-hexa.off"}) {
    POLYDEC_SHARED_MESH(path, name);
    INFO(name);
    const Mesh m = read_mesh(path);
    CHECK(m.n_faces() > 0);
    CHECK(m.positions().allFinite());
    for (const char* out : {"r.obj", "r.off", "r.ply"}) {
      write_mesh((d / out).string(), m);
      require_same(read_mesh((d / out).string()), m);
    }
    write_mesh((d / "rb.ply").string(), m, {}, {.binary = true});
    require_same(read_mesh((d / "rb.ply").string()), m);
  }
}

TEST_CASE("pmp-library's OFF BINARY: the bunny loads whole and is rewritten byte for byte", "[io]") {
  POLYDEC_SHARED_MESH(path, "bunny-hexa.off");
  const Mesh m = read_mesh(path);
  // The layout: header line, three int32 counts, 12 bytes per vertex, per face 4 + 4 n bytes;
  // the reader must have consumed exactly the file.
  const std::string bytes = slurp(path);
  REQUIRE(m.n_vertices() == 11764);
  REQUIRE(m.n_faces() == 5884);
  CHECK(bytes.size() ==
        11 + 12 + 12 * size_t(m.n_vertices()) + 4 * size_t(m.n_faces()) + 4 * size_t(m.n_halfedges()));
  CHECK(m.positions().allFinite());
  std::map<int, int> valences;
  for (int f = 0; f < m.n_faces(); ++f) ++valences[m.face_size(f)];
  CHECK(valences[6] > m.n_faces() / 2);  // hexagon-dominant
  CHECK(valences.begin()->first >= 5);
  CHECK(valences.rbegin()->first <= 7);
  // A bunny-sized object: bounding box between 1 mm and 1 m in these units.
  CHECK(m.bounding_box_diagonal() > 1e-3);
  CHECK(m.bounding_box_diagonal() < 1e1);
  const std::string p = (temp_dir() / "bunny.off").string();
  write_mesh(p, m, {}, {.binary = true});
  CHECK(slurp(p) == bytes);
}

TEST_CASE("accepted variants: BOM, CRLF, tabs, comments, COFF/NOFF, i/t/n, mixed PLY types", "[io]") {
  for (const char* f : {"obj/bom_crlf_tabs.obj", "off/bom.off", "off/crlf_tabs_comments.off", "off/coff.off",
                        "off/noff.off", "ply/bom_crlf_tabs.ply", "ply/mixed_types_big_endian.ply"}) {
    INFO(f);
    require_square(read_polygon_soup((std::string(POLYDEC_TEST_DATA) + "/bad/") + f));
  }
}

TEST_CASE("OBJ negative indices and face entry forms name the same vertices", "[io]") {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  const PolygonSoup a = read_polygon_soup_from_memory(v + "f 1 2 3 4\n", "obj", "a");
  for (const char* f : {"f -4 -3 -2 -1\n", "f 1/1 2/2 3/3 4/4\n", "f 1//1 2//2 3//3 -1//4\n",
                        "f 1/1/1 -3/2/2 3/-1/3 4/4/-1\n", "f 1/ 2 3 4\n"}) {
    INFO(f);
    const PolygonSoup b = read_polygon_soup_from_memory(v + f, "obj", "b");
    CHECK(b.face_indices == a.face_indices);
  }
  // Relative indices count the vertices read so far, not the file's total.
  const PolygonSoup c =
      read_polygon_soup_from_memory("v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\nv 0 1 0\nf 1 3 -1\n", "obj", "c");
  CHECK(c.face_indices == std::vector<int>{0, 1, 2, 0, 2, 3});
}

TEST_CASE("very long lines: a 1 MB comment is skipped, a 1 MB token is rejected by line", "[io]") {
  const std::string big(1 << 20, 'x');
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  require_square(read_polygon_soup_from_memory("# " + big + "\n" + square, "obj", "long.obj"));
  require_square(read_polygon_soup_from_memory(
      "ply\nformat ascii 1.0\ncomment " + big +
          "\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
          "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
      "ply", "long.ply"));
  // A 1 MB face line (a 500000-gon referring to the square's vertices) is read whole and then
  // rejected by validation for repeating vertices: no line-length limit anywhere.
  std::string face = "f";
  for (int i = 0; i < 500000; ++i) face.append(1, ' ').append(std::to_string(1 + i % 4));
  REQUIRE(face.size() > 1000000);
  CHECK_THROWS_WITH(read_mesh_from_memory(square + face + "\n", "obj", "long.obj"),
                    Catch::Contains("long.obj:6: face 1 repeats vertex 0"));
  try {
    read_polygon_soup_from_memory("OFF\n1 0 0\n" + std::string(1 << 20, '7') + " 0 0\n", "off", "long.off");
    FAIL("a 1 MB number was accepted");
  } catch (const FileError& e) {
    CHECK(e.line == 3);
    CHECK(e.reason.find("bad vertex coordinate '7777") != std::string::npos);
    CHECK(e.reason.size() < 200);  // the token is not copied whole into the message
  }
}

TEST_CASE("PLY scalar properties are written as doubles, bit-exactly, ascii and binary", "[io]") {
  const Mesh m = mixed_mesh();
  Eigen::VectorXd a(m.n_vertices()), b(m.n_vertices());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int v = 0; v < m.n_vertices(); ++v) {
    a[v] = U(rng) / 3;
    b[v] = std::ldexp(U(rng), v * 40 - 200);
  }
  const VertexScalars scalars{{"distance", a}, {"u_2", b}};
  for (bool binary : {false, true}) {
    const std::string p = (temp_dir() / (binary ? "sb.ply" : "sa.ply")).string();
    write_mesh(p, m, scalars, {.binary = binary});
    require_same(read_mesh(p), m);  // the extra properties are skipped
    const std::string s = slurp(p);
    CHECK(s.find("property double distance\nproperty double u_2\n") != std::string::npos);
    const size_t body = s.find("end_header\n") + 11;
    for (int v = 0; v < m.n_vertices(); ++v) {
      double x[5];
      if (binary) {
        std::memcpy(x, s.data() + body + 40 * v, 40);
      } else {
        size_t pos = body;
        for (int l = 0; l < v; ++l) pos = s.find('\n', pos) + 1;
        const char* q = s.data() + pos;
        for (double& xi : x) {
          while (*q == ' ') ++q;
          q = std::from_chars(q, s.data() + s.size(), xi).ptr;
        }
      }
      INFO("vertex " << v);
      CHECK(x[0] == m.positions()(v, 0));
      CHECK(x[3] == a[v]);
      CHECK(x[4] == b[v]);
    }
  }
}

TEST_CASE("writers refuse bad scalar fields, unknown formats and unwritable paths", "[io]") {
  const Mesh m = mixed_mesh();
  const std::string p = (temp_dir() / "w.ply").string();
  CHECK_THROWS_WITH(write_mesh(p, m, {{"has space", Eigen::VectorXd::Zero(m.n_vertices())}}),
                    Catch::Contains("'has space' is empty or has whitespace"));
  CHECK_THROWS_WITH(write_mesh(p, m, {{"short", Eigen::VectorXd::Zero(3)}}),
                    Catch::Contains("'short' has 3 values for 10 vertices"));
  CHECK_THROWS_AS(write_mesh((temp_dir() / "w.stl").string(), m), FileError);
  CHECK_THROWS_WITH(write_mesh("/nonexistent-dir/x.obj", m), Catch::Contains("cannot open file for writing"));
  CHECK_THROWS_WITH(read_mesh("/nonexistent-dir/x.obj"),
                    Catch::Contains("/nonexistent-dir/x.obj: cannot open"));
  CHECK_THROWS_WITH(read_mesh(temp_dir().string() + "/dir.off/"), Catch::Contains("unknown mesh format"));
  fs::create_directories(temp_dir() / "dir.off");
  CHECK_THROWS_WITH(read_mesh((temp_dir() / "dir.off").string()), Catch::Contains("is a directory"));
}

TEST_CASE("Matrix Market round-trips every double exactly, symmetric files are mirrored", "[io]") {
  const int n = 40;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < 300; ++k)
    t.emplace_back(int(rng() % n), int(rng() % (n + 3)), std::ldexp(U(rng), int(rng() % 1200) - 600));
  t.emplace_back(0, 0, 5e-324);  // subnormal
  t.emplace_back(1, 0, -1.7976931348623157e308);
  Eigen::SparseMatrix<double> A(n, n + 3);
  A.setFromTriplets(t.begin(), t.end());
  const std::string p = (temp_dir() / "A.mtx").string();
  write_matrix_market(p, A);
  CHECK(slurp(p).substr(0, 45) == "%%MatrixMarket matrix coordinate real general");
  const Eigen::SparseMatrix<double> B = read_matrix_market(p);
  REQUIRE(B.rows() == A.rows());
  REQUIRE(B.cols() == A.cols());
  CHECK(B.nonZeros() == A.nonZeros());
  CHECK(Eigen::MatrixXd(A - B).cwiseAbs().maxCoeff() == 0.0);

  const auto S = read_matrix_market_from_memory(
      "%%MatrixMarket matrix coordinate real symmetric\n% comment\n3 3 3\n1 1 2\n3 1 -1\n3 1 0.5\n", "s.mtx");
  Eigen::MatrixXd E(3, 3);
  E << 2, 0, -0.5, 0, 0, 0, -0.5, 0, 0;  // duplicates summed, mirrored
  CHECK(Eigen::MatrixXd(S) == E);
  const auto K = read_matrix_market_from_memory(
      "%%MatrixMarket matrix coordinate integer skew-symmetric\n2 2 1\n2 1 3\n", "k.mtx");
  CHECK(Eigen::MatrixXd(K)(0, 1) == -3.0);
  CHECK(Eigen::MatrixXd(K)(1, 0) == 3.0);

  // Dense array format: column by column; symmetric files hold the lower triangle, skew-symmetric
  // ones the strictly lower one.
  const auto G = read_matrix_market_from_memory(
      "%%MatrixMarket matrix array real general\n2 3\n1\n2\n0\n4\n5\n6\n", "g.mtx");
  Eigen::MatrixXd EG(2, 3);
  EG << 1, 0, 5, 2, 4, 6;
  CHECK(Eigen::MatrixXd(G) == EG);
  CHECK(G.nonZeros() == 5);  // the zero is not stored
  const auto AS = read_matrix_market_from_memory(
      "%%MatrixMarket matrix array real symmetric\n3 3\n% lower triangle\n4\n-1\n0\n4\n-1\n4\n", "s.mtx");
  Eigen::MatrixXd ES(3, 3);
  ES << 4, -1, 0, -1, 4, -1, 0, -1, 4;
  CHECK(Eigen::MatrixXd(AS) == ES);
  const auto AK =
      read_matrix_market_from_memory("%%MatrixMarket matrix array integer skew-symmetric\n2 2\n7\n", "k.mtx");
  CHECK(Eigen::MatrixXd(AK)(1, 0) == 7.0);
  CHECK(Eigen::MatrixXd(AK)(0, 1) == -7.0);
}

TEST_CASE("dense Matrix Market: written as an array, read back bit for bit", "[io]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  Eigen::MatrixXd A(7, 3);
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = 0; i < A.rows(); ++i) A(i, j) = std::ldexp(U(rng), int(rng() % 1200) - 600);
  A(0, 0) = 5e-324;  // subnormal
  A(1, 0) = -1.7976931348623157e308;
  A(2, 1) = 0.0;  // written, not stored on reading
  const std::string p = (temp_dir() / "dense.mtx").string();
  write_dense_matrix_market(p, A);
  const std::string text = slurp(p);
  CHECK(text.substr(0, 41) == "%%MatrixMarket matrix array real general\n");
  CHECK(std::count(text.begin(), text.end(), '\n') == 2 + A.size());  // header, size, one value a line
  const Eigen::SparseMatrix<double> B = read_matrix_market(p);
  REQUIRE(B.rows() == A.rows());
  REQUIRE(B.cols() == A.cols());
  CHECK(Eigen::MatrixXd(B) == A);
  // Column by column: the second value is A(1, 0).
  CHECK(text.find("\n-1.7976931348623157e+308\n") != std::string::npos);
  const std::string empty = (temp_dir() / "empty.mtx").string();
  write_dense_matrix_market(empty, Eigen::MatrixXd(0, 4));
  CHECK(read_matrix_market(empty).cols() == 4);
  CHECK_THROWS_AS(write_dense_matrix_market("/nonexistent-dir/d.mtx", A), FileError);
}

TEST_CASE("FileError formats FILE:LINE, FILE: byte N, or FILE alone", "[io]") {
  CHECK(std::string(FileError("a.obj", 12, -1, "bad").what()) == "a.obj:12: bad");
  CHECK(std::string(FileError("a.ply", 0, 345, "bad").what()) == "a.ply: byte 345: bad");
  CHECK(std::string(FileError("a.off", 0, -1, "bad").what()) == "a.off: bad");
  const FileError e("f", 3, -1, "why");
  CHECK(e.file == "f");
  CHECK(e.line == 3);
  CHECK(e.byte_offset == -1);
  CHECK(e.reason == "why");
}

}  // namespace test_io
