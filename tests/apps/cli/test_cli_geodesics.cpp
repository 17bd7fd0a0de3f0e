// tests/apps/cli/test_cli_geodesics.cpp — `polydec geodesics --per-source`: the written |V| x k
// matrix equals the library's one field per source (and one-by-one runs of the program), the JSON
// reports the phases' seconds, bad combinations are usage errors.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "polydec/apps/applications/geodesics.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/mesh/generators.h"
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
  for (const char* phase : {"read", "operators", "factorization", "solves", "write"})
    CHECK(j["seconds"][phase].get<double>() >= 0);
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
  CHECK(nlohmann::json::parse(s.out)["seconds"]["solves"].get<double>() >= 0);
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

}  // namespace test_cli_geodesics
