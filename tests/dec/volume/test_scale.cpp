// tests/dec/volume/test_scale.cpp — volumes at extreme scales: the refinement (face and cell points,
// weights, sub-tetrahedron flags) is the unit mesh's scaled, from 1e-150 to 1e150 and for
// coordinates up to kMaxVolumeCoordinate; the operators and stars are the unit mesh's times
// s^power wherever those entries are representable, and refused with a message naming the
// quantity and the edge where they are not (never NaN, Inf or silent zeros).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/dec/volume/refinement.h"
#include "polydec/operators/registry/volume_laplacians.h"
#include "polydec/operators/volume/laplacian.h"

using namespace polydec;

namespace test_volume_scale {
namespace {

struct Case {
  std::string name;
  VolumeMesh mesh;
};

// Small meshes with every kind of face the refinement meets: non-planar jittered quads,
// triangles, hexagons of truncated octahedra, pyramids.
std::vector<Case> cases() {
  return {{"jittered truncated octahedra", truncated_octahedra_volume(1, {0.15, 3})},
          {"jittered hexahedra", hex_grid_volume(2, 2, 2, {0.2, 5})},
          {"jittered tetrahedra", tet_grid_volume(2, 1, 1, {0.2, 7})},
          {"pyramids", pyramid_grid_volume(1, 1, 2)}};
}

VolumeMesh scaled(const VolumeMesh& mesh, double s) { return mesh.with_positions(mesh.positions() * s); }

double max_abs(const Eigen::MatrixXd& A) { return A.size() ? A.cwiseAbs().maxCoeff() : 0.0; }
double max_abs(const std::vector<double>& v) {
  return max_abs(Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size())).eval());
}
double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double m = 0;
  for (size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

// max |A 2^-power - B| / max |B| (A at scale 2^k, B at scale 1). The patterns may differ by entries
// that are round-off in one and exactly zero in the other (prolongation entries that cancel).
double scaled_difference(const SparseMatrix& A, const SparseMatrix& B, int power) {
  REQUIRE(A.rows() == B.rows());
  REQUIRE(A.cols() == B.cols());
  SparseMatrix a = A;
  for (Eigen::Index k = 0; k < a.nonZeros(); ++k) {
    REQUIRE(std::isfinite(a.valuePtr()[k]));
    a.valuePtr()[k] = std::ldexp(a.valuePtr()[k], -power);
  }
  const SparseMatrix d = a - B;
  const double m = d.nonZeros() ? d.coeffs().cwiseAbs().maxCoeff() : 0.0;
  return m / B.coeffs().cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("volume refinement: the unit mesh's points, weights and flags at every scale from 1e-150 to 1e150",
          "[volume-scale]") {
  const double scales[] = {0x1p-500, 1e-150, 0x1p-100, 0x1p70, 1e150, 0x1p500, 1e280};
  for (const CellPointRule rule : {CellPointRule::SquaredVolume, CellPointRule::PolyLaplace})
    for (const Case& c : cases()) {
      VolumeRefinementOptions options;
      options.cell_rule = rule;
      const VolumeRefinement unit = refine_volume(c.mesh, options);
      REQUIRE(unit.quality.n_degenerate == 0);
      for (const double s : scales) {
        CAPTURE(c.name, to_string(rule), s);
        const VolumeMesh m = scaled(c.mesh, s);
        const VolumeRefinement R = refine_volume(m, options);
        CHECK(R.quality.n_degenerate == 0);
        CHECK(R.quality.n_inverted == unit.quality.n_inverted);
        CHECK(R.tets == unit.tets);
        // Affine weights do not depend on the scale (round-off of the scaled route only).
        CHECK(max_difference(R.face_weights, unit.face_weights) <= 1e-12 * max_abs(unit.face_weights));
        CHECK(max_difference(R.cell_weights, unit.cell_weights) <= 1e-12 * max_abs(unit.cell_weights));
        // Points: s times the unit mesh's, relative to the mesh's size s (the decimal scales round
        // each coordinate, hence 1e-12 rather than round-off).
        const double size = s * max_abs(c.mesh.positions());
        CHECK(max_abs(R.face_points - unit.face_points * s) <= 1e-12 * size);
        CHECK(max_abs(R.cell_points - unit.cell_points * s) <= 1e-12 * size);
        CHECK(R.face_points.allFinite());
        CHECK(R.cell_points.allFinite());
      }
    }
}

TEST_CASE("volume refinement far from the origin: cells of size 1e-104 at 1e-100, of 1e146 at 1e150",
          "[volume-scale]") {
  const VolumeMesh base = truncated_octahedra_volume(1, {0.15, 3});
  const VolumeRefinement unit = refine_volume(base);
  for (const auto& [size, offset] : {std::pair{1e-104, 1e-100}, std::pair{1e146, 1e150}}) {
    CAPTURE(size, offset);
    Eigen::MatrixX3d X = base.positions() * size;
    X.rowwise() += Eigen::RowVector3d(offset, -offset, 0.5 * offset);
    const VolumeRefinement R = refine_volume(base.with_positions(X));
    CHECK(R.quality.n_degenerate == 0);
    CHECK(R.tets == unit.tets);
    // The offset costs the digits of the coordinates themselves (1e-4 of the offset is the cells' size).
    CHECK(max_difference(R.cell_weights, unit.cell_weights) <= 1e-8 * max_abs(unit.cell_weights));
  }
}

TEST_CASE("volume Laplacian, gradient and stars: the unit mesh's times s^power where representable",
          "[volume-scale]") {
  for (const Case& c : cases()) {
    const VolumeRefinement R1 = refine_volume(c.mesh);
    const VolumeLaplacian L1 = assemble_volume_laplacian(c.mesh, R1);
    const SparseMatrix G1 = volume_gradient(c.mesh, R1);
    const VolumeDec D1 = volume_dec(c.mesh, R1, VolumeDecOptions{.max_degree = 3, .complex = DecComplex::Mesh});
    for (const int k : {-290, -100, 80, 290}) {
      CAPTURE(c.name, k);
      const VolumeMesh m = scaled(c.mesh, std::ldexp(1.0, k));
      const VolumeRefinement R = refine_volume(m);
      const VolumeLaplacian L = assemble_volume_laplacian(m, R);
      CHECK(scaled_difference(L.S, L1.S, k) <= 1e-12);
      CHECK(scaled_difference(L.M, L1.M, 3 * k) <= 1e-12);
      CHECK(scaled_difference(volume_gradient(m, R), G1, -k) <= 1e-12);
      if (k < -100 || k > 100) continue;  // the mesh complex's stars: checked at 2^-100 and 2^80 only
      const VolumeDec D = volume_dec(m, R, VolumeDecOptions{.max_degree = 3, .complex = DecComplex::Mesh});
      for (int j = 0; j <= 3; ++j) {
        CAPTURE(j);
        CHECK(scaled_difference(D.star[j], D1.star[j], (3 - 2 * j) * k) <= 1e-12);
        CHECK(scaled_difference(D.P[j], D1.P[j], 0) <= 1e-12);
      }
    }
  }
}

TEST_CASE("volume operators beyond double range are refused, naming the quantity and the edge",
          "[volume-scale]") {
  const VolumeMesh base = hex_grid_volume(2, 2, 2, {0.2, 5});
  for (const double s : {1e-150, 1e150}) {
    CAPTURE(s);
    const VolumeMesh m = scaled(base, s);
    const VolumeRefinement R = refine_volume(m);
    // Mass entries would be s^3: 1e+-450.
    CHECK_THROWS_WITH(assemble_volume_laplacian(m, R),
                      Catch::Contains("mass matrix") && Catch::Contains("rescale the mesh") && Catch::Contains("edge"));
    CHECK_THROWS_AS(build_volume_operators(m, parse_volume_laplacian("ours"), {}), InvalidMeshError);
    CHECK_THROWS_WITH(volume_dec(m, R, VolumeDecOptions{.max_degree = 3, .complex = DecComplex::Mesh}),
                      Catch::Contains("star0") && Catch::Contains("length^"));
    // The stiffness alone (s^1) holds: one cell's, from the kernel, is the unit cell's times s.
    Eigen::MatrixXd S, S1;
    cell_matrices(m, R, 3, &S, nullptr);
    cell_matrices(base, refine_volume(base), 3, &S1, nullptr);
    CHECK(S.allFinite());
    CHECK(max_abs(S / s - S1) <= 1e-12 * max_abs(S1));
  }
  // Star1 (s^1) and star2 (s^-1) alone are representable at 1e150.
  const VolumeMesh big = scaled(base, 1e150);
  CHECK_NOTHROW(check_length_power(big, 1, "star1"));
  CHECK_NOTHROW(check_length_power(big, -1, "star2"));
  CHECK_THROWS_AS(check_length_power(big, -3, "star3"), InvalidMeshError);
  // Several quantities in one pass: the first one out of range, in the given order, is named.
  CHECK_NOTHROW(check_length_powers(big, {{1, "star1"}, {-1, "star2"}, {0, "a count"}}));
  CHECK_THROWS_WITH(check_length_powers(big, {{1, "star1"}, {-3, "star3"}, {3, "star0"}}),
                    Catch::Contains("star3") && !Catch::Contains("star0"));
  CHECK_THROWS_WITH(check_length_powers(big, star_length_powers(3)), Catch::Contains("star0's entries"));
  CHECK_NOTHROW(check_length_powers(big, {star_length_powers(2)[1], star_length_powers(2)[2]}));
  const VolumeMesh small = scaled(base, 1e-150);
  CHECK_THROWS_WITH(check_length_powers(small, {{-1, "star2"}, {3, "star0"}}), Catch::Contains("star0"));
}

TEST_CASE("volume mesh measures hold at coordinates up to kMaxVolumeCoordinate", "[volume-scale]") {
  const VolumeMesh base = truncated_octahedra_volume(1, {0.15, 3});
  for (const int k : {-480, 300, 990}) {
    CAPTURE(k);
    const double s = std::ldexp(1.0, k);
    const VolumeMesh m = scaled(base, s);
    CHECK(m.bounding_box_diagonal() == Approx(base.bounding_box_diagonal() * s).epsilon(1e-14));
    CHECK(m.mean_edge_length() == Approx(base.mean_edge_length() * s).epsilon(1e-14));
    CHECK(m.rms_radius() == Approx(base.rms_radius() * s).epsilon(1e-14));
    // Cell volumes s^3: representable at 2^300; at 2^990 and 2^-480 refused with the cell and the
    // size named, never inf or a false zero.
    if (3 * k < 1000 && 3 * k > -1000) {
      for (int c = 0; c < base.n_cells(); ++c)
        CHECK(std::ldexp(m.cell_volume(c), -3 * k) == Approx(base.cell_volume(c)).epsilon(1e-14));
    } else {
      CHECK_THROWS_WITH(m.cell_volume(0), Catch::Contains("cell 0") && Catch::Contains(k > 0 ? "1e+89" : "1e-43"));
      CHECK_THROWS_AS(m.volume(), InvalidMeshError);
    }
  }
  // Orientation: cells listed inward at 2^900 (volumes beyond double) are still turned outward.
  PolyhedronSoup soup;
  soup.positions = base.positions() * 0x1p900;
  soup.face_offsets = base.face_offsets();
  soup.face_indices = base.face_indices();
  for (int c = 0; c < base.n_cells(); ++c) {
    std::vector<int> hf(base.cell(c).begin(), base.cell(c).end());
    for (int& h : hf) h ^= 1;
    soup.add_cell(hf);
  }
  const VolumeMesh inward(std::move(soup));
  for (int c = 0; c < base.n_cells(); ++c)
    CHECK(std::vector<int>(inward.cell(c).begin(), inward.cell(c).end()) ==
          std::vector<int>(base.cell(c).begin(), base.cell(c).end()));
  Eigen::MatrixX3d X = base.positions();
  X(0, 0) = 2 * kMaxVolumeCoordinate;
  CHECK_THROWS_WITH(base.with_positions(X), Catch::Contains("vertex 0") && Catch::Contains("above the limit"));
}

}  // namespace test_volume_scale
