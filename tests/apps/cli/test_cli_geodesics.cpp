// tests/apps/cli/test_cli_geodesics.cpp — `polydec geodesics --per-source`: the written |V| x k
// matrix equals the library's one field per source (and one-by-one runs of the program), bad
// combinations are usage errors; the phases' times (times_ms) of every computing command's JSON.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "polydec/apps/applications/geodesics.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "tests/apps/cli/cli_run.h"

using namespace polydec;

namespace test_cli_geodesics {

TEST_CASE("polydec geodesics --per-source writes one distance field per source", "[geodesics]") {
  const test::ScratchDir scratch("geodesics_per_source");
  const std::string dir = scratch.dir.string();
  write_mesh(dir + "/sphere.obj", add_noise(hex_sphere(2), 0.05, 4));
  const Mesh mesh = read_mesh(dir + "/sphere.obj");
  const test::CliRun r = test::run_cli_in(
      dir, "geodesics " + dir + "/sphere.obj --source 3 --source 50 --source 3 --per-source --out " + dir +
               "/D.mtx --json");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["rows"] == mesh.n_vertices());
  CHECK(j["columns"] == 3);
  for (const char* phase : {"read", "operators", "factorization", "solve", "write"})
    CHECK(j["times_ms"][phase].get<double>() >= 0);
  const Eigen::MatrixXd D = Eigen::MatrixXd(read_matrix_market(dir + "/D.mtx"));
  REQUIRE(D.rows() == mesh.n_vertices());
  REQUIRE(D.cols() == 3);
  const HeatGeodesics heat(mesh);
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd one = heat.distance(c == 1 ? 50 : 3);
    CHECK((D.col(c) - one).cwiseAbs().maxCoeff() <= 1e-12 * one.maxCoeff());
  }
  // The single-field run reports its phases too.
  const test::CliRun s = test::run_cli_in(dir, "geodesics " + dir + "/sphere.obj --source 3 --json");
  REQUIRE(s.code == 0);
  CHECK(nlohmann::json::parse(s.out)["times_ms"]["solve"].get<double>() >= 0);
  // --per-source needs --out FILE.mtx, no picture.
  CHECK(test::run_cli_in(dir, "geodesics " + dir + "/sphere.obj --source 3 --per-source").code == 2);
  CHECK(test::run_cli_in(dir, "geodesics " + dir + "/sphere.obj --source 3 --per-source --out " + dir + "/d.ply").code ==
        2);
  CHECK(test::run_cli_in(dir, "geodesics " + dir + "/sphere.obj --source 3 --per-source --out " + dir +
                                  "/d.mtx --png " + dir + "/d.png")
            .code == 2);
  CHECK(test::run_cli_in(dir, "geodesics " + dir + "/sphere.obj --source 9999 --per-source --out " + dir + "/d.mtx")
            .code != 0);
}


namespace {

// The phases of `times_ms`: finite, non-negative, only the known names, and total at least their sum
// (total spans the whole command; the phases do not overlap). Rounding: a microsecond per phase.
void check_times(const std::string& command, const nlohmann::json& j, std::vector<std::string> expected) {
  INFO(command);
  REQUIRE(j.contains("times_ms"));
  const nlohmann::json& t = j["times_ms"];
  REQUIRE(t.is_object());
  REQUIRE(t.contains("total"));
  expected.push_back("total");
  for (const std::string& phase : expected) CHECK(t.contains(phase));
  double sum = 0;
  for (const auto& [name, value] : t.items()) {
    INFO(name);
    CHECK((name == "read" || name == "generate" || name == "operators" || name == "factorization" ||
           name == "solve" || name == "statistics" || name == "evaluation" || name == "render" || name == "write" ||
           name == "total"));
    REQUIRE(value.is_number());
    const double ms = value.get<double>();
    CHECK(std::isfinite(ms));
    CHECK(ms >= 0);
    if (name != "total") sum += ms;
  }
  CHECK(t["total"].get<double>() >= sum - 1e-3 * double(t.size()));
}

}  // namespace

TEST_CASE("every computing command's --json reports its phases' times", "[cli][times]") {
  const test::ScratchDir scratch("cli_times");
  const std::string dir = scratch.dir.string();
  const std::string obj = dir + "/sphere.obj", ovm = dir + "/grid.ovm";
  write_mesh(obj, add_noise(hex_sphere(1), 0.05, 4));
  write_volume_mesh(hex_grid_volume(2, 2, 2), ovm);
  const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
      {"operators " + obj + " --out " + dir + "/ops", {"read", "operators", "write"}},
      {"operators " + ovm + " --out " + dir + "/vops", {"read", "operators", "write"}},
      {"dec " + obj + " --out " + dir + "/dec", {"read", "operators", "write"}},
      {"dec " + ovm + " --complex mesh --out " + dir + "/vdec", {"read", "operators", "write"}},
      {"geodesics " + obj + " --source 0 --out " + dir + "/d.ply", {"read", "operators", "factorization", "solve", "write"}},
      {"geodesics " + ovm + " --source 0", {"read", "operators", "factorization", "solve"}},
      {"hodge " + obj + " --out " + dir + "/parts.txt", {"read", "operators", "solve", "write"}},
      {"spectrum " + obj + " --k 4 --out " + dir + "/spec", {"read", "operators", "solve", "write"}},
      {"spectrum " + obj + " --form 1 --k 3", {"read", "solve"}},
      {"curvature " + obj, {"read", "operators", "solve"}},
      {"harmonics " + obj, {"read", "operators", "solve"}},
      {"smooth " + obj + " --steps 2 --out " + dir + "/smooth", {"read", "operators", "solve", "write"}},
      {"spectral " + obj + " --hks --k 8 --samples 4", {"read", "operators", "solve"}},
      {"convert " + obj + " " + dir + "/copy.off", {"read", "write"}},
      {"convert " + ovm + " " + dir + "/copy.vtk", {"read", "write"}},
      {"poisson --resolutions 4 8 --family quads", {"solve"}},
      {"volume-spectrum --ball 2 --k 2", {"solve"}},
      {"info " + obj, {"read", "statistics"}},
      {"info " + ovm, {"read", "statistics"}},
      {"render " + obj + " --png " + dir + "/a.png --width 64 --height 48", {"read", "render"}},
      {"render " + obj + " --png " + dir + "/b.png --distance-from 0 --width 64 --height 48",
       {"read", "operators", "factorization", "solve", "render"}},
      {"render " + ovm + " --png " + dir + "/c.png --width 64 --height 48", {"read", "operators", "render"}},
      {"render " + ovm + " --png " + dir + "/d.png --distance-from 0 --width 64 --height 48",
       {"read", "operators", "factorization", "solve", "render"}},
      {"demo --level 1 --out " + dir + "/demo", {"generate", "operators", "factorization", "solve", "render", "write"}}};
  for (const auto& [args, phases] : runs) {
    const test::CliRun r = test::run_cli_in(dir, args + " --json");
    INFO(args << "\n" << r.err);
    REQUIRE(r.code == 0);
    check_times(args, nlohmann::json::parse(r.out), phases);
  }
}

}  // namespace test_cli_geodesics
