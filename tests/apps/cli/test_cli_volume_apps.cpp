// tests/apps/cli/test_cli_volume_apps.cpp — `polydec poisson --volume`, `polydec volume-spectrum` and
// `polydec spectrum --form K` on a volume file: their JSON against the library's numbers, the
// shared-cube branch, the files written, and refused options.
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "polydec/apps/applications/volume/poisson.h"
#include "polydec/apps/applications/volume/spectrum.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "tests/apps/cli/cli_run.h"
#include "tests/support/support.h"

using namespace polydec;
namespace fs = std::filesystem;

namespace test_cli_volume_apps {
namespace {

using Run = test::CliRun;

// Runs `polydec ARGS` in a scratch folder of its own, removed afterwards.
Run run(const std::string& args) {
  const test::ScratchDir scratch("cli_volapps");
  return test::run_cli_in(scratch.dir, args);
}

}  // namespace

TEST_CASE("polydec poisson --volume on generated hex grids", "[volume-apps][cli]") {
  const Run r = run("poisson --volume --resolutions 3 6 --json");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["levels"].size() == 2);
  CHECK(j["mass"] == "unlumped");
  const auto e = volume_franke_poisson(hex_grid_volume(6, 6, 6));
  CHECK(j["levels"][1]["vertices"] == 343);
  CHECK(j["levels"][1]["l2_error"].get<double>() == Approx(e.l2_error).epsilon(1e-10));
  CHECK(j["levels"][1]["rms_error"].get<double>() == Approx(e.rms_error).epsilon(1e-10));
  const auto e3 = volume_franke_poisson(hex_grid_volume(3, 3, 3));
  CHECK(j["levels"][1]["l2_slope"].get<double>() ==
        Approx(std::log(e.l2_error / e3.l2_error) / std::log(e.h / e3.h)).epsilon(1e-10));

  const Run t = run("poisson --volume --family truncated --resolutions 2 3");
  INFO(t.err);
  CHECK(t.code == 0);
  CHECK(t.out.find("slopes") != std::string::npos);

  CHECK(run("poisson --volume --family prisms").code == 2);
  CHECK(run("poisson --volume --resolutions 4").code == 2);
  CHECK(run("poisson --volume --data /nonexistent/folder").code == 3);
}

TEST_CASE("polydec poisson --volume --data reads the shared cubes", "[volume-apps][cli]") {
  const std::string path = test::shared_path("volume/cube_tetrahedron_1.ovm");
  if (path.empty()) {
    WARN("skipped: ../shared/data/volume not found");
    return;
  }
  const std::string dir = fs::path(path).parent_path().string();
  const Run r = run("poisson --volume --family tetrahedra --levels 1 2 --json --data '" + dir + "'");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["levels"].size() == 2);
  const auto e = volume_franke_poisson(read_volume_mesh(dir + "/cube_tetrahedron_2.ovm"));
  CHECK(j["levels"][1]["level"] == "cube_tetrahedron_2.ovm");
  CHECK(j["levels"][1]["l2_error"].get<double>() == Approx(e.l2_error).epsilon(1e-10));
}

TEST_CASE("polydec volume-spectrum on a hexahedral ball", "[volume-apps][cli]") {
  const Run r = run("volume-spectrum --ball 5 --k 5 --dirichlet --json");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["eigenvalues"].size() == 5);
  CHECK(j["boundary"] == "dirichlet");
  const BallSpectrum b = ball_spectrum(5, 5, true);
  for (int i = 0; i < 5; ++i) {
    CHECK(j["eigenvalues"][i]["eigenvalue"].get<double>() == Approx(b.eigenvalues[size_t(i)]).epsilon(1e-8));
    CHECK(j["eigenvalues"][i]["analytic"].get<double>() ==
          Approx(b.analytic[size_t(i)].lambda).epsilon(1e-12));
  }
  CHECK(j["eigenvalues"][0]["analytic"].get<double>() == Approx(M_PI * M_PI).epsilon(1e-12));

  const Run t = run("volume-spectrum --ball 4 --k 4");
  INFO(t.err);
  CHECK(t.code == 0);
  CHECK(t.out.find("Neumann") != std::string::npos);
  CHECK(t.out.find("(absolute)") != std::string::npos);
  CHECK(run("volume-spectrum --ball 1").code == 2);
  CHECK(run("volume-spectrum --k 0").code == 2);
}

TEST_CASE("polydec spectrum --form 1|2|3 on a volume mesh", "[volume-apps][volume-form-spectrum][cli]") {
  const test::ScratchDir scratch("cli_volform");
  const std::string path = (scratch.dir / "grid.ovm").string();
  write_volume_mesh(hex_grid_volume(2, 2, 3, {0.2, 83}), path);
  const VolumeMesh mesh = read_volume_mesh(path);
  for (int degree = 1; degree <= 3; ++degree)
    for (const char* complex : {"mesh", "complete"}) {
      INFO("--form " << degree << " --complex " << complex);
      const std::string out = (scratch.dir / fmt::format("out{}{}", degree, complex)).string();
      const Run r = test::run_cli_in(scratch.dir, fmt::format("spectrum '{}' --form {} --complex {} --k 5 --json --out '{}'",
                                                              path, degree, complex, out));
      INFO(r.err);
      REQUIRE(r.code == 0);
      const auto j = nlohmann::json::parse(r.out);
      FormSpectrumOptions o;
      o.degree = degree;
      o.k = 5;
      o.complex = std::string(complex) == "mesh" ? DecComplex::Mesh : DecComplex::Complete;
      const FormSpectrum s = volume_form_spectrum(mesh, o);
      REQUIRE(j["eigenvalues"].size() == 5);
      for (int i = 0; i < 5; ++i) CHECK(j["eigenvalues"][i].get<double>() == Approx(s.eigenvalues[i]).epsilon(1e-8));
      CHECK(j["k_cells"].get<long>() == s.eigenvectors.rows());
      const int counts[4] = {mesh.n_vertices(), mesh.n_edges(), mesh.n_faces(), mesh.n_cells()};
      if (o.complex == DecComplex::Mesh) CHECK(j["k_cells"].get<long>() == counts[degree]);
      for (const auto& file : j["files"]) CHECK(fs::exists(fs::path(out) / file.get<std::string>()));
    }
  const std::string base = "spectrum '" + path + "' --k 4 ";
  CHECK(test::run_cli_in(scratch.dir, base + "--form 4").code == 2);
  CHECK(test::run_cli_in(scratch.dir, base + "--form 1 --png x.png").code == 2);
  CHECK(test::run_cli_in(scratch.dir, base + "--form 1 --complex other").code == 2);
}

}  // namespace test_cli_volume_apps
