// tests/apps/applications/volume/test_applications.cpp — the 3D Franke Poisson study and the unit ball's
// eigenvalues ([volume-apps]): the exact Laplacian against finite differences, second-order
// convergence on hex grids, decreasing errors on the shared cubes, linear precision, spherical
// Bessel zeros against known values, ball eigenvalues converging under refinement.
#include <catch2/catch.hpp>
#include <cmath>

#include "polydec/apps/applications/volume/poisson.h"
#include "polydec/apps/applications/volume/spectrum.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/operators/registry/volume_laplacians.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_applications {

TEST_CASE("franke3d_laplacian matches central finite differences of franke3d", "[volume-apps]") {
  const double h = 1e-4;
  for (double x : {0.1, 0.37, 0.5, 0.81})
    for (double y : {0.05, 0.44, 0.9})
      for (double z : {0.2, 0.55, 0.97}) {
        const double f0 = franke3d(x, y, z);
        const double fd = (franke3d(x + h, y, z) + franke3d(x - h, y, z) + franke3d(x, y + h, z) +
                           franke3d(x, y - h, z) + franke3d(x, y, z + h) + franke3d(x, y, z - h) - 6 * f0) /
                          (h * h);
        const double exact = franke3d_laplacian(x, y, z);
        CHECK(std::abs(fd - exact) <= 1e-5 * std::max(1.0, std::abs(exact)));
      }
}

TEST_CASE("3D Franke Poisson on hex grids converges with slope 2 in both norms", "[volume-apps]") {
  // Lumped mass, n = 4, 8, 16: slopes 2.95 / 2.72 (4 -> 8, pre-asymptotic), then about 2.
  // Galerkin mass (the default), n = 4, 8, 16, 24: slopes 1.39, 1.69, 1.89: asymptotically 2 from
  // below, so its test pair is 16 -> 24.
  for (const bool lumped : {true, false}) {
    const std::vector<int> ns = lumped ? std::vector<int>{4, 8, 16} : std::vector<int>{8, 16, 24};
    std::vector<VolumeMesh> meshes;
    std::vector<std::string> labels;
    for (int n : ns) {
      meshes.push_back(hex_grid_volume(n, n, n));
      labels.push_back(std::to_string(n));
    }
    const auto s = volume_franke_convergence("hex grid", meshes, labels, lumped);
    REQUIRE(s.l2_slopes.size() == 2);
    for (size_t i = 0; i < 2; ++i) {
      INFO((lumped ? "lumped" : "Galerkin")
           << " level " << i << ": l2 slope " << s.l2_slopes[i] << ", rms slope " << s.rms_slopes[i]);
      CHECK(s.errors[i + 1].l2_error < s.errors[i].l2_error);
      CHECK(s.errors[i + 1].rms_error < s.errors[i].rms_error);
    }
    INFO((lumped ? "lumped" : "Galerkin")
         << ": last slopes " << s.l2_slopes.back() << " / " << s.rms_slopes.back());
    CHECK(std::abs(s.l2_slopes.back() - 2) < 0.3);
    CHECK(std::abs(s.rms_slopes.back() - 2) < 0.3);
  }
}

TEST_CASE("3D Franke Poisson errors decrease on the shared cubes", "[volume-apps]") {
  const std::vector<std::pair<std::string, int>> families{{"cube_hexahedron", 3}, {"cube_tetrahedron", 2}};
  for (const auto& [family, levels] : families) {
    std::vector<VolumeMesh> meshes;
    std::vector<std::string> labels;
    for (int l = 1; l <= levels; ++l) {
      const std::string name = family + "_" + std::to_string(l) + ".ovm";
      const std::string path = test::shared_path("volume/" + name);
      if (path.empty()) {
        WARN("skipped: ../shared/data/volume/" << name << " not found");
        return;
      }
      meshes.push_back(read_volume_mesh(path));
      labels.push_back(name);
    }
    const auto s = volume_franke_convergence(family, meshes, labels);
    for (size_t i = 1; i < s.errors.size(); ++i) {
      INFO(family << " level " << i + 1 << ": l2 " << s.errors[i].l2_error << " rms "
                  << s.errors[i].rms_error);
      CHECK(s.errors[i].h < s.errors[i - 1].h);
      CHECK(s.errors[i].l2_error < s.errors[i - 1].l2_error);
      CHECK(s.errors[i].rms_error < s.errors[i - 1].rms_error);
    }
  }
}

TEST_CASE("volume Poisson reproduces a linear function at interior vertices (shared cubes, level 2)",
          "[volume-apps]") {
  const auto linear = [](const Eigen::Vector3d& p) { return 0.3 + 1.2 * p.x() - 0.7 * p.y() + 2.1 * p.z(); };
  const auto zero = [](const Eigen::Vector3d&) { return 0.0; };
  for (const std::string family :
       {"cube_hexahedron", "cube_pyramids", "cube_truncated", "cube_tetrahedron"}) {
    const std::string path = test::shared_path("volume/" + family + "_2.ovm");
    if (path.empty()) {
      WARN("skipped: ../shared/data/volume/" << family << "_2.ovm not found");
      continue;
    }
    const VolumeMesh mesh = read_volume_mesh(path);
    for (bool lumped : {false, true}) {
      const auto e =
          volume_dirichlet_poisson(build_volume_operators(mesh, LaplacianChoice{}, {.with_gradient = false}),
                                   mesh, linear, zero, lumped);
      REQUIRE(e.n_boundary < e.n_vertices);  // interior vertices exist
      const double scale = e.exact.cwiseAbs().maxCoeff();
      INFO(family << (lumped ? " lumped" : " Galerkin") << ": max error "
                  << (e.solution - e.exact).cwiseAbs().maxCoeff());
      CHECK((e.solution - e.exact).cwiseAbs().maxCoeff() <= 1e-10 * scale);
    }
  }
}

TEST_CASE("spherical Bessel functions and their zeros", "[volume-apps]") {
  // Closed forms: j_2 = (3/x^3 - 1/x) sin x - 3 cos x / x^2; downward recurrence agrees at large l too.
  for (double x : {0.3, 1.0, 4.0, 12.5}) {
    const double j2 = (3 / (x * x * x) - 1 / x) * std::sin(x) - 3 * std::cos(x) / (x * x);
    CHECK(spherical_bessel_j(2, x) == Approx(j2).epsilon(1e-12).margin(1e-14));
    // Recurrence identity j_{l-1} + j_{l+1} = (2l+1)/x j_l at l = 7.
    CHECK(spherical_bessel_j(6, x) + spherical_bessel_j(8, x) ==
          Approx(15 / x * spherical_bessel_j(7, x)).epsilon(1e-10).margin(1e-300));
    // Derivative against central differences.
    const double d = 1e-6;
    CHECK(spherical_bessel_j_derivative(3, x) ==
          Approx((spherical_bessel_j(3, x + d) - spherical_bessel_j(3, x - d)) / (2 * d))
              .epsilon(1e-6)
              .margin(1e-9));
  }
  const auto z0 = spherical_bessel_zeros(0, 3);
  for (int n = 0; n < 3; ++n) CHECK(z0[n] == Approx((n + 1) * M_PI).epsilon(1e-13));
  CHECK(spherical_bessel_zeros(1, 1)[0] == Approx(4.4934094579).epsilon(1e-10));
  CHECK(spherical_bessel_zeros(1, 1, true)[0] == Approx(2.0815759778).epsilon(1e-10));
  // j_0' = -j_1: the derivative's zeros of l = 0 are those of j_1.
  CHECK(spherical_bessel_zeros(0, 2, true)[1] == Approx(spherical_bessel_zeros(1, 2)[1]).epsilon(1e-13));

  const auto d = ball_eigenvalues(10, true);
  REQUIRE(d.size() == 10);
  CHECK(d[0].lambda == Approx(M_PI * M_PI).epsilon(1e-13));
  for (int i = 1; i <= 3; ++i) CHECK(d[i].l == 1);               // j_{1,1} = 4.49 with multiplicity 3
  for (int i = 4; i <= 8; ++i) CHECK(d[i].l == 2);               // j_{2,1} = 5.76 with multiplicity 5
  CHECK(d[9].lambda == Approx(4 * M_PI * M_PI).epsilon(1e-13));  // j_{0,2} = 2 pi (6.28 < j_{3,1} = 6.99)
  const auto nm = ball_eigenvalues(5, false);
  CHECK(nm[0].lambda == 0);
  for (int i = 1; i <= 3; ++i) CHECK(nm[i].lambda == Approx(2.0815759778 * 2.0815759778).epsilon(1e-9));
  CHECK(nm[4].l == 2);  // j'_{2,1} = 3.34
}

TEST_CASE("hexahedral ball eigenvalues converge to the unit ball's", "[volume-apps]") {
  const int k = 10;
  for (bool dirichlet : {true, false}) {
    const BallSpectrum coarse = ball_spectrum(8, k, dirichlet);
    const BallSpectrum fine = ball_spectrum(16, k, dirichlet);
    double max_coarse = 0, max_fine = 0;
    for (int i = dirichlet ? 0 : 1; i < k; ++i) {
      max_coarse = std::max(max_coarse, coarse.relative_error[i]);
      max_fine = std::max(max_fine, fine.relative_error[i]);
    }
    INFO((dirichlet ? "Dirichlet" : "Neumann")
         << ": max relative error " << max_coarse << " (n = 8), " << max_fine << " (n = 16)");
    CHECK(max_fine < max_coarse);
    if (dirichlet) CHECK(max_fine < 0.05);
    if (!dirichlet) CHECK(std::abs(fine.eigenvalues[0]) < 1e-8);  // the constants
    for (int i = 0; i + 1 < k; ++i) CHECK(fine.eigenvalues[i] <= fine.eigenvalues[i + 1]);
    // No copy of a repeated eigenvalue missed: each discrete one lies within 10% of its analytic partner.
    for (int i = dirichlet ? 0 : 1; i < k; ++i) CHECK(fine.relative_error[i] < 0.1);
  }
}

}  // namespace test_volume_applications
