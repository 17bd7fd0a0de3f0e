// tests/apps/cli/test_cli_volume_geodesics.cpp — the volume branches of `polydec geodesics`, `spectrum`,
// `render` and `poisson --volume --laplacian` ([volume-cli]): JSON against the library's numbers, the
// VTK point data read back, the PNG written, refused options and bad input.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "polydec/apps/applications/geodesics.h"
#include "polydec/apps/applications/spectrum.h"
#include "polydec/apps/applications/volume/poisson.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/operators/registry/volume_laplacians.h"
#include "tests/apps/cli/cli_run.h"
#include "tests/support/support.h"

using namespace polydec;
namespace fs = std::filesystem;

namespace test_cli_volume_geodesics {
namespace {

// The SCALARS array NAME of a VTK file's POINT_DATA section.
Eigen::VectorXd vtk_point_data(const std::string& path, const std::string& name, int n) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line == "SCALARS " + name + " double 1") break;
  std::getline(in, line);  // LOOKUP_TABLE default
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) in >> v[i];
  REQUIRE(in);
  return v;
}

}  // namespace

TEST_CASE("polydec geodesics on a volume mesh", "[volume-cli]") {
  const test::ScratchDir scratch("cli_volgeo");
  const VolumeMesh mesh = hex_grid_volume(4, 3, 3, {0.2, 4});
  const std::string file = scratch.path("grid.vtk");
  write_volume_mesh(mesh, file);
  for (const std::string method : {"ours", "polylaplace"}) {
    const auto r =
        test::run_cli_in(scratch.dir, "geodesics '" + file + "' --source 0 --source 7 --laplacian " + method +
                                          " --euclidean --json --out '" + scratch.path("d.vtk") +
                                          "' --png '" + scratch.path("d.png") + "'");
    INFO(r.err);
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    const HeatGeodesics heat(build_volume_operators(mesh, parse_volume_laplacian(method)),
                             mesh.mean_edge_length());
    const Eigen::VectorXd d = heat.distance(std::vector<int>{0, 7});
    CHECK(j["laplacian"] == method);
    CHECK(j["cells"] == mesh.n_cells());
    CHECK(j["time_step"].get<double>() == Approx(heat.time_step()).epsilon(1e-14));
    CHECK(j["max"].get<double>() == Approx(d.maxCoeff()).epsilon(1e-10));
    CHECK(j["unreached"] == 0);
    CHECK(j.contains("rmse_vs_euclidean"));
    // The VTK file reads back as the mesh and carries the distances.
    CHECK(read_volume_mesh(scratch.path("d.vtk")).n_cells() == mesh.n_cells());
    const Eigen::VectorXd back = vtk_point_data(scratch.path("d.vtk"), "distance", mesh.n_vertices());
    CHECK((back - d).cwiseAbs().maxCoeff() <= 1e-14 * d.maxCoeff());
    CHECK(fs::file_size(scratch.path("d.png")) > 1000);
  }
  // A volume file of another extension with --volume.
  fs::copy_file(file, scratch.path("grid.txt"));
  CHECK(test::run_cli_in(scratch.dir, "geodesics --volume '" + scratch.path("grid.txt") + "' --source 3")
            .code == 0);
  // Refused: a surface method, a source out of range, --out .ply, --engine petsc.
  CHECK(test::run_cli_in(scratch.dir, "geodesics '" + file + "' --source 0 --laplacian cotan").code == 2);
  CHECK(test::run_cli_in(scratch.dir, "geodesics '" + file + "' --source 9999").code == 3);
  CHECK(test::run_cli_in(scratch.dir,
                         "geodesics '" + file + "' --source 0 --out '" + scratch.path("d.ply") + "'")
            .code == 3);
  CHECK(test::run_cli_in(scratch.dir, "geodesics '" + file + "' --source 0 --engine petsc").code == 2);
}

TEST_CASE("polydec spectrum on a volume mesh", "[volume-cli]") {
  const test::ScratchDir scratch("cli_volspec");
  const VolumeMesh mesh = hex_grid_volume(4, 4, 4);
  const std::string file = scratch.path("grid.ovm");
  write_volume_mesh(mesh, file);
  const auto r =
      test::run_cli_in(scratch.dir, "spectrum '" + file + "' --k 5 --mass unlumped --json --out '" +
                                        scratch.path("out") + "' --png '" + scratch.path("u.png") + "'");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  SpectrumOptions sopt;
  sopt.k = 5;
  sopt.lumped_mass = false;
  const Spectrum sp =
      laplacian_spectrum(build_volume_operators(mesh, LaplacianChoice{}, {.with_gradient = false}), sopt);
  REQUIRE(j["eigenvalues"].size() == 5);
  for (int i = 1; i < 5; ++i)
    CHECK(j["eigenvalues"][i].get<double>() == Approx(sp.eigenvalues[i]).epsilon(1e-8));
  // Neumann: lambda_0 = 0; the unit cube's first nonzero eigenvalue pi^2 (three times), within 8% on
  // this 4^3 grid (measured 5.2% above, Galerkin mass).
  CHECK(std::abs(j["eigenvalues"][0].get<double>()) < 1e-8 * sp.eigenvalues[1]);
  for (int i = 1; i <= 3; ++i) CHECK(j["eigenvalues"][i].get<double>() == Approx(M_PI * M_PI).epsilon(0.08));
  CHECK(j["files"] == nlohmann::json({"eigenvalues.txt", "eigenvectors.mtx", "eigenvectors.vtk"}));
  const Eigen::VectorXd u1 = vtk_point_data(scratch.path("out/eigenvectors.vtk"), "u001", mesh.n_vertices());
  CHECK(std::abs(std::abs(u1.dot(sp.eigenvectors.col(1))) - sp.eigenvectors.col(1).squaredNorm()) <
        1e-6 * sp.eigenvectors.col(1).squaredNorm());
  CHECK(fs::file_size(scratch.path("u.png")) > 1000);
  // Form spectra of volumes take degrees 1..3 (test_cli_volume_apps.cpp); others are usage errors.
  CHECK(test::run_cli_in(scratch.dir, "spectrum '" + file + "' --form 4").code == 2);
}

TEST_CASE("polydec render on a volume mesh", "[volume-cli]") {
  const test::ScratchDir scratch("cli_volrender");
  const std::string file = scratch.path("t.ovm");
  write_volume_mesh(truncated_octahedra_volume(2), file);
  const auto r = test::run_cli_in(scratch.dir, "render '" + file + "' --png '" + scratch.path("a.png") +
                                                   "' --distance-from 0 --cut-axis y --json");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["cut_normal"] == nlohmann::json({0.0, 1.0, 0.0}));
  CHECK(fs::file_size(scratch.path("a.png")) > 1000);
  CHECK(test::run_cli_in(scratch.dir, "render '" + file + "' --png '" + scratch.path("b.png") +
                                          "' --scalar x --cut-plane 0.3 0.3 0.3 1 1 1")
            .code == 0);
  // A plane missing the mesh: bad input naming the plane.
  const auto miss = test::run_cli_in(
      scratch.dir, "render '" + file + "' --png '" + scratch.path("c.png") + "' --cut-plane 0 0 5 0 0 1");
  CHECK(miss.code == 2);
  CHECK(miss.err.find("misses the volume mesh") != std::string::npos);
  CHECK(test::run_cli_in(scratch.dir,
                         "render '" + file + "' --png '" + scratch.path("c.png") + "' --cut-axis w")
            .code == 2);
}

TEST_CASE("polydec poisson --volume --laplacian", "[volume-cli]") {
  const test::ScratchDir scratch("cli_volpoisson");
  const auto r =
      test::run_cli_in(scratch.dir, "poisson --volume --resolutions 3 4 --laplacian polylaplace --json");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["laplacian"] == "polylaplace");
  const auto e =
      volume_franke_poisson(hex_grid_volume(4, 4, 4), false, parse_volume_laplacian("polylaplace"));
  CHECK(j["levels"][1]["l2_error"].get<double>() == Approx(e.l2_error).epsilon(1e-10));
  CHECK(test::run_cli_in(scratch.dir, "poisson --volume --resolutions 3 4 --laplacian aw11:0.5").code == 2);
}

}  // namespace test_cli_volume_geodesics
