// tests/apps/cli/test_cli_volume_binary.cpp — `polydec convert --binary` (VTK legacy BINARY,
// bit-exact back to the mesh) and `polydec info`'s face planarity following the coordinate
// precision of a volume file.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "tests/apps/cli/cli_run.h"
#include "tests/support/support.h"

using namespace polydec;
namespace fs = std::filesystem;

namespace test_cli_volume_binary {

namespace {

struct Scratch : test::ScratchDir {
  Scratch() : ScratchDir("cli_volume_binary") {}
};

test::CliRun run(const fs::path& dir, const std::string& args) { return test::run_cli_in(dir, args); }

std::string slurp(const std::string& path) {
  std::ostringstream s;
  s << std::ifstream(path, std::ios::binary).rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("polydec convert --binary writes VTK legacy BINARY, bit-exact", "[volume][cli][io]") {
  Scratch s;
  const VolumeMesh m = truncated_octahedra_volume(2, {0.2, 5});
  write_volume_mesh(m, s.path("t.ovm"));
  REQUIRE(run(s.dir, "convert " + s.path("t.ovm") + " " + s.path("b.vtk") + " --binary").code == 0);
  CHECK(slurp(s.path("b.vtk")).find("\nBINARY\n") != std::string::npos);
  const VolumeMesh b = read_volume_mesh(s.path("b.vtk"));
  CHECK(b.positions() == m.positions());
  CHECK(b.n_cells() == m.n_cells());
  CHECK(b.volume() == Approx(m.volume()).epsilon(1e-14));
  // Back to ASCII through the CLI: the same doubles.
  REQUIRE(run(s.dir, "convert " + s.path("b.vtk") + " " + s.path("a.vtk")).code == 0);
  CHECK(slurp(s.path("a.vtk")).find("\nASCII\n") != std::string::npos);
  CHECK(read_volume_mesh(s.path("a.vtk")).positions() == m.positions());
  // Formats without a binary form here: a usage error (exit 2).
  CHECK(run(s.dir, "convert " + s.path("t.ovm") + " " + s.path("x.ovm") + " --binary").code == 2);
  CHECK(run(s.dir, "convert " + s.path("t.ovm") + " " + s.path("x.mesh") + " --binary").code == 2);
  // The boundary surface in binary PLY reads back with the same positions.
  REQUIRE(run(s.dir, "convert " + s.path("t.ovm") + " " + s.path("bd.ply") + " --boundary --binary").code ==
          0);
  CHECK(read_mesh(s.path("bd.ply")).positions() == m.positions());
}

TEST_CASE("polydec info: volume face planarity follows the file's coordinate precision",
          "[volume][cli][io]") {
  // A hexahedral grid turned and moved to 1000: written with 6 significant digits, its planar
  // faces are planar only to the 0.005 the digits resolve.
  Scratch s;
  const VolumeMesh g = hex_grid_volume(3, 3, 3);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::MatrixX3d X = g.positions() * R.transpose();
  X.rowwise() += Eigen::RowVector3d(1000, 1000, 1000);
  std::string text = write_volume_mesh_to_string(g.with_positions(X), "ovm");
  const size_t begin = text.find("Vertices\n") + 9;
  const size_t end = text.find("Edges\n");
  std::string six = fmt::format("{}\n", g.n_vertices());
  for (int v = 0; v < g.n_vertices(); ++v)
    six += fmt::format("{:.6g} {:.6g} {:.6g}\n", X(v, 0), X(v, 1), X(v, 2));
  text.replace(begin, end - begin, six);
  std::ofstream(s.path("six.ovm")) << text;
  // The same numbers as exact doubles (binary VTK carries no digits to count).
  REQUIRE(run(s.dir, "convert " + s.path("six.ovm") + " " + s.path("exact.vtk") + " --binary").code == 0);

  auto info = [&](const std::string& file) {
    const test::CliRun r = run(s.dir, "info " + s.path(file) + " --json");
    REQUIRE(r.code == 0);
    return nlohmann::json::parse(r.out);
  };
  const auto six_digits = info("six.ovm"), exact = info("exact.vtk");
  INFO(six_digits.dump() << "\n" << exact.dump());
  CHECK(six_digits["coordinate_noise"].get<double>() == Approx(0.005));
  CHECK(exact["coordinate_noise"].get<double>() == 0.0);
  // Rounding moved corners by up to 0.005 out of their faces' planes: more than 1e-5 of the
  // faces' size, so the exact reading calls faces non-planar; none is beyond what 6 digits resolve.
  CHECK(exact["max_nonplanarity"].get<double>() > 1e-5);
  CHECK(exact["nonplanar_faces"].get<int>() > 0);
  CHECK(six_digits["nonplanar_faces"].get<int>() == 0);
  CHECK(six_digits["max_nonplanarity"].get<double>() == exact["max_nonplanarity"].get<double>());
}

}  // namespace test_cli_volume_binary
