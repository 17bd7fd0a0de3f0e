// tests/apps/cli/test_cli_feec.cpp — `polydec dec` and `polydec hodge`: files written match the
// library's matrices and cell lists; norms printed; bad input mapped to exit codes.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "polydec/apps/applications/hodge_decomposition.h"
#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/hodge_star.h"
#include <sstream>
#include "tests/apps/cli/cli_run.h"
#include "tests/support/feec_meshes.h"

using namespace polydec;

namespace test_cli_feec {

TEST_CASE("polydec dec writes the FEEC matrices and cell lists in matrix order", "[feec]") {
  const test::ScratchDir scratch("feec_dec");
  const std::string dir = scratch.dir.string();
  const Mesh mesh = test::torus(8, 6, 0.1, true);
  write_mesh(dir + "/torus.obj", mesh);
  const test::CliRun r = test::run_cli_in(dir, "dec " + dir + "/torus.obj --out " + dir + "/out --json");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  const Mesh m = read_mesh(dir + "/torus.obj");  // positions as written (17 digits)
  const Refinement ref = refine(m);
  const CoarseComplex K(m);
  const HodgeStars H = hodge_stars(m, ref, K);
  CHECK(j["pairs"] == K.n_pairs());
  CHECK(j["rank_star1"].get<int>() < K.n_pairs());  // hexagons: singular star1
  CHECK(test::relative_difference(read_matrix_market(dir + "/out/d0.mtx"), K.d0()) == 0.0);
  CHECK(test::relative_difference(read_matrix_market(dir + "/out/d1.mtx"), K.d1()) == 0.0);
  CHECK(test::relative_difference(read_matrix_market(dir + "/out/star1.mtx"), H.star1) <= 1e-15);
  CHECK(test::relative_difference(read_matrix_market(dir + "/out/star2.mtx"), H.star2) <= 1e-15);
  CHECK(test::relative_difference(read_matrix_market(dir + "/out/star0.mtx"), H.star0) <= 1e-15);
  for (const char* f : {"P0.mtx", "P1.mtx", "P2.mtx"}) CHECK(std::filesystem::exists(dir + "/out/" + f));
  std::ifstream edges(dir + "/out/edges.txt"), tris(dir + "/out/triangles.txt");
  for (int p = 0; p < K.n_pairs(); ++p) {
    int a = -1, b = -1;
    edges >> a >> b;
    REQUIRE((a == K.pairs()(p, 0) && b == K.pairs()(p, 1)));
  }
  for (int t = 0; t < K.n_triples(); ++t) {
    int a = -1, b = -1, c = -1;
    tris >> a >> b >> c;
    REQUIRE((a == K.triples()(t, 0) && b == K.triples()(t, 1) && c == K.triples()(t, 2)));
  }
}

TEST_CASE("polydec hodge decomposes a given 1-form and reports its norms", "[feec]") {
  const test::ScratchDir scratch("feec_hodge");
  const std::string dir = scratch.dir.string();
  const Mesh mesh = test::torus(10, 6, 0.1, false);
  write_mesh(dir + "/torus.obj", mesh);
  const Mesh m = read_mesh(dir + "/torus.obj");
  const HodgeDecomposer hd(m);
  // A form with all three parts: gradient of z, a harmonic form, a 1-cell bump.
  Eigen::VectorXd omega = hd.d0() * m.positions().col(2) + 0.5 * hd.harmonic_basis().col(0);
  omega[3] += 0.2;
  {
    std::ofstream f(dir + "/form.txt");
    f << "# test form\n";
    for (long p = 0; p < omega.size(); ++p) f << fmt::format("{:.17g}\n", omega[p]);
  }
  const HodgeParts expect = hd.decompose(omega);
  const test::CliRun r = test::run_cli_in(
      dir, "hodge " + dir + "/torus.obj --form " + dir + "/form.txt --json --out " + dir + "/parts.txt");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["harmonic_dimension"] == 2);
  CHECK(j["norm_exact"].get<double>() == Approx(expect.norm_exact).epsilon(1e-9));
  CHECK(j["norm_coexact"].get<double>() == Approx(expect.norm_coexact).epsilon(1e-9));
  CHECK(j["norm_harmonic"].get<double>() == Approx(expect.norm_harmonic).epsilon(1e-9));
  CHECK(expect.norm_coexact > 0);
  // The parts file: one line per pair, the parts sum to omega.
  std::ifstream parts(dir + "/parts.txt");
  std::string line;
  std::getline(parts, line);
  for (long p = 0; p < omega.size(); ++p) {
    int a, b;
    double w, e, c, h;
    parts >> a >> b >> w >> e >> c >> h;
    REQUIRE(w == Approx(omega[p]).margin(1e-15));
    REQUIRE(e + c + h == Approx(w).margin(1e-12));
  }
  // The built-in form runs too and has all three parts on a torus.
  const test::CliRun b = test::run_cli_in(dir, "hodge " + dir + "/torus.obj --json");
  REQUIRE(b.code == 0);
  const auto jb = nlohmann::json::parse(b.out);
  CHECK(jb["norm_exact"].get<double>() > 0);
  CHECK(jb["norm_coexact"].get<double>() > 0);
  CHECK(jb["norm_harmonic"].get<double>() > 0);
  // Bad input: wrong number of values (3), garbage (3), missing mesh (3), bad option (2).
  {
    std::ofstream f(dir + "/short.txt");
    f << "1\n2\n";
  }
  {
    std::ofstream f(dir + "/garbage.txt");
    f << "1\nabc\n";
  }
  CHECK(test::run_cli_in(dir, "hodge " + dir + "/torus.obj --form " + dir + "/short.txt").code == 3);
  CHECK(test::run_cli_in(dir, "hodge " + dir + "/torus.obj --form " + dir + "/garbage.txt").code == 3);
  CHECK(test::run_cli_in(dir, "hodge " + dir + "/missing.obj").code == 3);
  CHECK(test::run_cli_in(dir, "hodge " + dir + "/torus.obj --noise -1").code == 2);
}

TEST_CASE("polydec dec, hodge and spectrum on the mesh complex", "[feec][mesh-complex]") {
  const test::ScratchDir scratch("feec_mesh_complex");
  const std::string dir = scratch.dir.string();
  write_mesh(dir + "/torus.obj", test::torus(8, 6, 0.1, true));
  const Mesh m = read_mesh(dir + "/torus.obj");
  const test::CliRun r = test::run_cli_in(dir, "dec " + dir + "/torus.obj --complex mesh --out " + dir + "/out --json");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["complex"] == "mesh");
  CHECK(j["edges"] == m.n_edges());
  CHECK(j["times_ms"]["operators"].get<double>() >= 0);
  const SurfaceDec D = surface_dec(m, refine(m), {.complex = DecComplex::Mesh});
  CHECK(test::relative_difference(read_matrix_market(dir + "/out/d0.mtx"), D.d[0]) == 0.0);
  CHECK(test::relative_difference(read_matrix_market(dir + "/out/d1.mtx"), D.d[1]) == 0.0);
  for (int k = 0; k < 3; ++k) {
    CHECK(test::relative_difference(read_matrix_market(dir + fmt::format("/out/star{}.mtx", k)), D.star[k]) <= 1e-15);
    CHECK(test::relative_difference(read_matrix_market(dir + fmt::format("/out/P{}.mtx", k)), D.P[k]) <= 1e-15);
  }
  std::ifstream edges(dir + "/out/edges.txt"), faces(dir + "/out/faces.txt");
  for (int e = 0; e < m.n_edges(); ++e) {
    int a = -1, b = -1;
    edges >> a >> b;
    REQUIRE((a == m.edges()(e, 0) && b == m.edges()(e, 1)));
  }
  for (int f = 0; f < m.n_faces(); ++f) {
    std::string line;
    std::getline(faces, line);
    std::string expect;
    for (int v : m.face(f)) {
      if (!expect.empty()) expect += ' ';
      expect += std::to_string(v);
    }
    REQUIRE(line == expect);
  }
  // The Hodge decomposition of the built-in form on the mesh's edges: harmonic dimension 2.
  const test::CliRun h = test::run_cli_in(dir, "hodge " + dir + "/torus.obj --complex mesh --json");
  REQUIRE(h.code == 0);
  const auto jh = nlohmann::json::parse(h.out);
  CHECK(jh["harmonic_dimension"] == 2);
  CHECK(jh["edges"] == m.n_edges());
  // 1-form spectrum: two harmonic forms on the torus, the cochains on the edges.
  const test::CliRun s =
      test::run_cli_in(dir, "spectrum " + dir + "/torus.obj --form 1 --k 4 --complex mesh --json --out " + dir + "/sp");
  REQUIRE(s.code == 0);
  const auto js = nlohmann::json::parse(s.out);
  CHECK(js["cells"] == m.n_edges());
  CHECK(js["eigenpairs"][0]["kind"] == "harmonic");
  CHECK(js["eigenpairs"][1]["kind"] == "harmonic");
  CHECK(std::filesystem::exists(dir + "/sp/edges.txt"));
  // Bad choices are usage errors (exit 2).
  CHECK(test::run_cli_in(dir, "dec " + dir + "/torus.obj --complex full --out " + dir + "/x").code == 2);
  CHECK(test::run_cli_in(dir, "dec " + dir + "/torus.obj --complex mesh --spoke-rule x --out " + dir + "/x").code == 2);
  CHECK(test::run_cli_in(dir, "hodge " + dir + "/torus.obj --complex full").code == 2);
}

TEST_CASE("polydec dec --complex mesh on a volume mesh: every degree, cells with their orientations",
          "[feec][volume-mesh-complex]") {
  const test::ScratchDir scratch("feec_volume_mesh_complex");
  const std::string dir = scratch.dir.string();
  write_volume_mesh(truncated_octahedra_volume(2), dir + "/octahedra.ovm");
  const VolumeMesh m = read_volume_mesh(dir + "/octahedra.ovm");
  const test::CliRun r =
      test::run_cli_in(dir, "dec " + dir + "/octahedra.ovm --complex mesh --out " + dir + "/out --json");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["max_degree"] == 3);  // 24-vertex cells: the complete complex stops at degree 1
  CHECK(j["cells"] == m.n_cells());
  const VolumeDec D =
      volume_dec(m, refine_volume(m), VolumeDecOptions{.max_degree = 3, .complex = DecComplex::Mesh});
  for (int k = 0; k < 3; ++k)
    CHECK(test::relative_difference(read_matrix_market(dir + fmt::format("/out/d{}.mtx", k)), D.d[k]) == 0.0);
  for (int k = 0; k <= 3; ++k) {
    CHECK(test::relative_difference(read_matrix_market(dir + fmt::format("/out/star{}.mtx", k)), D.star[k]) <= 1e-15);
    CHECK(test::relative_difference(read_matrix_market(dir + fmt::format("/out/P{}.mtx", k)), D.P[k]) <= 1e-15);
  }
  // cells.txt: the half-faces of each cell; d2 has +1 for an even one, -1 for an odd one.
  std::ifstream cells(dir + "/out/cells.txt");
  for (int c = 0; c < m.n_cells(); ++c) {
    std::string line;
    std::getline(cells, line);
    std::istringstream in(line);
    int h = 0, count = 0;
    while (in >> h) {
      CHECK(D.d[2].coeff(c, h / 2) == (h % 2 == 0 ? 1.0 : -1.0));
      ++count;
    }
    CHECK(count == m.cell_size(c));
  }
}

}  // namespace test_cli_feec
