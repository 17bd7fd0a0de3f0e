// tests/apps/applications/test_spectral_tools.cpp — HKS against implicit heat steps, WKS normalization,
// biharmonic and diffusion distances (symmetric, zero diagonal, monotone in k), the sphere's
// first band reproducing a sphere, invariances.
#include <catch2/catch.hpp>
#include <random>

#include "polydec/apps/applications/spectral_tools.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/operators/solvers/cholesky.h"
#include "tests/support/feec_meshes.h"
#include "tests/support/renumbered.h"

using namespace polydec;

namespace test_spectral_tools {

namespace {

Spectrum spectrum_of(const Mesh& mesh, int k) {
  SpectrumOptions o;
  o.k = k;
  return laplacian_spectrum(mesh, o);
}

}  // namespace

TEST_CASE("HKS equals the heat equation solved by implicit steps", "[spectral_tools]") {
  // A small non-planar polygon mesh, nearly all eigenpairs: the truncation after k terms is
  // below exp(-lambda_k t) at the tested times.
  const Mesh mesh = add_noise(test::torus(10, 6, 0.1, true), 0.1, 3);
  const int n = mesh.n_vertices();
  const Spectrum sp = spectrum_of(mesh, n - 1);
  const OperatorSet ops = build_operators(mesh, parse_laplacian("ours"), false);
  SparseMatrix M(n, n);
  M.setIdentity();
  M.diagonal() = ops.M_lumped;
  const double lmax = sp.eigenvalues[n - 2];
  for (double t : {20 / lmax, 100 / lmax}) {
    // u(t) of M u' = S u, u(0) = e_x / M_xx: implicit Euler with N and 2N steps, Richardson-extrapolated.
    auto heat = [&](int steps) {
      const double dt = t / steps;
      const SparseCholesky chol(SparseMatrix(M - dt * ops.S), "M - dt S");
      Eigen::MatrixXd U = Eigen::MatrixXd(M).diagonal().cwiseInverse().asDiagonal();
      for (int s = 0; s < steps; ++s) U = chol.solve(Eigen::MatrixXd(M * U));
      return U;
    };
    const Eigen::MatrixXd U1 = heat(400), U2 = heat(800);
    const Eigen::VectorXd diag = (2 * U2 - U1).diagonal();
    Eigen::VectorXd times(1);
    times << t;
    const Eigen::VectorXd hks = heat_kernel_signature(sp, times).col(0);
    INFO("t = " << t << ", max relative difference "
                << ((hks - diag).cwiseQuotient(diag)).cwiseAbs().maxCoeff());
    CHECK(((hks - diag).cwiseQuotient(diag)).cwiseAbs().maxCoeff() <= 1e-3);
  }
}

TEST_CASE("HKS and WKS: standard samples, positivity, invariances", "[spectral_tools]") {
  const Mesh mesh = add_noise(hex_sphere(2), 0.1, 5);
  const Spectrum sp = spectrum_of(mesh, 40);
  const Eigen::VectorXd t = hks_times(sp, 50);
  CHECK(t.size() == 50);
  CHECK(t[0] == Approx(4 * std::log(10.0) / sp.eigenvalues[39]));
  CHECK(t[49] == Approx(4 * std::log(10.0) / sp.eigenvalues[1]));
  const Eigen::MatrixXd hks = heat_kernel_signature(sp, t);
  CHECK(hks.minCoeff() > 0);
  // Large t: HKS tends to 1 / area (phi_0^2); decreasing in t at every vertex.
  for (int j = 1; j < 50; ++j) CHECK((hks.col(j) - hks.col(j - 1)).maxCoeff() <= 0);
  const WksSamples ws = wks_samples(sp, 60);
  const Eigen::MatrixXd wks = wave_kernel_signature(sp, ws.energies, ws.sigma);
  CHECK(wks.minCoeff() > 0);
  // sum_x M_x WKS(x, e) = 1: the weights are normalized and every phi_i has unit M-norm.
  const OperatorSet ops = build_operators(mesh, parse_laplacian("ours"), false);
  for (int j = 0; j < 60; ++j) CHECK(ops.M_lumped.dot(wks.col(j)) == Approx(1).epsilon(1e-8));

  // Scale s: lambda / s^2, phi / s, the standard times s^2 t: s^2 HKS and WKS * s^2 unchanged.
  const double s = 7;
  const Spectrum sps = spectrum_of(mesh.with_positions(s * mesh.positions()), 40);
  CHECK((s * s * heat_kernel_signature(sps, hks_times(sps, 50)) - hks).norm() <= 1e-7 * hks.norm());
  const WksSamples wss = wks_samples(sps, 60);
  CHECK((s * s * wave_kernel_signature(sps, wss.energies, wss.sigma) - wks).norm() <= 1e-7 * wks.norm());
  // Translation and renumbering.
  const Spectrum spt =
      spectrum_of(mesh.with_positions(mesh.positions().rowwise() + Eigen::RowVector3d(5, 1, -2)), 40);
  CHECK((heat_kernel_signature(spt, hks_times(spt, 50)) - hks).norm() <= 1e-7 * hks.norm());
  const std::vector<int> perm = test::random_permutation(mesh.n_vertices(), 3);
  const Spectrum spp = spectrum_of(test::renumbered(mesh, perm), 40);
  const Eigen::MatrixXd hksp = heat_kernel_signature(spp, hks_times(spp, 50));
  double d = 0;
  for (int v = 0; v < mesh.n_vertices(); ++v)
    d = std::max(d, (hksp.row(perm[size_t(v)]) - hks.row(v)).norm());
  CHECK(d <= 1e-7 * hks.norm());
}

TEST_CASE("biharmonic and diffusion distances: symmetric, zero diagonal, monotone in k", "[spectral_tools]") {
  for (const Mesh& mesh :
       {test::genus2(1, 0.1, true), add_noise(test::planar_grid(8, 6, 0.2, true), 0.1, 2)}) {
    const Spectrum sp = spectrum_of(mesh, 30);
    const double t = 1 / sp.eigenvalues[1];
    const int a = 3, b = mesh.n_vertices() / 2, c = mesh.n_vertices() - 2;
    for (int kind = 0; kind < 2; ++kind) {
      auto dist = [&](int src, int k) {
        return kind == 0 ? biharmonic_distance(sp, src, k) : diffusion_distance(sp, t, src, k);
      };
      const Eigen::VectorXd da = dist(a, 0), db = dist(b, 0), dc = dist(c, 0);
      CHECK(da[a] == 0);
      CHECK(db[b] == 0);
      CHECK(da[b] == Approx(db[a]).epsilon(1e-12));
      CHECK(da[c] == Approx(dc[a]).epsilon(1e-12));
      CHECK(da.minCoeff() >= 0);
      CHECK(da.maxCoeff() > 0);
      // The triangle inequality (an L2 distance of spectral embeddings).
      CHECK(da[c] <= da[b] + db[c] + 1e-12 * da.maxCoeff());
      for (int k = 3; k < 30; ++k) CHECK((dist(a, k + 1) - dist(a, k)).minCoeff() >= -1e-14 * da.maxCoeff());
    }
  }
}

TEST_CASE("the unit sphere filtered to its first band (l <= 1) is a sphere", "[spectral_tools]") {
  for (const Mesh& mesh : {hex_sphere(3), project_to_unit_sphere(cube_sphere(10))}) {
    const Spectrum sp = spectrum_of(mesh, 10);
    const OperatorSet ops = build_operators(mesh, parse_laplacian("ours"), false);
    const Eigen::MatrixX3d Y = lowpass_filter(sp, ops.M_lumped, mesh.positions(), 4);
    const Eigen::VectorXd r = Y.rowwise().norm();
    const double mean = r.mean();
    WARN(mesh.n_faces() << " faces: filtered radius in [" << r.minCoeff() << ", " << r.maxCoeff() << "]");
    CHECK((r.array() - mean).abs().maxCoeff() <= 5e-3 * mean);
    CHECK(std::abs(mean - 1) <= 0.02);
    // A projection: filtering twice changes nothing.
    CHECK((lowpass_filter(sp, ops.M_lumped, Y, 4) - Y).norm() <= 1e-8 * Y.norm());
  }
}

TEST_CASE("spectral tools reject bad arguments", "[spectral_tools]") {
  const Spectrum sp = spectrum_of(hex_sphere(1), 8);
  CHECK_THROWS_AS(biharmonic_distance(sp, -1), std::invalid_argument);
  CHECK_THROWS_AS(biharmonic_distance(sp, 0, 9), std::invalid_argument);
  CHECK_THROWS_AS(diffusion_distance(sp, 0.0, 0), std::invalid_argument);
  CHECK_THROWS_AS(log_spaced(0, 1, 3), std::invalid_argument);
}

}  // namespace test_spectral_tools
