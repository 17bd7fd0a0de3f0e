// tests/apps/paper/test_volume_tables.cpp — the paper report's Volumes section (apps/paper/volume_tables.h)
// on its quick settings: every cube family and level present, slopes consistent with the errors and h,
// the ball's eigenvalue errors falling with n, and the Markdown section rendered from the results.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "polydec/apps/paper/volume_tables.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_tables {

TEST_CASE("volume_tables --quick: Poisson rows and slopes, ball errors, the report section",
          "[paper][volume-paper]") {
  POLYDEC_SHARED_MESH(cube, "volume/cube_hexahedron_1.ovm");
  const std::string data = std::filesystem::path(cube).parent_path().parent_path().string();
  const nlohmann::json v = volume_tables(data, true);
  for (const char* method : {"ours", "diamond"})
    for (const char* mass : {"galerkin", "lumped"})
      for (const char* family : {"hex", "pyramids", "truncated", "tetrahedra"}) {
        INFO(method << " " << mass << " " << family);
        const auto& rows = v["poisson"][method][mass][family];
        REQUIRE(rows.size() == (std::string(family) == "tetrahedra" ? 2u : 3u));
        for (size_t i = 1; i < rows.size(); ++i) {
          const double e0 = rows[i - 1]["l2_error"], e1 = rows[i]["l2_error"], h0 = rows[i - 1]["h"],
                       h1 = rows[i]["h"];
          CHECK(h1 < h0);
          if (e0 > 0) {
            const double slope = std::log(e1 / e0) / std::log(h1 / h0);
            CHECK(std::abs(rows[i]["l2_slope"].get<double>() - slope) <
                  1e-12 * std::max(1.0, std::abs(slope)));
          } else {
            CHECK(rows[i]["l2_slope"].is_null());  // level 1 of the truncated cube has no interior vertex
          }
        }
      }
  // The Galerkin errors fall from level to level on the hexahedral cube (docs/volumes.md).
  for (const char* method : {"ours", "diamond"}) {
    const auto& hex = v["poisson"][method]["galerkin"]["hex"];
    CHECK(hex[2]["l2_error"].get<double>() < hex[1]["l2_error"].get<double>());
  }
  // Two methods: different operators, different errors on the same meshes.
  CHECK(v["poisson"]["ours"]["galerkin"]["hex"][2]["l2_error"] !=
        v["poisson"]["diamond"]["galerkin"]["hex"][2]["l2_error"]);
  for (const char* bc : {"dirichlet", "neumann"}) {
    INFO(bc);
    const auto& runs = v["ball"][bc];
    REQUIRE(runs.size() == 2);
    CHECK(runs[1]["max_error"].get<double>() < runs[0]["max_error"].get<double>());
    CHECK(runs[1]["max_error"].get<double>() < 0.2);
    CHECK(runs[1]["eigenvalues"].size() == 10);
  }
  nlohmann::json results;
  const std::string absent = volume_tables_markdown(results);
  CHECK(absent.find("(not run)") != std::string::npos);
  results["volumes"] = v;
  const std::string md = volume_tables_markdown(results);
  CHECK(md.find("## Volumes") != std::string::npos);
  CHECK(md.find("cube_truncated_3.ovm") != std::string::npos);
  CHECK(md.find("| dirichlet | 8 |") != std::string::npos);
}

}  // namespace test_volume_tables
