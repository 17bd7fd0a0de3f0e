// tests/apps/cli/test_cli_exit_codes.cpp — the built `polydec` program maps failures to distinct
// exit codes (0 ok, 2 usage, 3 bad input, 4 solver failure) and says why in exactly one line on
// stderr.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "tests/apps/cli/cli_run.h"
#include "tests/support/support.h"

using namespace polydec;
namespace fs = std::filesystem;

namespace test_cli_exit_codes {

namespace {

struct Run {
  int code = -1;
  std::vector<std::string> err;  // stderr lines
  std::string out;
};

Run run(const fs::path& dir, const std::string& args) {
  const test::CliRun r = test::run_cli_in(dir, args);
  return {r.code, test::split_lines(r.err), r.out};
}

struct Scratch : test::ScratchDir {
  Scratch() : ScratchDir("cli_test") {}
};

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// Exit code `code` with one stderr line starting "polydec: " and containing `words`.
void expect_failure(const Run& r, int code, const std::string& words) {
  CHECK(r.code == code);
  REQUIRE(r.err.size() == 1);
  CHECK_THAT(r.err[0], Catch::StartsWith("polydec: ") && Catch::Contains(words));
}

}  // namespace

TEST_CASE("polydec exits 0 on success, with nothing on stderr", "[robust][cli]") {
  Scratch s;
  write_mesh(s.path("grid.obj"), quad_grid(4, 4));
  Run r = run(s.dir, "geodesics " + s.path("grid.obj") + " --source 0");
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  CHECK_THAT(r.out, Catch::Contains("distance"));
  r = run(s.dir, "geodesics " + s.path("grid.obj") +
                     " --source 0 --laplacian intrinsic-delaunay --mass unlumped --delta-source --time-step-edges operator");
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  r = run(s.dir, "--help");
  CHECK(r.code == 0);
}

TEST_CASE("polydec exits 2 on usage errors", "[robust][cli]") {
  Scratch s;
  write_mesh(s.path("grid.obj"), quad_grid(2, 2));
  const std::string grid = s.path("grid.obj");
  expect_failure(run(s.dir, ""), 2, "usage error");
  expect_failure(run(s.dir, "no-such-command"), 2, "usage error");
  expect_failure(run(s.dir, "geodesics " + grid + " --source 0 --bogus"), 2, "--bogus");
  expect_failure(run(s.dir, "geodesics " + grid), 2, "--source");
  expect_failure(run(s.dir, "geodesics " + grid + " --source zero"), 2, "usage error");
  expect_failure(run(s.dir, "geodesics " + grid + " --source 0 --mass heavy"), 2, "--mass");
  expect_failure(run(s.dir, "geodesics " + grid + " --source 0 --laplacian nope"), 2, "nope");
  expect_failure(run(s.dir, "geodesics " + grid + " --source 0 --time-step-edges both"), 2, "--time-step-edges");
  expect_failure(run(s.dir, "repair " + grid + " " + s.path("out.obj") + " --merge-tolerance -1"), 2,
                 "--merge-tolerance");
}

TEST_CASE("polydec exits 3 on bad input, naming the file and the problem", "[robust][cli]") {
  Scratch s;
  write_mesh(s.path("grid.obj"), quad_grid(2, 2));
  const std::string grid = s.path("grid.obj");
  expect_failure(run(s.dir, "geodesics " + s.path("missing.obj") + " --source 0"), 3, "missing.obj");
  write_text(s.path("junk.off"), "this is not a mesh\n");
  expect_failure(run(s.dir, "geodesics " + s.path("junk.off") + " --source 0"), 3, "junk.off");
  // A fin: three faces on the edge (1, 2).
  write_text(
      s.path("fin.obj"),
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0.5 1\nv 2 0.5 0\nf 1 2 3\nf 1 3 4\nf 2 3 5\nf 3 2 6\n");
  expect_failure(run(s.dir, "geodesics " + s.path("fin.obj") + " --source 0"), 3, "non-manifold");
  expect_failure(run(s.dir, "geodesics " + grid + " --source 99"), 3, "99");
  // A vertex that no face uses cannot be a source.
  write_text(s.path("lonely.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n");
  expect_failure(run(s.dir, "geodesics " + s.path("lonely.obj") + " --source 3"), 3, "source vertex 3");
  // Repair cannot fix a non-manifold edge: still bad input, said so.
  expect_failure(run(s.dir, "repair " + s.path("fin.obj") + " " + s.path("out.obj")), 3,
                 "still invalid after repair");
}

TEST_CASE("polydec exits 4 when a factorization fails, naming the operator", "[robust][cli]") {
  // A strongly non-convex decagon whose vertex 7 has negative lumped mass (-2.3% of the polygon's
  // area: its squared-area weight is negative), beside a separate patch of tiny triangles that
  // makes the mean edge length, and so the heat time step, small: M - t S is indefinite.
  Scratch s;
  PolygonSoup soup;
  const Mesh tiny = triangle_grid(12, 12);
  const double decagon[10][2] = {
      {0.66008772929804027, 0.38310639457895351},    {0.06042048096178998, 0.059255361334458079},
      {0.012069786289089999, 0.1616883075842106},    {-0.15404306852644853, 0.22305280334330982},
      {-0.33664512915794165, 0.18328097007149002},   {-0.91595804655426061, -0.26006271076774889},
      {-0.5058396898122679, -0.53862784288435039},   {-0.0073885978573050362, -0.27039794338713941},
      {0.041029612926050125, -0.090695463299041948}, {0.056109728765853434, -0.0052887316637353658}};
  soup.positions.resize(10 + tiny.n_vertices(), 3);
  std::vector<int> face;
  for (int k = 0; k < 10; ++k) {
    soup.positions.row(k) << decagon[k][0], decagon[k][1], 0;
    face.push_back(k);
  }
  soup.add_face(face);
  soup.positions.bottomRows(tiny.n_vertices()) =
      (1e-3 * tiny.positions()).rowwise() + Eigen::RowVector3d(2, 0, 0);
  for (int f = 0; f < tiny.n_faces(); ++f) {
    std::vector<int> t(tiny.face(f).begin(), tiny.face(f).end());
    for (int& v : t) v += 10;
    soup.add_face(t);
  }
  write_mesh(s.path("negative_mass.obj"), Mesh(soup));
  expect_failure(run(s.dir, "geodesics " + s.path("negative_mass.obj") + " --source 0"), 4,
                 "heat operator M - t S");
}

TEST_CASE("polydec repair reports what it changed and writes a valid mesh", "[robust][cli]") {
  Scratch s;
  // Two triangles with their shared edge's vertices duplicated, a duplicate face, an unused vertex.
  write_text(s.path("soup.obj"),
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 7 7 7\nf 1 2 3\nf 4 5 6\nf 1 2 3\n");
  const Run r = run(s.dir, "repair " + s.path("soup.obj") + " " + s.path("fixed.obj"));
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  CHECK_THAT(r.out, Catch::Contains("merged 2 vertices"));
  CHECK_THAT(r.out, Catch::Contains("removed 1 duplicate faces"));
  CHECK_THAT(r.out, Catch::Contains("removed 1 unreferenced vertices"));
  const Mesh fixed = read_mesh(s.path("fixed.obj"));
  CHECK(fixed.n_vertices() == 4);
  CHECK(fixed.n_faces() == 2);
  CHECK(fixed.n_components() == 1);
  CHECK(fixed.n_boundary_edges() == 4);
}

TEST_CASE("subcommands with --repair repair the file first, say what changed, and map source vertices",
          "[robust][cli]") {
  Scratch s;
  // Two triangles with their shared edge's vertices duplicated, a duplicate face, an unused vertex.
  write_text(s.path("soup.obj"),
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 7 7 7\nf 1 2 3\nf 4 5 6\nf 1 2 3\n");
  // Without --repair the duplicate face is invalid input.
  expect_failure(run(s.dir, "info " + s.path("soup.obj")), 3, "soup.obj");
  const Run info = run(s.dir, "info " + s.path("soup.obj") + " --repair --json");
  CHECK(info.code == 0);
  CHECK(info.err.size() == 3);  // merged vertices, duplicate face, unreferenced vertex
  for (const std::string& line : info.err) CHECK_THAT(line, Catch::StartsWith("polydec: --repair "));
  CHECK_THAT(info.out, Catch::Contains("\"vertices\": 4"));
  // File vertex 4 (1 1 0) becomes mesh vertex 3; its distance to file vertex 1 (1 0 0) is 1.
  const Run geo = run(s.dir, "geodesics " + s.path("soup.obj") + " --repair --source 4 --json --out " +
                                 s.path("d.ply"));
  CHECK(geo.code == 0);
  const Mesh out = read_mesh(s.path("d.ply"));
  CHECK(out.n_vertices() == 4);
  // The unused vertex 6 is removed: it cannot be a source.
  const Run gone = run(s.dir, "geodesics " + s.path("soup.obj") + " --repair --source 6");
  CHECK(gone.code == 3);
  REQUIRE(gone.err.size() == 4);  // the three repair lines, then the error
  CHECK_THAT(gone.err.back(),
             Catch::StartsWith("polydec: ") && Catch::Contains("source vertex 6 was removed by --repair"));
}

}  // namespace test_cli_exit_codes
