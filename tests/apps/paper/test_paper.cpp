// tests/apps/paper/test_paper.cpp — `polydec paper --quick`: the files it writes, ours within 1% of the
// authors' program, every baseline within 10% of the paper's printed value except the documented
// cells (docs/paper.md), and one cell of each table recomputed through the library directly.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "polydec/apps/applications/curvature.h"
#include "polydec/apps/applications/geodesics.h"
#include "polydec/apps/paper/paper.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/operators/registry/laplacians.h"
#include "tests/support/support.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace test_paper {

namespace {

struct PaperRun {
  int code = -1;
  fs::path dir;
  json results;
  std::string report, err;  // report.md, the program's stderr
};

std::string slurp(const fs::path& path) {
  std::stringstream ss;
  ss << std::ifstream(path).rdbuf();
  return ss.str();
}

// One quick run of the CLI per test binary (it takes seconds), kept for every test case; its output
// (folder out) and stderr (stderr.txt) in polydec_paper_test_PID, removed when the process exits.
const PaperRun& paper_run(const std::string& data) {
  static const polydec::test::ScratchDir scratch("paper_test");
  static const PaperRun r = [&] {
    PaperRun p;
    p.dir = scratch.dir / "out";
    const std::string cmd = std::string("'") + POLYDEC_CLI_PATH + "' paper --quick --data '" + data +
                            "' --out '" + p.dir.string() + "' 2>'" + scratch.path("stderr.txt") + "'";
    const int status = std::system(cmd.c_str());
    p.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream j(p.dir / "results.json");
    if (j) p.results = json::parse(j, nullptr, false);
    p.report = slurp(p.dir / "report.md");
    p.err = slurp(scratch.path("stderr.txt"));
    return p;
  }();
  return r;
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

}  // namespace

// One test case (three sections) for one run of the CLI: ctest starts each test case in its own process.
TEST_CASE("polydec paper --quick: report and pictures written, cells agree with the authors' program, the paper "
          "and the library",
          "[paper][cli]") {
  POLYDEC_SHARED_MESH(sphere, "quad-sphere.off");
  const PaperRun& r = paper_run(fs::path(sphere).parent_path().string());
  if (r.code != 0) FAIL("polydec paper exited with code " << r.code << ", its stderr:\n" << r.err);
  REQUIRE(r.results.is_object());
  SECTION("the report, the results and the pictures are written") {
    for (const char* t : {"table1", "table2", "table3", "table4", "table6", "figure9", "figure7", "figure8"})
      CHECK(r.results.contains(t));
    CHECK(!r.results.contains("table5"));  // --quick leaves the timings out
    // The phases' times; the steps' times add up to at most the evaluation's (they do not overlap).
    REQUIRE(r.results["times_ms"].is_object());
    const json& t = r.results["times_ms"];
    REQUIRE(t.contains("evaluation"));
    REQUIRE(t.contains("write"));
    CHECK(t["total"].get<double>() >= t["evaluation"].get<double>() + t["write"].get<double>() - 2e-3);
    double steps = 0;
    for (const auto& [label, ms] : r.results["step_times_ms"].items()) {
      INFO(label);
      CHECK(ms.get<double>() >= 0);
      steps += ms.get<double>();
    }
    CHECK(r.results["step_times_ms"].size() >= 10);
    CHECK(steps <= t["evaluation"].get<double>() + 1e-3);
    CHECK(r.results["table2"]["REGULAR SPHERE"].size() >= 13);
    CHECK(r.results["table6"]["L-SHAPED"].contains("centroid-unlumped"));
    for (const char* h : {"## Table 1", "## Table 2", "## Table 3", "## Table 4", "## Table 5", "## Table 6",
                          "## Figure 9", "## Figures 7 and 8"})
      CHECK(r.report.find(h) != std::string::npos);
    for (const char* f : {"figure7-geodesics.png", "figure8-geodesics.png", "figure9.svg", "figure9.png",
                          "figure9-hexagons.svg"}) {
      INFO(f);
      REQUIRE(fs::exists(r.dir / f));
      CHECK(fs::file_size(r.dir / f) > 2000);
    }
  }
  SECTION("ours within 1% of the authors' program, baselines within 10% of the paper") {
    const json& a = r.results["authors_program"];
    int compared = 0;
    for (const auto& [t, meshes] : a.items())
      for (const auto& [mesh, cells] : meshes.items())
        for (const auto& [m, v] : cells.items()) {
          if (!r.results[t].contains(mesh)) continue;  // HEX / FINE SPHERE are not in the quick run
          INFO(t << " " << mesh << " " << m);
          CHECK(rel(r.results[t][mesh][m].get<double>(), v.get<double>()) <= 0.01);
          ++compared;
        }
    CHECK(compared >= 10);

    // Cells outside 10% of the paper's printed value, each explained in docs/paper.md. The test fails
    // when one more cell deviates, and also when one of these comes back in line (update the list and
    // the explanation then).
    const std::set<std::string> documented = {
        "table4/L-SHAPED/aw11:1",                   "table4/TETRIS 1/ours",
        "table6/TETRIS 1/ours",                     "table6/L-SHAPED/convex",
        "table6/L-SHAPED/convex-unlumped",          "table6/TETRIS 2/convex-unlumped",
        "table6/L-SHAPED/abs-area-unlumped",        "table6/TETRIS 2/abs-area-unlumped"};
    std::set<std::string> outside;
    int checked = 0;
    for (const char* t : {"table2", "table3", "table4", "table6"})
      for (const auto& [mesh, cells] : r.results["paper"][t].items())
        for (const auto& [m, v] : cells.items()) {
          if (!r.results[t].contains(mesh)) continue;
          REQUIRE(r.results[t][mesh].contains(m));
          ++checked;
          if (rel(r.results[t][mesh][m].get<double>(), v.get<double>()) > 0.10)
            outside.insert(std::string(t) + "/" + mesh + "/" + m);
        }
    CHECK(checked >= 80);
    CHECK(outside == documented);
  }
  SECTION("cells recomputed through the library agree") {
    POLYDEC_SHARED_MESH(plane, "quad-plane.obj");
    // Table 2, REGULAR SPHERE, Galerkin mass, ours.
    const polydec::Mesh s = polydec::project_to_unit_sphere(polydec::read_mesh(sphere));
    polydec::CurvatureOptions c;
    c.lumped_mass = false;
    const double h = polydec::curvature_rmse(polydec::mean_curvature(s, c), 1.0);
    CHECK(r.results["table2"]["REGULAR SPHERE"]["ours-unlumped"].get<double>() == Approx(h).epsilon(1e-12));
    // Table 4, QUADS 2, AW11 with lambda 0.5.
    const polydec::Mesh q = polydec::read_mesh(plane);
    const polydec::HeatGeodesics heat(polydec::build_operators(q, polydec::parse_laplacian("aw11:0.5")),
                                      q.mean_edge_length());
    Eigen::VectorXd e(q.n_vertices());
    for (int v = 0; v < q.n_vertices(); ++v) e[v] = (q.position(v) - q.position(0)).norm();
    CHECK(r.results["table4"]["QUADS 2"]["aw11:0.5"].get<double>() ==
          Approx(polydec::rmse(heat.distance(0), e)).epsilon(1e-12));
    // Figure 9: second-order convergence of ours on the three families (the paper's claim).
    for (const char* family : {"triangles", "quads", "hexagons"}) {
      INFO(family);
      const double slope = r.results["figure9"][family]["ours"].get<double>();
      CHECK(slope >= 1.8);
      CHECK(slope <= 2.3);
    }
    // Intrinsic Delaunay has no negative off-diagonals on a closed mesh (section 5.5: 0%).
    CHECK(r.results["figure7"]["amo_quad.off"]["intrinsic-delaunay"].get<double>() == 0.0);
    CHECK(r.results["figure7"]["amo_quad.off"]["ours"].get<double>() <
          r.results["figure7"]["amo_quad.off"]["aw11:0.5"].get<double>());
  }
}

}  // namespace test_paper
