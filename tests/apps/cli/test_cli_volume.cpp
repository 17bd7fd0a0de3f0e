// tests/apps/cli/test_cli_volume.cpp — `polydec info` and `polydec convert` on volume meshes:
// the JSON report against the mesh's own numbers, conversions between the volume formats and
// to the boundary surface, usage and bad-input exit codes; gmsh files (groups and skipped elements
// in `info`, `geodesics --source-group`, `convert` to .msh and back; each command reads a .msh or
// .vtu file as the kind it holds, and names a broken one's file and line).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "polydec/apps/applications/volume/hodge_decomposition.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/mesh_groups.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "tests/apps/cli/cli_run.h"
#include "tests/support/support.h"

using namespace polydec;
namespace fs = std::filesystem;

namespace test_cli_volume {

namespace {

using Run = test::CliRun;

Run run(const fs::path& dir, const std::string& args) { return test::run_cli_in(dir, args); }

struct Scratch : test::ScratchDir {
  Scratch() : ScratchDir("cli_volume") {}
};

}  // namespace

TEST_CASE("polydec info on volume meshes", "[volume][cli]") {
  Scratch s;
  write_volume_mesh(hex_grid_volume(2, 3, 2), s.path("hex.ovm"));
  Run r = run(s.dir, "info " + s.path("hex.ovm") + " --json");
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["kind"] == "volume");
  CHECK(j["vertices"] == 3 * 4 * 3);
  CHECK(j["cells"] == 12);
  CHECK(j["cell_shapes"]["hexahedron"] == 12);
  CHECK(j["cell_shapes"]["other"] == 0);
  CHECK(j["volume"].get<double>() == Approx(1.0));
  CHECK(j["min_cell_volume"].get<double>() == Approx(1.0 / 12));
  CHECK(j["euler_characteristic"] == 1);
  CHECK(j["boundary_faces"] == 2 * (2 * 3 + 3 * 2 + 2 * 2));
  CHECK(j["boundary_euler_characteristic"] == 2);
  CHECK(j["boundary_vertices"] == 3 * 4 * 3 - 2);
  CHECK(j["max_nonplanarity"].get<double>() < 1e-14);

  // Jittered pyramids through VTK: non-planar faces are reported, relative to the face size.
  const VolumeMesh p = pyramid_grid_volume(2, 2, 2, {0.3, 1});
  write_volume_mesh(p, s.path("pyr.vtk"));
  r = run(s.dir, "info " + s.path("pyr.vtk") + " --json");
  REQUIRE(r.code == 0);
  j = nlohmann::json::parse(r.out);
  CHECK(j["cell_shapes"]["pyramid"] == 48);
  CHECK(j["volume"].get<double>() == Approx(1.0));
  CHECK(j["nonplanar_faces"].get<int>() > 0);
  CHECK(j["max_nonplanarity"].get<double>() < 0.3);

  // --volume reads a file of any name by its first word; the text report.
  fs::copy_file(s.path("hex.ovm"), s.path("hex.txt"));
  r = run(s.dir, "info --volume " + s.path("hex.txt"));
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("12 hexahedra") && Catch::Contains("Euler characteristic 2"));

  // Shared data: the truncated-octahedra cube.
  const std::string cube = test::shared_path("volume/cube_truncated_1.ovm");
  if (!cube.empty()) {
    r = run(s.dir, "info " + cube + " --json");
    REQUIRE(r.code == 0);
    j = nlohmann::json::parse(r.out);
    CHECK(j["cells"] == 9);
    CHECK(j["volume"].get<double>() == Approx(1.0));
    CHECK(j["cell_shapes"]["other"].get<int>() >= 1);
  }
}

TEST_CASE("polydec convert between volume formats and to the boundary", "[volume][cli]") {
  Scratch s;
  const VolumeMesh m = tet_grid_volume(2, 2, 2, {0.2, 3});
  write_volume_mesh(m, s.path("t.ovm"));
  Run r = run(s.dir, "convert " + s.path("t.ovm") + " " + s.path("t.vtk") + " --json");
  REQUIRE(r.code == 0);
  CHECK(nlohmann::json::parse(r.out)["cells"] == 48);
  r = run(s.dir, "convert " + s.path("t.vtk") + " " + s.path("t.mesh"));
  REQUIRE(r.code == 0);
  const VolumeMesh back = read_volume_mesh(s.path("t.mesh"));
  CHECK(back.positions() == m.positions());
  CHECK(back.n_cells() == m.n_cells());
  CHECK(back.volume() == Approx(m.volume()).epsilon(1e-14));

  r = run(s.dir, "convert " + s.path("t.ovm") + " " + s.path("b.off") + " --boundary");
  REQUIRE(r.code == 0);
  const Mesh b = read_mesh(s.path("b.off"));
  CHECK(b.n_faces() == 2 * 4 * 6);
  CHECK(b.n_boundary_edges() == 0);
  CHECK(b.n_vertices() - b.n_unreferenced_vertices() - b.n_edges() + b.n_faces() == 2);

  // Usage errors (exit 2) and bad input (exit 3, naming file and line).
  CHECK(run(s.dir, "convert " + s.path("t.ovm") + " " + s.path("x.off")).code == 2);
  CHECK(run(s.dir, "convert " + s.path("t.ovm") + " " + s.path("x.vtk") + " --boundary").code == 2);
  CHECK(run(s.dir, "convert " + s.path("t.ovm") + " " + s.path("x.vtk") + " --dual").code == 2);
  CHECK(run(s.dir, "convert " + s.path("b.off") + " " + s.path("x.off") + " --boundary").code == 2);
  std::ofstream(s.path("bad.ovm")) << "OVM ASCII\nVertices\n1\n0 0\nEdges\n0\n";
  r = run(s.dir, "info " + s.path("bad.ovm"));
  CHECK(r.code == 3);
  CHECK_THAT(r.err, Catch::Contains(s.path("bad.ovm") + ":4: a vertex needs 3 coordinates"));
}

namespace {

std::string msh_fixture(const std::string& name) { return std::string(POLYDEC_TEST_DATA) + "/msh/" + name; }

}  // namespace

TEST_CASE("polydec info, geodesics --source-group and convert on gmsh files", "[cli][msh]") {
  test::ScratchDir dir("cli_msh");
  const std::string tet = msh_fixture("tet_41_binary.msh");
  const MeshGroups groups = read_mesh_groups(tet);

  test::CliRun r = test::run_cli_in(dir.dir, "info '" + tet + "' --json");
  REQUIRE(r.code == 0);
  nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j["kind"] == "volume");
  CHECK(j["cells"] == 90);
  CHECK(j["volume"].get<double>() == Approx(2.0).epsilon(1e-13));
  CHECK(j["skipped_elements"] == nlohmann::json({{"lines", 2}, {"points", 1}, {"triangles", 14}}));
  CHECK(j["groups"]["left"]["vertices"] == groups.vertices.at("left").size());
  CHECK(j["groups"]["solid"]["cells"] == 90);
  CHECK(j["groups"]["left"]["cells"] == 0);

  r = test::run_cli_in(dir.dir, "info '" + msh_fixture("quad_22_ascii.msh") + "' --json");
  REQUIRE(r.code == 0);
  j = nlohmann::json::parse(r.out);
  CHECK(j["faces"] == 11);
  CHECK(j["groups"]["plate"]["faces"] == 11);
  CHECK(j["skipped_elements"]["lines"] == 2);

  // --source-group edge: the same run as the group's vertices given one by one.
  std::string listed;
  for (int v : groups.vertices.at("edge")) listed += " --source " + std::to_string(v);
  r = test::run_cli_in(dir.dir, "geodesics '" + tet + "' --source-group edge --json");
  REQUIRE(r.code == 0);
  const nlohmann::json by_group = nlohmann::json::parse(r.out);
  r = test::run_cli_in(dir.dir, "geodesics '" + tet + "'" + listed + " --json");
  REQUIRE(r.code == 0);
  const nlohmann::json by_index = nlohmann::json::parse(r.out);
  CHECK(by_group["sources"] == by_index["sources"]);
  CHECK(by_group["sources"].size() == 3);
  CHECK(by_group["max"] == by_index["max"]);
  CHECK(by_group["mean"] == by_index["mean"]);

  r = test::run_cli_in(dir.dir, "geodesics '" + tet + "' --source-group nope");
  CHECK(r.code == 2);
  CHECK(r.err.find("has no group 'nope' (groups 'corner', 'edge', 'left', 'solid')") != std::string::npos);
  r = test::run_cli_in(dir.dir, "geodesics '" + tet + "'");
  CHECK(r.code == 2);
  CHECK(r.err.find("--source V or --source-group NAME") != std::string::npos);

  // MEDIT references: --source-group "ref 5" is the triangle's three vertices.
  {
    const std::string medit = dir.path("refs.mesh");
    std::ofstream(medit) << "MeshVersionFormatted 2\nDimension 3\nVertices\n5\n0 0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
                            "1 1 1 7\nTriangles\n1\n1 2 3 5\nTetrahedra\n2\n1 2 3 4 0\n2 3 4 5 3\nEnd\n";
    r = test::run_cli_in(dir.dir, "geodesics '" + medit + "' --source-group 'ref 5' --json");
    REQUIRE(r.code == 0);
    const nlohmann::json medit_group = nlohmann::json::parse(r.out);
    r = test::run_cli_in(dir.dir, "geodesics '" + medit + "' --source 0 --source 1 --source 2 --json");
    REQUIRE(r.code == 0);
    const nlohmann::json medit_index = nlohmann::json::parse(r.out);
    CHECK(medit_group["sources"] == medit_index["sources"]);
    CHECK(medit_group["max"] == medit_index["max"]);
    // polydec convert writes .meshb.
    r = test::run_cli_in(dir.dir, "convert '" + medit + "' '" + dir.path("refs.meshb") + "'");
    REQUIRE(r.code == 0);
    CHECK(read_volume_mesh(dir.path("refs.meshb")).positions() == read_volume_mesh(medit).positions());
  }

  // convert: a volume .msh to a gmsh 4.1 file and back, a surface to .msh.
  const std::string out = dir.path("out.msh");
  REQUIRE(test::run_cli_in(dir.dir, "convert '" + msh_fixture("prism_22_binary.msh") + "' '" + out + "'").code == 0);
  const VolumeMesh a = read_volume_mesh(msh_fixture("prism_22_binary.msh")), b = read_volume_mesh(out);
  CHECK(a.positions() == b.positions());
  CHECK(a.n_cells() == b.n_cells());
  CHECK(b.volume() == Approx(a.volume()).epsilon(1e-14));
  // The file now exists as a volume; converting a surface over it writes a surface.
  REQUIRE(test::run_cli_in(dir.dir, "convert '" + msh_fixture("tri_22_binary.msh") + "' '" + out + "'").code == 0);
  CHECK(!is_volume_mesh_path(out));
  r = test::run_cli_in(dir.dir, "info '" + out + "' --json");
  REQUIRE(r.code == 0);
  CHECK(nlohmann::json::parse(r.out)["faces"] == 14);
}

TEST_CASE("each command reads a .msh or .vtu file as what it holds, a broken one is named by file and line",
          "[cli][msh]") {
  test::ScratchDir dir("cli_msh_kind");
  write_volume_mesh(hex_grid_volume(2, 2, 2, {0.2, 3}), dir.path("v.vtu"));
  write_mesh(dir.path("s.vtu"), quad_grid(3, 3));
  const std::string tet = msh_fixture("tet_41_ascii.msh"), tri = msh_fixture("tri_22_binary.msh");
  struct Input {
    std::string path;
    bool volume;
    int vertices;
  };
  const Input inputs[] = {{tet, true, 44}, {tri, false, 13}, {dir.path("v.vtu"), true, 27}, {dir.path("s.vtu"), false, 16}};
  for (const Input& in : inputs) {
    INFO(in.path);
    test::CliRun r = test::run_cli_in(dir.dir, "info '" + in.path + "' --json");
    REQUIRE(r.code == 0);
    nlohmann::json j = nlohmann::json::parse(r.out);
    CHECK(j["vertices"] == in.vertices);
    CHECK(j.contains("cells") == in.volume);
    r = test::run_cli_in(dir.dir, "operators '" + in.path + "' --out '" + dir.path("ops") + "' --json");
    REQUIRE(r.code == 0);
    CHECK(read_matrix_market(dir.path("ops") + "/S.mtx").rows() == in.vertices);
    r = test::run_cli_in(dir.dir, "spectrum '" + in.path + "' --k 3 --json");
    REQUIRE(r.code == 0);
    j = nlohmann::json::parse(r.out);
    CHECK(j.contains("cells") == in.volume);
    CHECK(std::abs(j["eigenvalues"][0].get<double>()) < 1e-8);
    r = test::run_cli_in(dir.dir, "geodesics '" + in.path + "' --source 0 --json");
    REQUIRE(r.code == 0);
    r = test::run_cli_in(dir.dir, "convert '" + in.path + "' '" + dir.path(in.volume ? "c.ovm" : "c.obj") + "'");
    REQUIRE(r.code == 0);
    CHECK((in.volume ? read_volume_mesh(dir.path("c.ovm")).n_vertices() : read_mesh(dir.path("c.obj")).n_vertices()) ==
          in.vertices);
    // A surface for --order 2, a volume refused with the usage error.
    r = test::run_cli_in(dir.dir, "operators '" + in.path + "' --order 2 --out '" + dir.path("q") + "'");
    CHECK(r.code == (in.volume ? 2 : 0));
  }
  // A broken surface .msh: every command names the file and the line of the bad token.
  std::ifstream good(msh_fixture("tri_41_ascii.msh"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(good)), {});
  const size_t at = bytes.find("\n2 0 0\n") + 1;
  REQUIRE(at != std::string::npos + 1);
  bytes.replace(at, 5, "2 x 0");
  const long line = 1 + long(std::count(bytes.begin(), bytes.begin() + long(at), '\n'));
  const std::string bad = dir.path("bad.msh");
  std::ofstream(bad, std::ios::binary) << bytes;
  const std::string expected = fmt::format("{}:{}: bad node coordinate 'x'", bad, line);
  for (const std::string& command :
       {"info '" + bad + "'", "operators '" + bad + "' --out '" + dir.path("o") + "'", "spectrum '" + bad + "' --k 2",
        "geodesics '" + bad + "' --source 0", "dec '" + bad + "' --out '" + dir.path("d") + "'", "hodge '" + bad + "'",
        "render '" + bad + "' --png '" + dir.path("p.png") + "'", "convert '" + bad + "' '" + dir.path("x.obj") + "'"}) {
    INFO(command);
    const test::CliRun r = test::run_cli_in(dir.dir, command);
    CHECK(r.code == 3);
    CHECK(r.err.find(expected) != std::string::npos);
  }
}

}  // namespace test_cli_volume

namespace test_cli_volume {

TEST_CASE("polydec operators on volumes far outside the ordinary sizes: results or a refusal naming the file",
          "[volume][cli][volume-scale]") {
  Scratch s;
  const VolumeMesh m = hex_grid_volume(2, 2, 2, {0.2, 5});
  // At 1e63 every entry is representable: S is the unit mesh's times 1e63 (the route before per-cell
  // scaling gave NaN here).
  write_volume_mesh(m.with_positions(m.positions() * 1e63), s.path("big.vtk"));
  write_volume_mesh(m, s.path("unit.vtk"));
  REQUIRE(run(s.dir, "operators " + s.path("big.vtk") + " --out " + s.path("big")).code == 0);
  REQUIRE(run(s.dir, "operators " + s.path("unit.vtk") + " --out " + s.path("unit")).code == 0);
  using Sparse = Eigen::SparseMatrix<double>;
  const Sparse S = read_matrix_market(s.path("big/S.mtx")), S1 = read_matrix_market(s.path("unit/S.mtx"));
  CHECK(S.coeffs().allFinite());
  CHECK(Sparse(Sparse(S / 1e63) - S1).coeffs().cwiseAbs().maxCoeff() <= 1e-12 * S1.coeffs().cwiseAbs().maxCoeff());
  // At 1e150 the mass (length^3) is not: exit 3, the file, the quantity and the edge named.
  write_volume_mesh(m.with_positions(m.positions() * 1e150), s.path("huge.vtk"));
  const Run r = run(s.dir, "operators " + s.path("huge.vtk") + " --out " + s.path("huge"));
  CHECK(r.code == 3);
  CHECK_THAT(r.err, Catch::Contains("huge.vtk: edge") && Catch::Contains("mass matrix") &&
                        Catch::Contains("rescale the mesh"));
}

}  // namespace test_cli_volume

namespace test_cli_volume {

TEST_CASE("polydec hodge on a volume mesh: the library's decomposition, harmonic dimension 1 on a solid torus",
          "[volume][cli][volume-mesh-complex]") {
  Scratch s;
  const VolumeMesh m = hex_torus_volume(12, 2, 1.0, 0.4, {0.15, 2});
  write_volume_mesh(m, s.path("torus.ovm"));
  const Run r = run(s.dir, "hodge " + s.path("torus.ovm") + " --complex mesh --out " + s.path("parts.txt") + " --json");
  REQUIRE(r.code == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j["kind"] == "volume");
  CHECK(j["harmonic_dimension"] == 1);
  CHECK(j["edges"] == m.n_edges());
  for (const char* phase : {"read", "operators", "solve", "write", "total"}) CHECK(j["times_ms"].contains(phase));
  // The file's columns: i j omega exact coexact harmonic, one line per mesh edge in edges() order;
  // the parts equal the library's decomposition of the same omega.
  std::ifstream in(s.path("parts.txt"));
  std::string line;
  std::getline(in, line);
  Eigen::VectorXd omega(m.n_edges());
  Eigen::MatrixXd parts(m.n_edges(), 3);
  for (int e = 0; e < m.n_edges(); ++e) {
    int a = -1, b = -1;
    REQUIRE(in >> a >> b >> omega[e] >> parts(e, 0) >> parts(e, 1) >> parts(e, 2));
    CHECK(a == m.edges()(e, 0));
    CHECK(b == m.edges()(e, 1));
  }
  const HodgeParts p = VolumeHodgeDecomposer(m, {}, DecComplex::Mesh).decompose(omega);
  const double scale = omega.cwiseAbs().maxCoeff();
  CHECK((parts.col(0) - p.exact).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  CHECK((parts.col(1) - p.coexact).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  CHECK((parts.col(2) - p.harmonic).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  CHECK(p.norm_harmonic > 1e-3 * p.norm);
  CHECK(run(s.dir, "hodge " + s.path("torus.ovm") + " --repair").code == 2);
}

}  // namespace test_cli_volume
