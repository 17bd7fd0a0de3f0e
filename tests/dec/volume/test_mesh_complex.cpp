// tests/dec/volume/test_mesh_complex.cpp — the volume mesh complex (dec/volume/mesh_complex.h) on
// hexahedra, tetrahedra, pyramids, prisms, truncated octahedra, a hexahedral solid torus, a prism
// over a 100-gon and merged truncated octahedra (Voronoi-like cells of 40+ vertices): d d = 0,
// P_{k+1} d_k = d_k^tet P_k, the cell-by-cell stars against P_k^T star_k^tet P_k, S = -d0^T star1 d0,
// star0 = M, positive definite star1..star3, star3 = diag(1 / vol_c), independence of how faces
// and cells are listed, and VolumeDec on the mesh complex.
#include <Eigen/SparseCholesky>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/dec/volume/mesh_complex.h"
#include "polydec/dec/volume/whitney.h"
#include "polydec/operators/volume/laplacian.h"
#include "tests/support/support.h"
#include "tests/support/volume_meshes.h"

using namespace polydec;

namespace test_volume_mesh_complex {
using polydec::test::relative_difference;

namespace {

double max_abs(const SparseMatrix& A) { return A.nonZeros() ? A.coeffs().cwiseAbs().maxCoeff() : 0.0; }

bool positive_definite(const SparseMatrix& A) {
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(A);
  return ldlt.info() == Eigen::Success && ldlt.vectorD().minCoeff() > 0;
}

struct Case {
  std::string name;
  VolumeMesh mesh;
};

std::vector<Case> meshes() {
  std::vector<Case> out;
  out.push_back({"jittered hexahedra", hex_grid_volume(3, 2, 2, {0.25, 3})});
  out.push_back({"jittered tetrahedra", tet_grid_volume(2, 2, 2, {0.2, 5})});
  out.push_back({"jittered pyramids", pyramid_grid_volume(2, 2, 1, {0.2, 7})});
  out.push_back({"hexagonal prism", test::prism_volume(6)});
  out.push_back({"single pyramid", test::single_pyramid()});
  out.push_back({"truncated octahedra", truncated_octahedra_volume(2, {0.15, 11})});
  out.push_back({"hex solid torus", test::hex_solid_torus(6)});
  out.push_back({"prism over a 100-gon", test::prism_volume(100)});
  out.push_back({"merged truncated octahedra", test::merge_neighbour_cells(truncated_octahedra_volume(3, {0.15, 13}), 30)});
  out.push_back({"twice merged truncated octahedra",
                 test::merge_neighbour_cells(test::merge_neighbour_cells(truncated_octahedra_volume(2, {0.2, 5}), 30), 50)});
  return out;
}

int largest_cell(const VolumeMesh& mesh) {
  size_t m = 0;
  for (int c = 0; c < mesh.n_cells(); ++c) m = std::max(m, mesh.cell_vertices(c).size());
  return int(m);
}

}  // namespace

TEST_CASE("volume mesh complex: d d = 0, commuting prolongations, stars, S = -d0^T star1 d0",
          "[volume][volume-dec][volume-mesh-complex]") {
  for (const Case& cs : meshes()) {
    INFO(cs.name);
    const VolumeMesh& mesh = cs.mesh;
    const VolumeRefinement R = refine_volume(mesh);
    const SimplexComplex3 refined = volume_refined_complex(mesh, R);
    SparseMatrix d[3], dr[3], P[4];
    for (int k = 0; k < 3; ++k) d[k] = volume_mesh_d(mesh, k), dr[k] = refined.d(k);
    CHECK(d[0].rows() == mesh.n_edges());
    CHECK(d[1].rows() == mesh.n_faces());
    CHECK(d[2].rows() == mesh.n_cells());
    CHECK(max_abs(SparseMatrix(d[1] * d[0])) == 0.0);
    CHECK(max_abs(SparseMatrix(d[2] * d[1])) == 0.0);
    for (int k = 0; k < 4; ++k) {
      P[k] = volume_mesh_prolongation(mesh, R, refined, k);
      CHECK(P[k].rows() == refined.n_simplices(k));
    }
    for (int k = 0; k < 3; ++k) {
      INFO("k = " << k);
      CHECK(relative_difference(SparseMatrix(P[k + 1] * d[k]), SparseMatrix(dr[k] * P[k])) < 1e-12);
    }
    const std::array<SparseMatrix, 4> star = volume_mesh_stars(mesh, R);
    for (int k = 0; k < 4; ++k) {
      INFO("k = " << k);
      const SparseMatrix global = P[k].transpose() * volume_refined_star(mesh, R, refined, k) * P[k];
      CHECK(relative_difference(star[size_t(k)], global) < 1e-12);
      CHECK(relative_difference(star[size_t(k)], SparseMatrix(star[size_t(k)].transpose())) < 1e-14);
      if (k > 0) CHECK(positive_definite(star[size_t(k)]));
    }
    const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
    CHECK(relative_difference(SparseMatrix(-d[0].transpose() * star[1] * d[0]), L.S) < 1e-12);
    CHECK(relative_difference(star[0], L.M) < 1e-12);
    // P3: vol_tau / vol_c on every sub-tetrahedron (signed along the sorted orientation), star3 = 1 / vol_c.
    std::vector<double> vol(size_t(mesh.n_cells()), 0.0);
    const std::vector<RefinedTet> tets = refined_tets(mesh, R);
    std::vector<double> signed_vol(tets.size());
    for (size_t i = 0; i < tets.size(); ++i) {
      std::array<int, 4> v = {tets[i].v[0], tets[i].v[1], tets[i].v[2], tets[i].v[3]};
      Eigen::Vector3d p[4];
      // (x_i, x_{i+1}, x_f, x_c) in the half-face's outward order is negatively oriented.
      for (int a = 0; a < 4; ++a) p[a] = refined_position(mesh, R, tets[i].v[a]);
      vol[size_t(v[3] - mesh.n_vertices() - mesh.n_faces())] -= tet_signed_volume(p[0], p[1], p[2], p[3]);
      std::sort(v.begin(), v.end());
      for (int a = 0; a < 4; ++a) p[a] = refined_position(mesh, R, v[size_t(a)]);
      signed_vol[i] = tet_signed_volume(p[0], p[1], p[2], p[3]);
    }
    const Eigen::MatrixXd P3 = Eigen::MatrixXd(P[3]);
    double worst = 0;
    for (size_t i = 0; i < tets.size(); ++i) {
      std::array<int, 4> v = {tets[i].v[0], tets[i].v[1], tets[i].v[2], tets[i].v[3]};
      std::sort(v.begin(), v.end());
      const int c = v[3] - mesh.n_vertices() - mesh.n_faces();
      worst = std::max(worst, std::abs(P3(refined.index(v), c) - signed_vol[i] / vol[size_t(c)]));
    }
    CHECK(worst < 1e-12);
    // star3 = sum |vol_tau| / vol_c^2: 1 / vol_c without inverted sub-tetrahedra, more with them.
    const Eigen::VectorXd s3 = Eigen::MatrixXd(star[3]).diagonal();
    CHECK(star[3].nonZeros() == mesh.n_cells());
    for (int c = 0; c < mesh.n_cells(); ++c) {
      if (R.quality.n_inverted == 0)
        CHECK(std::abs(s3[c] * vol[size_t(c)] - 1) < 1e-12);
      else
        CHECK(s3[c] * vol[size_t(c)] > 1 - 1e-12);
    }
  }
}

TEST_CASE("volume mesh complex: planar faces give star3 = 1 / cell volume", "[volume][volume-dec][volume-mesh-complex]") {
  for (const VolumeMesh& mesh : {truncated_octahedra_volume(2), test::prism_volume(100), hex_torus_volume(6, 2)}) {
    const VolumeRefinement R = refine_volume(mesh);
    REQUIRE(R.quality.n_inverted == 0);
    const SparseMatrix s3 = volume_mesh_stars(mesh, R)[3];
    for (int c = 0; c < mesh.n_cells(); ++c) CHECK(std::abs(s3.coeff(c, c) * mesh.cell_volume(c) - 1) < 1e-12);
  }
}

TEST_CASE("volume mesh complex: large cells, minimum-norm face rule", "[volume][volume-dec][volume-mesh-complex]") {
  const VolumeMesh merged =
      test::merge_neighbour_cells(test::merge_neighbour_cells(truncated_octahedra_volume(3, {0.2, 5}), 30), 50);
  CHECK(largest_cell(merged) >= 60);
  const VolumeMesh prism = test::prism_volume(100);
  for (const VolumeMesh* mesh : {&merged, &prism}) {
    const VolumeRefinement R = refine_volume(*mesh);
    // The complete complex refuses these cells from degree 1 on; the mesh complex takes every degree.
    CHECK_THROWS_AS(volume_coarse_complex(*mesh, 1), std::invalid_argument);
    const VolumeDec D = volume_dec(*mesh, R, VolumeDecOptions{.max_degree = 3, .complex = DecComplex::Mesh,
                                                              .spoke_rule = SpokeRule::MinimumNorm});
    CHECK(D.complex == DecComplex::Mesh);
    CHECK(D.coarse.n_simplices(1) == 0);
    for (int k = 0; k < 3; ++k)
      CHECK(relative_difference(SparseMatrix(D.P[k + 1] * D.d[k]), SparseMatrix(D.refined.d(k) * D.P[k])) < 1e-12);
    for (int k = 1; k < 4; ++k) CHECK(positive_definite(D.star[k]));
    const VolumeLaplacian L = assemble_volume_laplacian(*mesh, R);
    CHECK(relative_difference(SparseMatrix(-D.d[0].transpose() * D.star[1] * D.d[0]), L.S) < 1e-12);
  }
}

TEST_CASE("volume mesh complex: independent of the face order of a cell and of a face's start",
          "[volume][volume-dec][volume-mesh-complex]") {
  const VolumeMesh meshes[] = {test::merge_neighbour_cells(truncated_octahedra_volume(2, {0.15, 17}), 30),
                               hex_grid_volume(2, 2, 2, {0.3, 19}), pyramid_grid_volume(1, 1, 2, {0.2, 23})};
  for (const VolumeMesh& mesh : meshes) {
    const VolumeMesh other = test::relisted_volume(mesh);
    REQUIRE(other.n_faces() == mesh.n_faces());
    const VolumeRefinement R = refine_volume(mesh), Ro = refine_volume(other);
    const std::array<SparseMatrix, 4> a = volume_mesh_stars(mesh, R), b = volume_mesh_stars(other, Ro);
    for (int k = 0; k < 4; ++k) CHECK(relative_difference(a[size_t(k)], b[size_t(k)]) < 1e-12);
    for (int k = 1; k < 4; ++k)
      CHECK(relative_difference(volume_mesh_prolongation(mesh, R, k), volume_mesh_prolongation(other, Ro, k)) < 1e-12);
  }
}

TEST_CASE("volume mesh complex in VolumeDec: every degree, equal to the building blocks",
          "[volume][volume-dec][volume-mesh-complex]") {
  const VolumeMesh mesh = truncated_octahedra_volume(2, {0.15, 29});
  const VolumeRefinement R = refine_volume(mesh);
  const std::array<SparseMatrix, 4> stars = volume_mesh_stars(mesh, R);
  for (int degree = 0; degree <= 3; ++degree) {
    const VolumeDec D = volume_dec(mesh, R, VolumeDecOptions{.max_degree = degree, .complex = DecComplex::Mesh});
    CHECK(D.max_degree == degree);
    CHECK(D.coarse.n_simplices(1) == 0);
    for (int k = 0; k < 3; ++k) CHECK(D.d[k].size() == (k < degree ? volume_mesh_d(mesh, k).size() : 0));
    for (int k = 0; k <= 3; ++k) {
      if (k > degree) {
        CHECK(D.P[k].size() == 0);
        CHECK(D.star[k].size() == 0);
        continue;
      }
      CHECK(relative_difference(D.P[k], volume_mesh_prolongation(mesh, R, k)) == 0.0);
      CHECK(relative_difference(D.star[k], stars[size_t(k)]) < 1e-15);
    }
  }
  // The mesh complex's forms are independent: the reduced basis keeps every coarse cell.
  const VolumeDec D = volume_dec(mesh, R, VolumeDecOptions{.max_degree = 3, .complex = DecComplex::Mesh});
  const int counts[4] = {mesh.n_vertices(), mesh.n_edges(), mesh.n_faces(), mesh.n_cells()};
  for (int k = 1; k <= 3; ++k) CHECK(int(volume_form_span(D, mesh, R, k).cells.size()) == counts[k]);
  // The integer overload stays the complete complex.
  const VolumeMesh hexes = hex_grid_volume(1, 1, 1);
  const VolumeDec C = volume_dec(hexes, refine_volume(hexes), 1);
  CHECK(C.complex == DecComplex::Complete);
  CHECK(C.coarse.n_simplices(1) == 28);
  CHECK_THROWS_AS(volume_dec(hexes, refine_volume(hexes), VolumeDecOptions{.max_degree = 4}), std::invalid_argument);
  CHECK_THROWS_AS(volume_mesh_d(hexes, 3), std::invalid_argument);
  CHECK_THROWS_AS(volume_mesh_prolongation(hexes, refine_volume(hexes), 4), std::invalid_argument);
}

TEST_CASE("volume mesh complex: the rule's minimum-norm edges, cells that are not balls refused",
          "[volume][volume-dec][volume-mesh-complex]") {
  // P1's rows on a cell's interior edges (v, x_c), (x_f, x_c) are of least norm: orthogonal to the
  // cycles of the cell's edge graph, which its face boundaries span, so (P1 d1^T)(rho, f) = 0 for
  // every face f of the cell.
  const VolumeMesh mesh = test::merge_neighbour_cells(truncated_octahedra_volume(2, {0.15, 31}), 30);
  const VolumeRefinement R = refine_volume(mesh);
  const SimplexComplex3 refined = volume_refined_complex(mesh, R);
  const Eigen::MatrixXd C = Eigen::MatrixXd(SparseMatrix(volume_mesh_prolongation(mesh, R, refined, 1) *
                                                         SparseMatrix(volume_mesh_d(mesh, 1).transpose())));
  const int nV = mesh.n_vertices(), nF = mesh.n_faces();
  double worst = 0, scale = 0;
  int rows = 0;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    std::vector<int> ends(mesh.cell_vertices(c).begin(), mesh.cell_vertices(c).end());
    for (int hf : mesh.cell(c)) ends.push_back(nV + hf / 2);
    for (int a : ends) {
      const std::array<int, 2> e = {a, nV + nF + c};
      const int r = refined.index(e);
      REQUIRE(r >= 0);
      ++rows;
      scale = std::max(scale, C.row(r).cwiseAbs().maxCoeff());
      for (int hf : mesh.cell(c)) worst = std::max(worst, std::abs(C(r, hf / 2)));
    }
  }
  CHECK(rows > 0);
  CHECK(worst <= 1e-12 * std::max(scale, 1.0));

  // A solid torus as one cell (a square frame: 16 quads, V - E + F = 0).
  Eigen::MatrixX3d X(16, 3);
  const double rad[2] = {2.0, 1.0};
  const int corner[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  for (int ring = 0; ring < 2; ++ring)
    for (int z = 0; z < 2; ++z)
      for (int k = 0; k < 4; ++k)
        X.row(8 * ring + 4 * z + k) << rad[ring] * corner[k][0], rad[ring] * corner[k][1], double(z);
  auto id = [](int ring, int z, int k) { return 8 * ring + 4 * z + (k % 4); };
  std::vector<std::vector<int>> faces;
  for (int k = 0; k < 4; ++k) {
    faces.push_back({id(0, 1, k), id(0, 1, k + 1), id(1, 1, k + 1), id(1, 1, k)});  // top, up
    faces.push_back({id(0, 0, k), id(1, 0, k), id(1, 0, k + 1), id(0, 0, k + 1)});  // bottom, down
    faces.push_back({id(0, 0, k), id(0, 0, k + 1), id(0, 1, k + 1), id(0, 1, k)});  // outer side
    faces.push_back({id(1, 0, k), id(1, 1, k), id(1, 1, k + 1), id(1, 0, k + 1)});  // inner side
  }
  const VolumeMesh torus = test::volume_from_cells(X, {faces});
  REQUIRE(torus.n_cells() == 1);
  CHECK(torus.cell_volume(0) > 0);
  const VolumeRefinement Rt = refine_volume(torus);
  CHECK_THROWS_WITH(volume_mesh_stars(torus, Rt), Catch::Contains("cell 0") && Catch::Contains("not a sphere"));
  CHECK_THROWS_WITH(volume_mesh_prolongation(torus, Rt, 1), Catch::Contains("not a sphere"));
}

TEST_CASE("volume mesh complex on the shared cube meshes", "[volume][volume-dec][volume-mesh-complex]") {
  for (const char* name : {"volume/noisycube.ovm", "volume/cube_truncated_2.ovm", "volume/cube_pyramids_2.ovm",
                           "volume/cube_tetrahedron_1.ovm"}) {
    const std::string path = test::shared_path(name);
    if (path.empty()) {
      WARN("skipped: " << name << " missing");
      continue;
    }
    INFO(name);
    const VolumeMesh mesh = read_volume_mesh(path);
    const VolumeRefinement R = refine_volume(mesh);
    const VolumeDec D = volume_dec(mesh, R, VolumeDecOptions{.max_degree = 3, .complex = DecComplex::Mesh});
    for (int k = 0; k < 3; ++k) {
      CHECK(max_abs(SparseMatrix(D.refined.d(k) * D.P[k])) > 0);
      CHECK(relative_difference(SparseMatrix(D.P[k + 1] * D.d[k]), SparseMatrix(D.refined.d(k) * D.P[k])) < 1e-12);
    }
    const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
    CHECK(relative_difference(SparseMatrix(-D.d[0].transpose() * D.star[1] * D.d[0]), L.S) < 1e-12);
    CHECK(relative_difference(D.star[0], L.M) < 1e-12);
    for (int k = 1; k < 4; ++k) CHECK(positive_definite(D.star[k]));
    CHECK(D.star[3].nonZeros() == mesh.n_cells());
  }
}

TEST_CASE("volume mesh complex: sub-tetrahedra flagged degenerate add nothing to star1..star3",
          "[volume][volume-dec][volume-mesh-complex]") {
  const VolumeMesh mesh = test::merge_neighbour_cells(truncated_octahedra_volume(2, {0.15, 37}), 30);
  VolumeRefinement R = refine_volume(mesh);
  // Every 7th sub-tetrahedron flagged, as the refinement flags flat ones.
  for (size_t i = 0; i < R.tets.size(); i += 7) R.tets[i] = SubTet::Degenerate;
  const SimplexComplex3 refined = volume_refined_complex(mesh, R);
  const std::array<SparseMatrix, 4> star = volume_mesh_stars(mesh, R);
  for (int k = 0; k < 4; ++k) {
    INFO("k = " << k);
    const SparseMatrix P = volume_mesh_prolongation(mesh, R, refined, k);
    CHECK(relative_difference(star[size_t(k)], SparseMatrix(P.transpose() * volume_refined_star(mesh, R, refined, k) * P)) <
          1e-12);
    if (k > 0) CHECK(positive_definite(star[size_t(k)]));
  }
  const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
  const SparseMatrix d0 = volume_mesh_d(mesh, 0);
  CHECK(relative_difference(SparseMatrix(-d0.transpose() * star[1] * d0), L.S) < 1e-12);
  CHECK(relative_difference(star[0], L.M) < 1e-12);
}

}  // namespace test_volume_mesh_complex

namespace test_volume_mesh_complex {
namespace {

// A and B with the same pattern (outer and inner arrays) and bitwise equal values.
bool identical(const SparseMatrix& A, const SparseMatrix& B) {
  if (A.rows() != B.rows() || A.cols() != B.cols() || A.nonZeros() != B.nonZeros()) return false;
  if (!A.isCompressed() || !B.isCompressed()) return false;
  for (Eigen::Index j = 0; j <= A.outerSize(); ++j)
    if (A.outerIndexPtr()[j] != B.outerIndexPtr()[j]) return false;
  for (Eigen::Index p = 0; p < A.nonZeros(); ++p)
    if (A.innerIndexPtr()[p] != B.innerIndexPtr()[p] || A.valuePtr()[p] != B.valuePtr()[p]) return false;
  return true;
}

// The straightforward assembly of the cells' shares (volume_mesh_cell): every local entry as a
// triplet, summed by setFromTriplets; a refined simplex's P row from the first cell that has it.
VolumeMeshDec triplet_assembly(const VolumeMesh& mesh, const VolumeRefinement& R, const SimplexComplex3& refined,
                               int max_degree) {
  std::vector<Eigen::Triplet<double>> st[4], pt[4];
  std::vector<char> done[4];
  for (int k = 1; k <= max_degree; ++k) done[k].assign(size_t(refined.n_simplices(k)), 0);
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const VolumeMeshCell cell = volume_mesh_cell(mesh, R, refined, c, max_degree);
    const std::vector<int>* ids[4] = {&cell.vertices, &cell.edges, &cell.faces, nullptr};
    const std::vector<int> self{c};
    ids[3] = &self;
    for (int k = 0; k <= std::min(max_degree, 2); ++k) {
      const int n = int(ids[k]->size());
      REQUIRE(cell.star[k].rows() == n);
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) st[k].emplace_back((*ids[k])[size_t(a)], (*ids[k])[size_t(b)], cell.star[k](a, b));
    }
    if (max_degree >= 3) st[3].emplace_back(c, c, cell.star3);
    for (int k = 1; k <= max_degree; ++k) {
      REQUIRE(cell.P[k].rows() == Eigen::Index(cell.rows[k].size()));
      REQUIRE(cell.P[k].cols() == Eigen::Index(ids[k]->size()));
      for (size_t i = 0; i < cell.rows[k].size(); ++i) {
        const int row = cell.rows[k][i];
        if (done[k][size_t(row)]) continue;
        done[k][size_t(row)] = 1;
        for (Eigen::Index j = 0; j < cell.P[k].cols(); ++j)
          if (cell.P[k](Eigen::Index(i), j) != 0.0) pt[k].emplace_back(row, (*ids[k])[size_t(j)], cell.P[k](Eigen::Index(i), j));
      }
    }
  }
  const int sizes[4] = {mesh.n_vertices(), mesh.n_edges(), mesh.n_faces(), mesh.n_cells()};
  VolumeMeshDec out;
  for (int k = 0; k <= max_degree; ++k) {
    out.star[k].resize(sizes[k], sizes[k]);
    out.star[k].setFromTriplets(st[k].begin(), st[k].end());
    if (k == 0) continue;
    out.P[k].resize(refined.n_simplices(k), sizes[k]);
    out.P[k].setFromTriplets(pt[k].begin(), pt[k].end());
  }
  return out;
}

}  // namespace

TEST_CASE("volume mesh complex: the assembly into slots equals a triplet assembly of the cells' shares",
          "[volume][volume-dec][volume-mesh-complex]") {
  std::vector<Case> cases;
  cases.push_back({"jittered hexahedra", hex_grid_volume(3, 3, 2, {0.25, 41})});
  cases.push_back({"jittered tetrahedra", tet_grid_volume(2, 2, 2, {0.2, 43})});
  cases.push_back({"jittered pyramids", pyramid_grid_volume(2, 2, 2, {0.2, 47})});
  cases.push_back({"truncated octahedra", truncated_octahedra_volume(3, {0.15, 53})});
  cases.push_back({"Voronoi-like merged truncated octahedra",
                   test::merge_neighbour_cells(truncated_octahedra_volume(3, {0.15, 59}), 30)});
  cases.push_back({"prism over a 100-gon", test::prism_volume(100)});
  // Last: every 5th sub-tetrahedron flagged degenerate (zero contributions keep their entries).
  cases.push_back({"hexahedra with flagged sub-tetrahedra", hex_grid_volume(2, 2, 2, {0.2, 61})});
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& cs = cases[i];
    INFO(cs.name);
    VolumeRefinement R = refine_volume(cs.mesh);
    if (i + 1 == cases.size())
      for (size_t t = 0; t < R.tets.size(); t += 5) R.tets[t] = SubTet::Degenerate;
    const SimplexComplex3 refined = volume_refined_complex(cs.mesh, R);
    for (int degree : {3, 1}) {
      INFO("max_degree " << degree);
      const VolumeMeshDec D = volume_mesh_dec(cs.mesh, R, refined, degree);
      const VolumeMeshDec T = triplet_assembly(cs.mesh, R, refined, degree);
      for (int k = 0; k <= degree; ++k) {
        INFO("k = " << k);
        CHECK(identical(D.star[k], T.star[k]));
        if (k > 0) CHECK(identical(D.P[k], T.P[k]));
      }
      const std::array<SparseMatrix, 4> stars = volume_mesh_stars(cs.mesh, R, degree);
      for (int k = 0; k <= degree; ++k) CHECK(identical(stars[size_t(k)], T.star[k]));
      for (int k = 1; k <= degree; ++k) CHECK(identical(volume_mesh_prolongation(cs.mesh, R, refined, k), T.P[k]));
    }
  }
  // The cell's share refuses a cell out of range.
  const VolumeMesh hexes = hex_grid_volume(1, 1, 1);
  const VolumeRefinement Rh = refine_volume(hexes);
  CHECK_THROWS_AS(volume_mesh_cell(hexes, Rh, volume_refined_complex(hexes, Rh), 1), std::invalid_argument);
}

}  // namespace test_volume_mesh_complex
