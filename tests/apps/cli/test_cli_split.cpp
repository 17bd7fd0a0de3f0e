// tests/apps/cli/test_cli_split.cpp — several virtual vertices per face on the command line: `polydec
// operators --virtual-vertex split` writes the library's split S, M, lumped M, G, D, P with the fan
// diagnostics; `polydec poisson --family sawtooth --laplacian split --json`; refused combinations exit 2.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/mesh/sawtooth_grid.h"
#include "polydec/operators/surface/split_laplacian.h"
#include "tests/apps/cli/cli_run.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_cli_split {
using polydec::test::relative_difference;

TEST_CASE("polydec operators --virtual-vertex split and poisson --family sawtooth", "[split][cli]") {
  test::ScratchDir s("cli_split");
  write_mesh(s.path("saw.obj"), sawtooth_grid(3, 3));
  const Mesh mesh = read_mesh(s.path("saw.obj"));
  const test::CliRun r = test::run_cli_in(
      s.dir, "operators " + s.path("saw.obj") + " --virtual-vertex split --out " + s.path("o") + " --json");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  const SplitLaplacian L = split_laplacian(mesh);
  CHECK(j["faces_split"] == 6);
  CHECK(j["pieces"] == L.split.n_pieces());
  CHECK(j["fan_inverted_before"].get<int>() > 0);
  CHECK(j["fan_inverted"] == 0);
  CHECK(j["fan_degenerate"] == 0);
  for (const auto& [file, A] : {std::pair<const char*, const SparseMatrix*>{"S.mtx", &L.S}, {"M.mtx", &L.M},
                                {"G.mtx", &L.G}, {"D.mtx", &L.D}, {"P.mtx", &L.P}}) {
    INFO(file);
    CHECK(relative_difference(read_matrix_market(s.path(std::string("o/") + file)), *A) < 1e-14);
  }
  CHECK((SparseMatrix(read_matrix_market(s.path("o/M_lumped.mtx"))).diagonal() - L.M_lumped).norm() <=
        1e-14 * L.M_lumped.norm());
  CHECK(test::run_cli_in(s.dir, "operators " + s.path("saw.obj") + " --virtual-vertex split --order 2 --out " +
                                    s.path("x"))
            .code == 2);
  CHECK(test::run_cli_in(s.dir, "operators " + s.path("saw.obj") + " --virtual-vertex split --virtual-lift quadric --out " +
                                    s.path("x"))
            .code == 2);
  const test::CliRun p = test::run_cli_in(s.dir, "poisson --family sawtooth --laplacian split --resolutions 4 8 --json");
  REQUIRE(p.code == 0);
  const auto q = nlohmann::json::parse(p.out);
  REQUIRE(q["families"].contains("sawtooth"));
  CHECK(q["families"].size() == 1);
  CHECK(q["laplacian"] == "split");
  CHECK(q["families"]["sawtooth"]["levels"].size() == 2);
}

}  // namespace test_cli_split
