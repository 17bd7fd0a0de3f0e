// tests/apps/cli/test_cli_quadratic.cpp — `--order 2` on the command line: `polydec operators` writes
// the library's quadratic S, M, HRZ-lumped M, P and one dofs.txt line per vertex and edge;
// `polydec poisson --order 2 --json` reports L2 and H1 slopes for four families; `polydec
// spectrum --order 2` gives the library's quadratic eigenvalues; refused combinations exit 2.
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>

#include "polydec/apps/applications/quadratic.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/mesh/generators.h"
#include "tests/apps/cli/cli_run.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_cli_quadratic {
using polydec::test::relative_difference;

TEST_CASE("polydec operators --order 2", "[quadratic][cli]") {
  test::ScratchDir s("cli_quadratic");
  write_mesh(s.path("hex.obj"), hex_grid(3, 4));
  const Mesh mesh = read_mesh(s.path("hex.obj"));
  const test::CliRun r = test::run_cli_in(
      s.dir, "operators " + s.path("hex.obj") + " --order 2 --out " + s.path("q") + " --json");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  const int nd = mesh.n_vertices() + mesh.n_edges();
  CHECK(j["dofs"] == nd);
  const Refinement R = refine(mesh);
  const QuadraticLaplacian Q = assemble_quadratic_laplacian(mesh, R);
  CHECK(relative_difference(read_matrix_market(s.path("q/S.mtx")), Q.S) < 1e-14);
  CHECK(relative_difference(read_matrix_market(s.path("q/M.mtx")), Q.M) < 1e-14);
  CHECK((SparseMatrix(read_matrix_market(s.path("q/M_lumped.mtx"))).diagonal() - Q.M_lumped).norm() <=
        1e-14 * Q.M_lumped.norm());
  CHECK(relative_difference(read_matrix_market(s.path("q/P.mtx")), quadratic_prolongation(mesh, R)) < 1e-14);
  std::ifstream dofs(s.path("q/dofs.txt"));
  int lines = 0;
  double worst = 0;
  for (double x, y, z; dofs >> x >> y >> z; ++lines)
    if (lines < nd) worst = std::max(worst, (Eigen::RowVector3d(x, y, z) - Q.dofs.row(lines)).norm());
  CHECK(lines == nd);
  CHECK(worst == 0.0);
  // Refused: order 3, --repeat, volumes.
  CHECK(test::run_cli_in(s.dir, "operators " + s.path("hex.obj") + " --order 3 --out " + s.path("x")).code ==
        2);
  CHECK(test::run_cli_in(s.dir, "operators " + s.path("hex.obj") + " --order 2 --repeat 2").code == 2);
}

TEST_CASE("polydec poisson --order 2 --json and spectrum --order 2", "[quadratic][cli]") {
  test::ScratchDir s("cli_quadratic_apps");
  const test::CliRun r = test::run_cli_in(s.dir, "poisson --order 2 --resolutions 4 8 --json");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  for (const char* family : {"triangles", "quads", "hexagons", "non-convex"}) {
    INFO(family);
    REQUIRE(j["families"].contains(family));
    CHECK(j["families"][family]["levels"].size() == 2);
    CHECK(j["families"][family]["l2_slope"].get<double>() > 2.0);
    CHECK(j["families"][family]["h1_slope"].get<double>() > 1.0);
  }
  CHECK(test::run_cli_in(s.dir, "poisson --order 2 --mass lumped").code == 2);

  write_mesh(s.path("sphere.obj"), hex_sphere(1));
  const test::CliRun sp =
      test::run_cli_in(s.dir, "spectrum " + s.path("sphere.obj") + " --order 2 --k 5 --json");
  REQUIRE(sp.code == 0);
  const auto js = nlohmann::json::parse(sp.out);
  SpectrumOptions o;
  o.k = 5;
  const Spectrum ref = quadratic_spectrum(read_mesh(s.path("sphere.obj")), o);
  for (int i = 1; i < 5; ++i)
    CHECK(std::abs(js["eigenvalues"][size_t(i)].get<double>() - ref.eigenvalues[i]) <=
          1e-8 * ref.eigenvalues[i]);
  CHECK(test::run_cli_in(s.dir, "spectrum " + s.path("sphere.obj") + " --order 2 --form 1").code == 2);
}

}  // namespace test_cli_quadratic
