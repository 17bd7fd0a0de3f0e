// tests/operators/registry/test_volume_laplacians.cpp — the volume method registry and the volume gradient
// and divergence ([volume-gradient]): S = D G exactly, G exact on linear functions (one constant
// vector on every sub-tetrahedron), D 1-orthogonality (the divergence of any field sums to zero),
// both cell-point rules, and the registry's names and errors; operators on a caller's refinement
// bitwise equal to those on a fresh one.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstring>
#include <random>

#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/operators/registry/volume_laplacians.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_laplacians {

namespace {

std::vector<std::pair<std::string, VolumeMesh>> meshes() {
  return {{"jittered hex 3x2x2", hex_grid_volume(3, 2, 2, {0.25, 7})},
          {"pyramids 2x2x2", pyramid_grid_volume(2, 2, 2, {0.2, 3})},
          {"truncated octahedra n=2", truncated_octahedra_volume(2)},
          {"jittered tets 2x2x2", tet_grid_volume(2, 2, 2, {0.2, 5})},
          {"hex torus", hex_torus_volume(8, 2, 2.0, 0.5)}};
}

}  // namespace

TEST_CASE("volume operators: S = D G, and S equals the volume Laplacian's", "[volume-gradient]") {
  for (const auto& [label, mesh] : meshes())
    for (const std::string method : {"ours", "polylaplace"}) {
      INFO(label << ", " << method);
      const OperatorSet ops = build_volume_operators(mesh, parse_volume_laplacian(method));
      CHECK(ops.name == method);
      CHECK(ops.n_input_vertices == mesh.n_vertices());
      CHECK(ops.mean_edge_length == Approx(mesh.mean_edge_length()));
      REQUIRE(ops.G.cols() == mesh.n_vertices());
      REQUIRE(ops.D.rows() == mesh.n_vertices());
      CHECK(test::relative_difference(SparseMatrix(ops.D * ops.G), ops.S) < 1e-12);
      VolumeRefinementOptions ro;
      ro.cell_rule = method == "ours" ? CellPointRule::SquaredVolume : CellPointRule::PolyLaplace;
      const VolumeRefinement r = refine_volume(mesh, ro);
      const VolumeLaplacian L = assemble_volume_laplacian(mesh, r);
      CHECK(test::relative_difference(ops.S, L.S) == 0.0);
      CHECK(test::relative_difference(ops.M, L.M) == 0.0);
      CHECK(ops.sub_tet_quality.n_degenerate == r.quality.n_degenerate);
      CHECK(ops.sub_tet_quality.n_inverted == r.quality.n_inverted);
      CHECK_FALSE(ops.volume_refinement.has_value());  // kept only when asked for
      // Without the gradient, on two threads, keeping the refinement: the same S, no G, the same
      // refinement as a fresh one.
      const OperatorSet plain =
          build_volume_operators(mesh, parse_volume_laplacian(method),
                                 {.with_gradient = false, .threads = 2, .keep_refinement = true});
      CHECK(plain.G.size() == 0);
      CHECK(test::relative_difference(plain.S, ops.S) == 0.0);
      REQUIRE(plain.volume_refinement.has_value());
      CHECK(plain.volume_refinement->cell_points == r.cell_points);
      CHECK(plain.volume_refinement->face_points == r.face_points);
      CHECK(plain.volume_refinement->cell_weights == r.cell_weights);
    }
}

TEST_CASE("volume gradient is exact on linear functions, divergence sums to zero", "[volume-gradient]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> n01;
  for (const auto& [label, mesh] : meshes()) {
    INFO(label);
    const VolumeRefinement r = refine_volume(mesh);
    const SparseMatrix G = volume_gradient(mesh, r);
    const Eigen::VectorXd w = sub_tet_volumes(mesh, r);
    REQUIRE(G.rows() == 3 * w.size());
    Eigen::VectorXd same_pass;
    volume_gradient(mesh, r, &same_pass);
    CHECK(same_pass == w);  // the gradient's own pass gives the same volumes, bit for bit
    CHECK(w.sum() == Approx(mesh.volume()).epsilon(1e-12));
    const Eigen::Vector3d a(0.3, -1.2, 0.7);
    const Eigen::VectorXd u = mesh.positions() * a + Eigen::VectorXd::Constant(mesh.n_vertices(), 2.5);
    const Eigen::VectorXd g = G * u;
    double worst = 0;
    for (Eigen::Index t = 0; t < w.size(); ++t)
      if (w[t] > 0) worst = std::max(worst, (g.segment<3>(3 * t) - a).norm());
    CHECK(worst < 1e-10 * a.norm());
    // D = -G^T W: 1^T D X = -(G 1)^T W X = 0 for any field X.
    const SparseMatrix D = volume_divergence(G, w);
    Eigen::VectorXd X(G.rows());
    for (Eigen::Index i = 0; i < X.size(); ++i) X[i] = n01(rng);
    const Eigen::VectorXd div = D * X;
    CHECK(std::abs(div.sum()) < 1e-12 * (D.cwiseAbs() * X.cwiseAbs()).sum());
  }
}

TEST_CASE("volume Laplacian registry: names and unknown methods", "[volume-gradient]") {
  const auto names = volume_laplacian_names();
  REQUIRE(names.size() >= 2);
  CHECK(names[0] == "ours");
  CHECK(std::find(names.begin(), names.end(), "polylaplace") != names.end());
  CHECK_THROWS_AS(parse_volume_laplacian("cotan"), std::invalid_argument);
  CHECK_THROWS_WITH(parse_volume_laplacian("aw11:0.5"), Catch::Contains("polylaplace"));
  LaplacianChoice surface = parse_laplacian("centroid");
  CHECK_THROWS_AS(build_volume_operators(hex_grid_volume(1, 1, 1), surface), std::invalid_argument);
}

TEST_CASE("volume gradient on the shared cubes: S = D G", "[volume-gradient]") {
  for (const std::string name : {"cube_pyramids_2.ovm", "cube_truncated_2.ovm", "noisycube.ovm"}) {
    POLYDEC_SHARED_MESH(path, "volume/" + name);
    INFO(name);
    const VolumeMesh mesh = read_volume_mesh(path);
    for (const std::string method : {"ours", "polylaplace"}) {
      const OperatorSet ops = build_volume_operators(mesh, parse_volume_laplacian(method));
      CHECK(test::relative_difference(SparseMatrix(ops.D * ops.G), ops.S) < 1e-12);
    }
  }
}

TEST_CASE("volume operators on a given refinement: bitwise the fresh one's, another rule or mesh refused",
          "[volume-gradient]") {
  const VolumeMesh mesh = truncated_octahedra_volume(2, {0.2, 5});
  auto same = [](const SparseMatrix& a, const SparseMatrix& b) {
    return a.rows() == b.rows() && a.nonZeros() == b.nonZeros() &&
           std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr()) &&
           std::equal(a.valuePtr(), a.valuePtr() + a.nonZeros(), b.valuePtr(),
                      [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; });
  };
  for (const std::string method : {"ours", "polylaplace", "diamond"}) {
    INFO(method);
    VolumeRefinementOptions ro;
    ro.cell_rule = method == "polylaplace" ? CellPointRule::PolyLaplace : CellPointRule::SquaredVolume;
    const VolumeRefinement r = refine_volume(mesh, ro);
    VolumeOperatorOptions given;
    given.refinement = &r;
    given.keep_refinement = true;
    const OperatorSet a = build_volume_operators(mesh, parse_volume_laplacian(method), given);
    const OperatorSet b = build_volume_operators(mesh, parse_volume_laplacian(method));
    CHECK(same(a.S, b.S));
    CHECK(same(a.M, b.M));
    CHECK(same(a.G, b.G));
    CHECK(same(a.D, b.D));
    CHECK(a.M_lumped == b.M_lumped);
    REQUIRE(a.volume_refinement);
    CHECK(a.volume_refinement->cell_points == r.cell_points);
    // The other cell-point rule, or a refinement of another mesh, is refused.
    VolumeRefinementOptions other = ro;
    other.cell_rule = method == "polylaplace" ? CellPointRule::SquaredVolume : CellPointRule::PolyLaplace;
    const VolumeRefinement wrong = refine_volume(mesh, other);
    given.refinement = &wrong;
    CHECK_THROWS_AS(build_volume_operators(mesh, parse_volume_laplacian(method), given), std::invalid_argument);
    const VolumeRefinement foreign = refine_volume(hex_grid_volume(2, 2, 2), ro);
    given.refinement = &foreign;
    CHECK_THROWS_AS(build_volume_operators(mesh, parse_volume_laplacian(method), given), std::invalid_argument);
  }
}

}  // namespace test_volume_laplacians
