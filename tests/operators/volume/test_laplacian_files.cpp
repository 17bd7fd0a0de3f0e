// tests/operators/volume/test_laplacian_files.cpp — the polyhedral operators and DEC on the shared
// polyLaplace cube meshes (../shared/data/volume): properties and linear precision on hexahedra,
// pyramids and truncated octahedra, the standard FEM and rule independence on the tetrahedral
// cubes, S = -d0^T star1 d0 and d d = 0 on the cubes DEC supports.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/operators/volume/laplacian.h"
#include "tests/support/volume_meshes.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_laplacian_files {
using polydec::test::relative_difference;

namespace {

double max_interior_defect(const VolumeMesh& mesh, const SparseMatrix& S) {
  const Eigen::MatrixXd SX = S * mesh.positions();
  const double scale = S.coeffs().cwiseAbs().maxCoeff() * mesh.bounding_box_diagonal();
  double worst = 0;
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (!mesh.is_boundary_vertex(v)) worst = std::max(worst, SX.row(v).cwiseAbs().maxCoeff() / scale);
  return worst;
}

}  // namespace

TEST_CASE("shared cube meshes: S, M properties and linear precision", "[volume][volume-operators]") {
  for (const char* name : {"volume/cube_hexahedron_2.ovm", "volume/cube_pyramids_2.ovm",
                           "volume/cube_truncated_2.ovm", "volume/cube_tetrahedron_1.ovm"}) {
    const std::string path = test::shared_path(name);
    if (path.empty()) {
      WARN("skipped: " << name << " missing");
      continue;
    }
    INFO(name);
    const VolumeMesh mesh = read_volume_mesh(path);
    for (CellPointRule rule : {CellPointRule::SquaredVolume, CellPointRule::PolyLaplace}) {
      VolumeRefinementOptions o;
      o.cell_rule = rule;
      const VolumeRefinement R = refine_volume(mesh, o);
      CHECK(R.quality.ok());
      const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
      const double scale = L.S.coeffs().cwiseAbs().maxCoeff();
      CHECK(relative_difference(L.S, SparseMatrix(L.S.transpose())) < 1e-14);
      CHECK((L.S * Eigen::VectorXd::Ones(mesh.n_vertices())).cwiseAbs().maxCoeff() < 1e-12 * scale);
      CHECK(std::abs(L.M_lumped.sum() - mesh.volume()) < 1e-12 * mesh.volume());
      CHECK(max_interior_defect(mesh, L.S) < 1e-11);
      // Negative semi-definite: x^T S x <= 0 for random x.
      for (int trial = 0; trial < 5; ++trial) {
        const Eigen::VectorXd x = Eigen::VectorXd::Random(mesh.n_vertices());
        CHECK(x.dot(L.S * x) <= 1e-12 * scale * x.squaredNorm());
      }
    }
  }
}

TEST_CASE("shared tetrahedral cubes: both cell-point rules give the same S", "[volume][volume-operators]") {
  for (const char* name : {"volume/cube_tetrahedron_1.ovm", "volume/cube_tetrahedron_2.ovm"}) {
    const std::string path = test::shared_path(name);
    if (path.empty()) {
      WARN("skipped: " << name << " missing");
      continue;
    }
    const VolumeMesh mesh = read_volume_mesh(path);
    VolumeRefinementOptions o;
    o.cell_rule = CellPointRule::PolyLaplace;
    const VolumeLaplacian a = assemble_volume_laplacian(mesh, refine_volume(mesh));
    const VolumeLaplacian b = assemble_volume_laplacian(mesh, refine_volume(mesh, o));
    CHECK(relative_difference(a.S, b.S) < 1e-12);
    CHECK(relative_difference(a.M, b.M) < 1e-12);
  }
}

TEST_CASE("shared cube meshes: DEC identities", "[volume][volume-dec]") {
  for (const char* name : {"volume/cube_hexahedron_1.ovm", "volume/cube_pyramids_1.ovm",
                           "volume/cube_truncated_1.ovm", "volume/noisycube.ovm"}) {
    const std::string path = test::shared_path(name);
    if (path.empty()) {
      WARN("skipped: " << name << " missing");
      continue;
    }
    INFO(name);
    const VolumeMesh mesh = read_volume_mesh(path);
    const VolumeRefinement R = refine_volume(mesh);
    const VolumeDec D = volume_dec(mesh, R);
    CHECK(SparseMatrix(D.d[1] * D.d[0]).norm() == 0.0);
    CHECK(SparseMatrix(D.d[2] * D.d[1]).norm() == 0.0);
    const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
    CHECK(relative_difference(SparseMatrix(-D.d[0].transpose() * D.star[1] * D.d[0]), L.S) < 1e-12);
    CHECK(relative_difference(D.star[0], L.M) < 1e-12);
  }
}

TEST_CASE("DEC degree limits by cell size: lower degrees on larger cells", "[volume][volume-dec]") {
  // A cell of m vertices gives star_k a dense C(m, k+1)^2 block: each limit is the largest m whose
  // block fits kMaxDecLocalBlock.
  auto binomial = [](long n, long k) {
    long c = 1;
    for (long i = 0; i < k; ++i) c = c * (n - i) / (i + 1);
    return c;
  };
  for (int k = 1; k <= 3; ++k) {
    const long m = max_dec_cell_vertices(k);
    CHECK(binomial(m, k + 1) * binomial(m, k + 1) <= kMaxDecLocalBlock);
    CHECK(binomial(m + 1, k + 1) * binomial(m + 1, k + 1) > kMaxDecLocalBlock);
  }
  CHECK(max_dec_cell_vertices(3) < max_dec_cell_vertices(2));
  CHECK(max_dec_cell_vertices(2) < max_dec_cell_vertices(1));

  // A 7-gonal prism (14 vertices): degree 3 is refused naming the cell, degree 2 is complete.
  const VolumeMesh prism = test::prism_volume(7);
  REQUIRE(int(prism.cell_vertices(0).size()) == 14);
  CHECK(volume_dec_max_degree(prism) == 2);
  const VolumeRefinement Rp = refine_volume(prism);
  CHECK_THROWS_WITH(volume_dec(prism, Rp), Catch::Contains("cell 0") && Catch::Contains("14 vertices"));
  const VolumeDec Dp = volume_dec(prism, Rp, 2);
  CHECK(Dp.coarse.n_quads() == 0);
  CHECK(Dp.d[2].size() == 0);
  CHECK(Dp.star[3].size() == 0);
  CHECK(SparseMatrix(Dp.d[1] * Dp.d[0]).norm() == 0.0);
  const VolumeLaplacian Lp = assemble_volume_laplacian(prism, Rp);
  CHECK(relative_difference(SparseMatrix(-Dp.d[0].transpose() * Dp.star[1] * Dp.d[0]), Lp.S) < 1e-12);
  CHECK(std::abs(Lp.M_lumped.sum() - prism.volume()) < 1e-12 * prism.volume());

  // Truncated octahedra (24 vertices inside the box): 1-forms, so S = -d0^T star1 d0 on them too.
  const VolumeMesh mesh = truncated_octahedra_volume(3);
  size_t largest = 0;
  for (int c = 0; c < mesh.n_cells(); ++c) largest = std::max(largest, mesh.cell_vertices(c).size());
  REQUIRE(largest == 24);
  CHECK(volume_dec_max_degree(mesh) == 1);
  const VolumeRefinement R = refine_volume(mesh);
  const VolumeDec D = volume_dec(mesh, R, 1);
  CHECK(D.coarse.n_triples() == 0);
  const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
  CHECK(relative_difference(SparseMatrix(-D.d[0].transpose() * D.star[1] * D.d[0]), L.S) < 1e-12);
  CHECK(relative_difference(D.star[0], L.M) < 1e-12);
}

}  // namespace test_volume_laplacian_files
