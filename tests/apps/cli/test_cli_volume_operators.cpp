// tests/apps/cli/test_cli_volume_operators.cpp — `polydec operators` and `polydec dec` on volume
// meshes: the written matrices against the library's, --volume on a file without a volume
// extension, --cell-point, the DEC files' identities, and the exit codes of refused input.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/operators/volume/laplacian.h"
#include "tests/support/volume_meshes.h"
#include "tests/apps/cli/cli_run.h"
#include "tests/support/support.h"

using namespace polydec;
namespace fs = std::filesystem;

namespace test_cli_volume_operators {
using polydec::test::relative_difference;

namespace {

using Run = test::CliRun;

Run run(const fs::path& dir, const std::string& args) { return test::run_cli_in(dir, args); }

struct Scratch : test::ScratchDir {
  Scratch() : ScratchDir("cli_volops") {}
};

}  // namespace

TEST_CASE("polydec operators on volume meshes", "[volume][volume-operators][cli]") {
  Scratch s;
  const VolumeMesh written = hex_grid_volume(2, 2, 3, {0.2, 5});
  write_volume_mesh(written, s.path("hex.ovm"));
  const VolumeMesh mesh = read_volume_mesh(s.path("hex.ovm"));
  Run r = run(s.dir, "operators " + s.path("hex.ovm") + " --out " + s.path("ops") + " --json");
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["cells"] == 12);
  CHECK(j["subtet_degenerate"] == 0);
  const VolumeRefinement R = refine_volume(mesh);
  const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
  CHECK(relative_difference(read_matrix_market(s.path("ops/S.mtx")), L.S) < 1e-14);
  CHECK(relative_difference(read_matrix_market(s.path("ops/M.mtx")), L.M) < 1e-14);
  CHECK((SparseMatrix(read_matrix_market(s.path("ops/M_lumped.mtx"))).diagonal() - L.M_lumped).norm() <
        1e-14 * L.M_lumped.norm());
  CHECK(relative_difference(read_matrix_market(s.path("ops/P.mtx")), volume_prolongation(mesh, R)) < 1e-14);

  // --volume on a file without a volume extension; --cell-point polylaplace.
  fs::copy_file(s.path("hex.ovm"), s.path("hex.dat"));
  r = run(s.dir,
          "operators " + s.path("hex.dat") + " --volume --cell-point polylaplace --out " + s.path("pl"));
  REQUIRE(r.code == 0);
  VolumeRefinementOptions o;
  o.cell_rule = CellPointRule::PolyLaplace;
  CHECK(relative_difference(read_matrix_market(s.path("pl/S.mtx")),
                            assemble_volume_laplacian(mesh, refine_volume(mesh, o)).S) < 1e-14);
  r = run(s.dir, "operators " + s.path("hex.ovm") + " --cell-point nonsense --out " + s.path("x"));
  CHECK(r.code == 2);
  CHECK(r.err.find("nonsense") != std::string::npos);
}

TEST_CASE("polydec dec on volume meshes", "[volume][volume-dec][cli]") {
  Scratch s;
  write_volume_mesh(hex_grid_volume(2, 1, 1, {0.2, 3}), s.path("hex.ovm"));
  const VolumeMesh mesh = read_volume_mesh(s.path("hex.ovm"));
  Run r = run(s.dir, "dec " + s.path("hex.ovm") + " --out " + s.path("dec") + " --json");
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  const VolumeDec D = volume_dec(mesh, refine_volume(mesh));
  CHECK(j["pairs"] == D.coarse.n_pairs());
  CHECK(j["quadruples"] == D.coarse.n_quads());
  CHECK(j["rank_star3"].get<int>() > 0);
  SparseMatrix d[3], star[4];
  for (int k = 0; k < 3; ++k) d[k] = read_matrix_market(s.path("dec/d" + std::to_string(k) + ".mtx"));
  for (int k = 0; k < 4; ++k) {
    star[k] = read_matrix_market(s.path("dec/star" + std::to_string(k) + ".mtx"));
    CHECK(relative_difference(star[k], D.star[k]) < 1e-14);
    CHECK(relative_difference(read_matrix_market(s.path("dec/P" + std::to_string(k) + ".mtx")), D.P[k]) <
          1e-14);
  }
  CHECK(SparseMatrix(d[1] * d[0]).norm() == 0.0);
  CHECK(SparseMatrix(d[2] * d[1]).norm() == 0.0);
  const SparseMatrix S = star[1];
  CHECK(relative_difference(SparseMatrix(-d[0].transpose() * S * d[0]),
                            assemble_volume_laplacian(mesh, refine_volume(mesh)).S) < 1e-12);
  std::ifstream tets(s.path("dec/tetrahedra.txt"));
  int lines = 0;
  for (std::string line; std::getline(tets, line);) ++lines;
  CHECK(lines == D.coarse.n_quads());

  // A 14-vertex cell: forms up to degree 2 by default, with a warning; degree 3 asked for is bad
  // input naming the cell; a degree outside 0..3 is a usage error.
  write_volume_mesh(test::prism_volume(7), s.path("prism.ovm"));
  r = run(s.dir, "dec " + s.path("prism.ovm") + " --out " + s.path("t") + " --json");
  REQUIRE(r.code == 0);
  j = nlohmann::json::parse(r.out);
  CHECK(j["max_degree"] == 2);
  CHECK(j["rank_star3"].is_null());
  CHECK(r.err.find("up to degree 2") != std::string::npos);
  for (const char* f : {"d0.mtx", "d1.mtx", "star2.mtx", "P2.mtx", "triangles.txt"})
    CHECK(fs::exists(s.path(std::string("t/") + f)));
  for (const char* f : {"d2.mtx", "star3.mtx", "P3.mtx", "tetrahedra.txt"}) CHECK(!fs::exists(s.path(std::string("t/") + f)));
  CHECK(std::find(j["files"].begin(), j["files"].end(), "d2.mtx") == j["files"].end());
  r = run(s.dir, "dec " + s.path("prism.ovm") + " --out " + s.path("t3") + " --max-degree 3");
  CHECK(r.code == 3);
  CHECK(r.err.find("cell 0") != std::string::npos);
  CHECK(run(s.dir, "dec " + s.path("prism.ovm") + " --out " + s.path("t4") + " --max-degree 4").code == 2);
}

}  // namespace test_cli_volume_operators
