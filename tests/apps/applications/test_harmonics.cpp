// tests/apps/applications/test_harmonics.cpp — spherical harmonics (closed forms, orthonormality) and the
// paper's Table 3 error of eq. (30) on the unit-sphere meshes.
#include <cmath>
#include <numbers>

#include "polydec/apps/applications/harmonics.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "tests/support/paper_spheres.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_harmonics {

namespace {

Mesh unit_sphere_mesh(const std::string& path) { return project_to_unit_sphere(read_mesh(path)); }

}  // namespace

TEST_CASE("harmonics: associated Legendre functions match closed forms (Condon-Shortley phase)", "[apps]") {
  for (double x : {-0.9, -0.3, 0.0, 0.4, 0.95}) {
    const double s = std::sqrt(1 - x * x);
    CHECK(associated_legendre(0, 0, x) == Approx(1.0));
    CHECK(associated_legendre(1, 1, x) == Approx(-s));
    CHECK(associated_legendre(2, 0, x) == Approx(0.5 * (3 * x * x - 1)));
    CHECK(associated_legendre(2, 1, x) == Approx(-3 * x * s));
    CHECK(associated_legendre(3, 3, x) == Approx(-15 * s * s * s));
    CHECK(associated_legendre(4, 2, x) == Approx(7.5 * (7 * x * x - 1) * s * s));
  }
}

TEST_CASE("harmonics: band 1 is the coordinates with the y axis as polar axis", "[apps]") {
  const double c = std::sqrt(3.0 / (4.0 * std::numbers::pi));
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.3, -0.5, 0.8), Eigen::Vector3d(-0.7, 0.1, -0.2)}) {
    const Eigen::Vector3d u = p.normalized();
    CHECK(spherical_harmonic(p, 1, 0) == Approx(c * u.y()));
    CHECK(spherical_harmonic(p, 1, 1) == Approx(c * u.z()));
    CHECK(spherical_harmonic(p, 1, -1) == Approx(c * u.x()));
  }
}

TEST_CASE("harmonics: Y_l^m are orthonormal under the mass of a fine sphere", "[apps]") {
  POLYDEC_SHARED_MESH(path, "quad-sphere.off");
  const Mesh sphere = unit_sphere_mesh(path);
  const OperatorSet ops = build_operators(sphere, parse_laplacian("ours"), false);
  std::vector<Eigen::VectorXd> Y;
  for (int l = 0; l <= 3; ++l)
    for (int m = -l; m <= l; ++m) {
      Eigen::VectorXd y(sphere.n_vertices());
      for (int v = 0; v < sphere.n_vertices(); ++v) y[v] = spherical_harmonic(sphere.position(v), l, m);
      Y.push_back(y);
    }
  // Quadrature with the Galerkin mass of a 512-face sphere, exact up to O(h^2) and growing with
  // l: measured max |G_aa - 1| = 0.075, max |G_ab| = 0.013 for l <= 3.
  double max_off = 0, max_diag = 0;
  for (size_t a = 0; a < Y.size(); ++a)
    for (size_t b = 0; b < Y.size(); ++b) {
      const double g = Y[a].dot(ops.M * Y[b]);
      if (a == b)
        max_diag = std::max(max_diag, std::abs(g - 1));
      else
        max_off = std::max(max_off, std::abs(g));
    }
  CHECK(max_diag <= 0.1);
  CHECK(max_off <= 0.02);
}

// Reference values: the authors' program (Table 3, l = 1..8), tolerance 1% relative.
TEST_CASE("harmonics: Table 3 error on REGULAR and NOISY SPHERE", "[apps]") {
  POLYDEC_SHARED_MESH(regular_path, "quad-sphere.off");
  POLYDEC_SHARED_MESH(noisy_path, "noisy-sphere.off");
  const HarmonicsError regular = spherical_harmonics_error(unit_sphere_mesh(regular_path));
  const HarmonicsError noisy = spherical_harmonics_error(unit_sphere_mesh(noisy_path));
  CHECK(regular.sum(8) == Approx(0.039341).epsilon(0.01));
  CHECK(noisy.sum(8) == Approx(0.064276).epsilon(0.01));
  // The caption's l = 1..9 adds a ninth, positive band.
  CHECK(regular.sum(9) > regular.sum(8));
  CHECK(regular.band_error.size() == 9);
  // The per-vertex shares add up to the total.
  CHECK(regular.vertex_error.sum() == Approx(regular.sum(9)).epsilon(1e-10));
}

TEST_CASE("harmonics: Table 3 error on HEX and FINE SPHERE", "[apps]") {
  POLYDEC_SHARED_MESH(path, "unit-sphere.off");
  HarmonicsOptions o;
  o.max_band = 8;
  CHECK(spherical_harmonics_error(test::hex_sphere(path).ops, o).sum(8) == Approx(7.411e-7).epsilon(0.01));
  CHECK(spherical_harmonics_error(test::fine_sphere(path).ops, o).sum(8) == Approx(3.168e-4).epsilon(0.01));
}

}  // namespace test_harmonics
