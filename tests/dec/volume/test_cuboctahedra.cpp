// tests/dec/volume/test_cuboctahedra.cpp — cuboctahedra_volume(n), the structure of polyLaplace's
// cube_truncated_L.ovm files: counts, exact cell volumes, Euler characteristic, and the same
// Poisson errors as the shared files at n = 2, 4 (levels 2, 3: the same mesh up to numbering).
#include <catch2/catch.hpp>
#include <cmath>

#include "polydec/apps/applications/volume/poisson.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_cuboctahedra_volume {

TEST_CASE("cuboctahedra_volume: counts, volumes, Euler characteristic", "[volume][volume-generators]") {
  for (int n : {1, 2, 3}) {
    INFO("n = " << n);
    const VolumeMesh mesh = cuboctahedra_volume(n);
    CHECK(mesh.n_cells() == 9 * n * n * n);
    CHECK(mesh.n_vertices() == (n + 1) * (n + 1) * (n + 1) + 3 * n * (n + 1) * (n + 1));
    CHECK(mesh.n_vertices() - mesh.n_edges() + mesh.n_faces() - mesh.n_cells() == 1);
    const double cube = 1.0 / (n * n * n);
    for (int c = 0; c < mesh.n_cells(); ++c) {
      const double expected = mesh.cell_vertices(c).size() == 4 ? cube / 48 : cube * 5 / 6;
      CHECK(std::abs(mesh.cell_volume(c) - expected) < 1e-12 * cube);
    }
    CHECK(std::abs(mesh.volume() - 1.0) < 1e-12);
  }
}

TEST_CASE("cuboctahedra_volume reproduces the shared cube_truncated files", "[volume][volume-generators]") {
  for (int level : {2, 3}) {
    POLYDEC_SHARED_MESH(path, "volume/cube_truncated_" + std::to_string(level) + ".ovm");
    const VolumeMesh file = read_volume_mesh(path);
    const VolumeMesh generated = cuboctahedra_volume(1 << (level - 1));
    INFO(path);
    REQUIRE(generated.n_vertices() == file.n_vertices());
    REQUIRE(generated.n_cells() == file.n_cells());
    CHECK(std::abs(generated.mean_edge_length() - file.mean_edge_length()) < 1e-12 * file.mean_edge_length());
    const VolumePoissonError a = volume_franke_poisson(file), b = volume_franke_poisson(generated);
    CHECK(std::abs(a.l2_error - b.l2_error) < 1e-10 * a.l2_error);
    CHECK(std::abs(a.rms_error - b.rms_error) < 1e-10 * a.rms_error);
  }
}

}  // namespace test_cuboctahedra_volume
