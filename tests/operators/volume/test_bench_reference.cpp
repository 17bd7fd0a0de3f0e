// tests/operators/volume/test_bench_reference.cpp — polydec's volume S and M against the plain
// reference of bench/plain_volume_reference.cpp (the benchmark's baseline, an independent second
// route: face and cell points from the quadratics' normal equations, weights from the minimum-norm
// solution of [X^T; 1^T] w = [x; 1], gradients from the inverse of [1 p], triplet assembly).
#include <catch2/catch.hpp>
#include <numeric>
#include <random>

#include "bench/plain_volume_reference.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/operators/volume/laplacian.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_bench_reference {
using polydec::test::relative_difference;

namespace {

// planar_boundary: the boundary faces are planar, so the refined mesh (split at the face points)
// encloses exactly the mesh's volume (split at the vertex centroids).
void check_against_reference(const VolumeMesh& mesh, bool planar_boundary = true) {
  const VolumeLaplacian L = assemble_volume_laplacian(mesh, refine_volume(mesh));
  SparseMatrix S, M;
  plain_volume_reference::build(plain_volume_reference::from_volume_mesh(mesh), S, M);
  REQUIRE(S.norm() > 0);
  REQUIRE(M.norm() > 0);
  CHECK(relative_difference(L.S, S) < 1e-10);
  CHECK(relative_difference(L.M, M) < 1e-10);
  // The reference's total mass is the mesh volume (M 1 sums to it): a check of the oracle itself.
  if (planar_boundary) CHECK(std::abs(M.sum() - mesh.volume()) < 1e-12 * mesh.volume());
}

}  // namespace

TEST_CASE("volume S and M equal the plain benchmark reference on generated meshes", "[volume][volume-bench-ref]") {
  const VolumeJitter jitter{0.2, 7};
  SECTION("hexahedra") { check_against_reference(hex_grid_volume(3, 4, 2, jitter)); }
  SECTION("tetrahedra") { check_against_reference(tet_grid_volume(3, 2, 2, jitter)); }
  SECTION("pyramids") { check_against_reference(pyramid_grid_volume(2, 2, 3, jitter)); }
  SECTION("truncated octahedra") { check_against_reference(truncated_octahedra_volume(2, jitter)); }
  SECTION("truncated octahedra, planar faces") { check_against_reference(truncated_octahedra_volume(3)); }
}

TEST_CASE("volume S and M equal the plain benchmark reference on the shared cubes", "[volume][volume-bench-ref]") {
  for (const char* name : {"volume/cube_hexahedron_2.ovm", "volume/cube_pyramids_2.ovm", "volume/cube_truncated_2.ovm",
                           "volume/cube_tetrahedron_1.ovm", "volume/noisycube.ovm"}) {
    POLYDEC_SHARED_MESH(path, name);
    INFO(path);
    // The reference takes the coordinates as exact doubles: so does the mesh here (the noisy
    // cube's 6 digits would let polydec count some of its nearly planar faces as planar).
    check_against_reference(read_volume_mesh(path).with_precision({}), path.find("noisy") == std::string::npos);
  }
}

}  // namespace test_volume_bench_reference

namespace test_volume_bench_reference {

// The mesh with its cells in a random order (a cell order without spatial coherence: the threaded
// assembly's other path).
VolumeMesh shuffle_cells(const VolumeMesh& mesh, unsigned seed) {
  PolyhedronSoup soup;
  soup.positions = mesh.positions();
  soup.precision = mesh.precision();
  for (int f = 0; f < mesh.n_faces(); ++f) soup.add_face(mesh.face(f));
  std::vector<int> order(size_t(mesh.n_cells()));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  for (const int c : order) soup.add_cell(mesh.cell(c));
  return VolumeMesh(std::move(soup));
}

TEST_CASE("volume refinement and assembly: bitwise identical for every thread count", "[volume][volume-operators][volume-threads]") {
  // 9240 cells, divisible by 2, 3 and 4; 8303 cells, divisible by none of them (the threads' cell
  // ranges then differ in size, and each vertex's owner must follow the same ranges). Both allow
  // up to 4 threads (2048 cells each); with 3 and 4 their seams hold more than 1/8 of the cells,
  // which takes the assembly's blocks. 10 x 11 x 197 = 21670 cells (divisible by 2 only) has thin
  // seams for every T here: T - 1 seam groups, taken by the threads as they come free.
  const int nz = GENERATE(22, 23, 197);
  const VolumeMesh grid = nz == 22   ? hex_grid_volume(20, 21, 22, VolumeJitter{0.2, 3})
                          : nz == 23 ? hex_grid_volume(19, 19, 23, VolumeJitter{0.2, 3})
                                     : hex_grid_volume(10, 11, 197, VolumeJitter{0.2, 3});
  INFO(grid.n_cells() << " cells");
  const bool shuffled = GENERATE(false, true);
  INFO((shuffled ? "cells shuffled" : "cells in the grid's order"));
  const VolumeMesh mesh = shuffled ? shuffle_cells(grid, 5) : grid;
  VolumeRefinementOptions one;
  const VolumeRefinement R1 = refine_volume(mesh, one);
  const VolumeLaplacian L1 = assemble_volume_laplacian(mesh, R1);
  REQUIRE(L1.S.nonZeros() > 0);
  for (int T : {2, 3, 4}) {
    INFO(T << " threads");
    VolumeRefinementOptions o;
    o.threads = T;
    const VolumeRefinement RT = refine_volume(mesh, o);
    CHECK(RT.cell_weights == R1.cell_weights);
    CHECK(RT.face_weights == R1.face_weights);
    CHECK(RT.tets == R1.tets);
    CHECK(RT.cell_points == R1.cell_points);
    const VolumeLaplacian LT = assemble_volume_laplacian(mesh, RT, nullptr, T);
    REQUIRE(LT.S.nonZeros() == L1.S.nonZeros());
    CHECK(Eigen::VectorXd(LT.S.coeffs()) == Eigen::VectorXd(L1.S.coeffs()));
    CHECK(Eigen::VectorXd(LT.M.coeffs()) == Eigen::VectorXd(L1.M.coeffs()));
    CHECK(LT.M_lumped == L1.M_lumped);
  }
}

}  // namespace test_volume_bench_reference
