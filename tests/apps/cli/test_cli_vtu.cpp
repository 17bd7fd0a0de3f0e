// tests/apps/cli/test_cli_vtu.cpp — the command line with VTK XML files ([vtu-cli]): `info` on a .vtu
// written by VTK (counts, volume, the skipped boundary cells), `geodesics` and `spectrum --vtu` on a
// volume writing their fields as .vtu point data (equal to the JSON and the .mtx), `convert` to .vtu
// (base64, and zlib-compressed with --compress); a surface .vtu taken as a surface by every command,
// and `convert --boundary` writing one.
#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "polydec/dec/detail/io_common.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/io/vtu.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "tests/apps/cli/cli_run.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_cli_vtu {

TEST_CASE("polydec info, geodesics, spectrum and convert with .vtu files", "[vtu-cli]") {
  const test::ScratchDir scratch("cli_vtu");
  const std::string fixture = std::string(POLYDEC_TEST_DATA) + "/vtu/vtk_zlib_appended_raw.vtu";
  {
    const auto r = test::run_cli_in(scratch.dir, "info '" + fixture + "' --json");
    INFO(r.err);
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["vertices"] == 33);
    CHECK(j["cells"] == 17);
    CHECK(std::abs(j["volume"].get<double>() - 0.75) <= 1e-15);
    CHECK(j["skipped_cells"] ==
          nlohmann::json({{"line", 1}, {"polygon", 1}, {"quad", 1}, {"triangle", 2}, {"vertex", 1}}));
    const auto text = test::run_cli_in(scratch.dir, "info '" + fixture + "'");
    CHECK(text.out.find("skipped lower-dimensional cells beside the volume cells: 1 line, 1 polygon, 1 quad, "
                        "2 triangle, 1 vertex") != std::string::npos);
  }
  const VolumeMesh mesh = hex_grid_volume(3, 3, 2, {0.2, 5});
  const std::string file = scratch.path("grid.vtu");
  write_volume_mesh(mesh, file);
  {
    const auto r = test::run_cli_in(
        scratch.dir, "geodesics '" + file + "' --source 0 --json --out '" + scratch.path("d.vtu") + "'");
    INFO(r.err);
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    const Eigen::VectorXd d = read_vtu_fields(scratch.path("d.vtu")).point_scalars.at("distance");
    REQUIRE(d.size() == mesh.n_vertices());
    CHECK(d.maxCoeff() == j["max"].get<double>());
    CHECK(d[0] == j["min"].get<double>());
    CHECK(read_volume_mesh(scratch.path("d.vtu")).positions() == mesh.positions());
  }
  {
    const auto r = test::run_cli_in(
        scratch.dir, "spectrum '" + file + "' --k 3 --vtu --json --out '" + scratch.path("sp") + "'");
    INFO(r.err);
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["files"][2] == "eigenvectors.vtu");
    const VtuFields f = read_vtu_fields(scratch.path("sp/eigenvectors.vtu"));
    const Eigen::MatrixXd U = Eigen::MatrixXd(read_matrix_market(scratch.path("sp/eigenvectors.mtx")));
    REQUIRE(f.point_scalars.size() == 3);
    for (int i = 0; i < 3; ++i) CHECK(f.point_scalars.at(fmt::format("u{:03d}", i)) == U.col(i));
  }
  {
    const auto r =
        test::run_cli_in(scratch.dir, "convert '" + file + "' '" + scratch.path("b.vtu") + "' --binary");
    INFO(r.err);
    REQUIRE(r.code == 0);
    CHECK(read_volume_mesh(scratch.path("b.vtu")).positions() == mesh.positions());
  }
  {
    // --compress: appended zlib blocks, the same mesh; only for .vtu.
    const auto r =
        test::run_cli_in(scratch.dir, "convert '" + file + "' '" + scratch.path("c.vtu") + "' --compress");
    INFO(r.err);
    REQUIRE(r.code == 0);
    const std::string bytes = io_detail::slurp(scratch.path("c.vtu"));
    CHECK(bytes.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos);
    CHECK(bytes.find("<AppendedData encoding=\"raw\">") != std::string::npos);
    CHECK(read_volume_mesh(scratch.path("c.vtu")).positions() == mesh.positions());
    const auto wrong =
        test::run_cli_in(scratch.dir, "convert '" + file + "' '" + scratch.path("c.vtk") + "' --compress");
    CHECK(wrong.code == 2);
    CHECK(wrong.err.find("--compress") != std::string::npos);
  }
}

TEST_CASE("a surface .vtu is a surface for the commands, and convert --boundary writes one", "[vtu-cli]") {
  const test::ScratchDir scratch("cli_vtu_surface");
  const Mesh surface = hex_sphere(2);
  const std::string file = scratch.path("s.vtu");
  write_mesh(file, surface);
  CHECK_FALSE(is_volume_mesh_path(file));
  {
    const auto r = test::run_cli_in(scratch.dir, "info '" + file + "' --json");
    INFO(r.err);
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["vertices"] == surface.n_vertices());
    CHECK(j["faces"] == surface.n_faces());
    CHECK_FALSE(j.contains("cells"));
  }
  {
    // The same Laplacian as from the same mesh written as OFF.
    write_mesh(scratch.path("s.off"), surface);
    const auto a = test::run_cli_in(scratch.dir, "operators '" + file + "' --out '" + scratch.path("a") + "'");
    const auto b =
        test::run_cli_in(scratch.dir, "operators '" + scratch.path("s.off") + "' --out '" + scratch.path("b") + "'");
    INFO(a.err << b.err);
    REQUIRE(a.code == 0);
    REQUIRE(b.code == 0);
    const Eigen::SparseMatrix<double> Sa = read_matrix_market(scratch.path("a/S.mtx"));
    const Eigen::SparseMatrix<double> Sb = read_matrix_market(scratch.path("b/S.mtx"));
    CHECK((Sa - Sb).norm() <= 1e-12 * Sb.norm());
  }
  {
    const VolumeMesh mesh = hex_grid_volume(2, 2, 3);
    write_volume_mesh(mesh, scratch.path("v.vtk"));
    const auto r = test::run_cli_in(scratch.dir, "convert '" + scratch.path("v.vtk") + "' '" +
                                                     scratch.path("boundary.vtu") + "' --boundary");
    INFO(r.err);
    REQUIRE(r.code == 0);
    const Mesh b = read_mesh(scratch.path("boundary.vtu"));
    CHECK(b.n_faces() == mesh.boundary_surface().n_faces());
    CHECK(b.positions() == mesh.positions());
  }
  {
    // --help lists every format a command reads.
    const auto r = test::run_cli_in(scratch.dir, "geodesics --help");
    CHECK(r.out.find(".obj, .off, .ply, .msh, .vtu; volumes: .ovm, .vtk, .mesh, .meshb, .msh, .vtu") !=
          std::string::npos);
  }
}

}  // namespace test_cli_vtu
