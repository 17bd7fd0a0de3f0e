// tests/apps/applications/test_smoothing.cpp — conformalized mean curvature flow (eq. 28): the noisy sphere
// becomes round, the area and the centroid are kept, the flow commutes with scaling.
#include "polydec/apps/applications/curvature.h"
#include "polydec/apps/applications/smoothing.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_smoothing {

namespace {

// Standard deviation / mean of the distances to the area centroid.
double radius_spread(const Mesh& m) {
  const OperatorSet ops = build_operators(m, parse_laplacian("ours"), false);
  const Eigen::RowVector3d c = (ops.M_lumped.transpose() * m.positions()) / ops.M_lumped.sum();
  const Eigen::VectorXd r = (m.positions().rowwise() - c).rowwise().norm();
  return std::sqrt((r.array() - r.mean()).square().mean()) / r.mean();
}

}  // namespace

TEST_CASE("smoothing: the noisy sphere becomes a sphere (Figure 4)", "[apps]") {
  POLYDEC_SHARED_MESH(path, "noisy-sphere.off");
  // noisy-sphere.off's noise is tangential (its vertices lie on the unit sphere up to 1e-4);
  // add a random displacement of up to 0.3 mean edge lengths in every direction on top.
  const Mesh noisy = add_noise(read_mesh(path), 0.3, 11);
  SmoothingOptions o;
  CurvatureFlow flow(noisy, o);
  double spread = radius_spread(noisy);
  const double initial = spread;
  for (int i = 0; i < 10; ++i) {
    const Mesh& m = flow.step();
    const double s = radius_spread(m);
    CHECK(s < spread);  // monotone decrease
    spread = s;
    // area restored, centroid at the origin (relative to the size)
    const OperatorSet ops = build_operators(m, parse_laplacian("ours"), false);
    CHECK(ops.M_lumped.sum() == Approx(flow.area()).epsilon(1e-12));
    const Eigen::RowVector3d c = (ops.M_lumped.transpose() * m.positions()) / ops.M_lumped.sum();
    CHECK(c.norm() <= 1e-12 * std::sqrt(flow.area()));
  }
  INFO("initial spread " << initial << ", after 10 steps " << spread);
  // Measured: 0.0224 before, 0.0068 after one step, 0.00238 after ten (eps = 1e-3 * area).
  // The discrete flow does not keep an irregular polygonal sphere exactly round (a spread of
  // order 1e-3 remains, see the next test), so the bound is 0.003, i.e. 0.3% of the radius.
  CHECK(spread < 0.003);
}

TEST_CASE("smoothing: the flow commutes with scaling and keeps a round sphere round", "[apps]") {
  const Mesh sphere = cube_sphere(6);
  const double s = 1e4;
  SmoothingOptions o;
  CurvatureFlow a(sphere, o), b(sphere.with_positions(s * sphere.positions()), o);
  CHECK(b.time_step() == Approx(s * s * a.time_step()).epsilon(1e-12));
  for (int i = 0; i < 3; ++i) {
    const Eigen::MatrixX3d Xa = a.step().positions(), Xb = b.step().positions();
    CHECK((Xb / s - Xa).cwiseAbs().maxCoeff() <= 1e-9);
  }
  // A cube sphere starts exactly round (spread 0); the flow moves it by less than 0.1% of the
  // radius (measured 6.8e-4 after three steps).
  CHECK(radius_spread(a.mesh()) <= 1e-3);
}

TEST_CASE("smoothing: unlumped mass and bad options", "[apps]") {
  const Mesh sphere = add_noise(cube_sphere(6), 0.2, 7);
  SmoothingOptions o;
  o.lumped_mass = false;
  const std::vector<Mesh> steps = curvature_flow(sphere, 3, o);
  REQUIRE(steps.size() == 4);
  CHECK(radius_spread(steps[3]) < radius_spread(steps[0]));
  o.time_step = -1;
  CHECK_THROWS_AS(CurvatureFlow(sphere, o), std::invalid_argument);
}

}  // namespace test_smoothing
