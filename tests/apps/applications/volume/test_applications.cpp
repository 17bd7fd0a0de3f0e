// tests/apps/applications/volume/test_applications.cpp — the 3D Franke Poisson study and the unit ball's
// eigenvalues ([volume-apps]): the exact Laplacian against finite differences, second-order
// convergence on hex grids, decreasing errors on the shared cubes, linear precision, spherical
// Bessel zeros against known values, ball eigenvalues converging under refinement.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>

#include "polydec/apps/applications/volume/poisson.h"
#include "polydec/apps/applications/volume/spectrum.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/hodge_star.h"
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

namespace test_volume_applications {
namespace {

// How many of `values` lie below `zero`.
int count_below(const Eigen::VectorXd& values, double zero) {
  int n = 0;
  for (double v : values) n += v < zero;
  return n;
}

// Every value of `sub` that is at least `floor` and below `ceiling` has as many copies in `super`
// (within `tol` relative) as in `sub`; returns the number of values checked.
int contained(const Eigen::VectorXd& sub, const Eigen::VectorXd& super, double floor, double ceiling, double tol) {
  int checked = 0;
  for (double v : sub) {
    if (v < floor || v >= ceiling) continue;
    int in_sub = 0, in_super = 0;
    for (double w : sub) in_sub += std::abs(w - v) <= tol * v;
    for (double w : super) in_super += std::abs(w - v) <= tol * v;
    INFO("eigenvalue " << v);
    CHECK(in_super >= in_sub);
    ++checked;
  }
  return checked;
}

}  // namespace

// The 1-, 2- and 3-form spectra of `mesh` (first Betti number b1; b2 = b3 = 0) on both complexes
// with both 0-form masses: real, ascending, non-negative, zero eigenvalues = Betti numbers, Hodge
// parts summing to the eigenforms, star-orthonormal eigenvectors, and the eigenvalues d carries
// from one degree to the next. Adds the eigenvalues compared per relation to `checked`.
void check_volume_form_spectra(const char* name, const VolumeMesh& mesh, int b1, int checked[3]) {
  for (DecComplex complex : {DecComplex::Mesh, DecComplex::Complete})
    for (bool lumped : {true, false}) {
      INFO(name << ", " << to_string(complex) << " complex, " << (lumped ? "lumped" : "Galerkin") << " M0");
      double volume = 0;
      for (int c = 0; c < mesh.n_cells(); ++c) volume += mesh.cell_volume(c);
      const double zero = 1e-8 / std::pow(volume, 2.0 / 3.0);
      SpectrumOptions fo;
      fo.k = 12;
      fo.lumped_mass = lumped;
      const Spectrum f = volume_laplacian_spectrum(mesh, false, fo);
      FormSpectrum s[4];
      for (int degree = 1; degree <= 3; ++degree) {
        FormSpectrumOptions o;
        o.degree = degree;
        o.k = 24;
        o.lumped_mass = lumped;
        o.complex = complex;
        s[degree] = volume_form_spectrum(mesh, o);
        INFO("degree " << degree);
        const Eigen::VectorXd& ev = s[degree].eigenvalues;
        // Real, ascending, non-negative; zero eigenvalues = b_k (b2 = b3 = 0 for both shapes).
        CHECK(ev.allFinite());
        CHECK(ev.minCoeff() > -zero);
        for (Eigen::Index i = 1; i < ev.size(); ++i) CHECK(ev[i] >= ev[i - 1]);
        CHECK(count_below(ev, zero) == (degree == 1 ? b1 : 0));
        // The eigenforms' Hodge parts sum to them; a zero eigenvalue's form is harmonic, a non-zero
        // one's harmonic part is round-off.
        const FormSpectrum& sp = s[degree];
        REQUIRE(sp.harmonic.cols() == ev.size());
        for (Eigen::Index i = 0; i < ev.size(); ++i) {
          CHECK((sp.exact.col(i) + sp.coexact.col(i) + sp.harmonic.col(i) - sp.eigenvectors.col(i)).norm() <=
                1e-12 * sp.eigenvectors.col(i).norm());
          if (ev[i] < zero)
            CHECK(sp.kinds[size_t(i)] == FormKind::Harmonic);
          else
            CHECK(sp.norm_harmonic[i] < 1e-6);
          if (degree == 3) CHECK(sp.norm_coexact[i] == 0.0);
        }
      }
      // Star-orthonormal eigenvectors (on the mesh complex star1 is the one of volume_dec).
      if (complex == DecComplex::Mesh) {
        const VolumeRefinement R = refine_volume(mesh);
        const VolumeDec D = volume_dec(mesh, R, VolumeDecOptions{.max_degree = 3, .complex = DecComplex::Mesh});
        for (int degree = 1; degree <= 3; ++degree) {
          const Eigen::MatrixXd& W = s[degree].eigenvectors;
          const Eigen::MatrixXd G = W.transpose() * (D.star[degree] * W);
          CHECK((G - Eigen::MatrixXd::Identity(G.rows(), G.cols())).norm() < 1e-8);
        }
      }
      // d0 maps the non-zero function eigenpairs to 1-form ones, d1 the co-exact 1-forms' to
      // 2-form ones, d2 the 2-forms' to 3-form ones, each to ~1e-8 relative; and every 3-form
      // eigenvalue is a 2-form one (star2^-1 d2^T star3 maps back). Checked below the largest value
      // computed on the receiving side (a copy beyond it would not be seen).
      checked[0] += contained(f.eigenvalues, s[1].eigenvalues, 1e3 * zero, s[1].eigenvalues.maxCoeff() * (1 - 1e-6), 1e-8);
      Eigen::VectorXd coexact1(0);
      for (Eigen::Index i = 0; i < s[1].eigenvalues.size(); ++i)
        if (s[1].kinds[size_t(i)] == FormKind::Coexact) {
          coexact1.conservativeResize(coexact1.size() + 1);
          coexact1[coexact1.size() - 1] = s[1].eigenvalues[i];
        }
      checked[1] += contained(coexact1, s[2].eigenvalues, 1e3 * zero, s[2].eigenvalues.maxCoeff() * (1 - 1e-6), 1e-8);
      checked[2] +=
          contained(s[3].eigenvalues, s[2].eigenvalues, 1e3 * zero, s[2].eigenvalues.maxCoeff() * (1 - 1e-6), 1e-8);
    }
}

// Two test cases (one a shape) so that the suite runs them side by side.
TEST_CASE("volume form spectra on a jittered cube: Betti numbers, d maps eigenforms, star-orthonormal, both complexes",
          "[volume-apps][volume-form-spectrum]") {
  // A jittered hex grid of the cube [0, pi]^3 (b1 = 0).
  const VolumeMesh grid = hex_grid_volume(3, 3, 3, {0.2, 71});
  const VolumeMesh cube = grid.with_positions(grid.positions() * M_PI);
  int checked[3] = {0, 0, 0};
  check_volume_form_spectra("cube [0, pi]^3", cube, 0, checked);
  // Each relation exercised (the complete complex's 3-form values lie above its 24 smallest 2-form
  // ones, so the third relation is the mesh complex's).
  INFO("eigenvalues compared: " << checked[0] << ", " << checked[1] << ", " << checked[2]);
  for (int r = 0; r < 3; ++r) CHECK(checked[r] >= 6);
  FormSpectrumOptions bad;
  bad.degree = 4;
  CHECK_THROWS_AS(volume_form_spectrum(cube, bad), std::invalid_argument);
  bad.degree = 2;
  bad.k = 1000000;
  CHECK_THROWS_AS(volume_form_spectrum(cube, bad), std::invalid_argument);
}

TEST_CASE("volume form spectra on a solid torus: one harmonic 1-form, d maps eigenforms, both complexes",
          "[volume-apps][volume-form-spectrum]") {
  // A hexahedral solid torus (b1 = 1).
  int checked[3] = {0, 0, 0};
  check_volume_form_spectra("solid torus", hex_torus_volume(8, 2), 1, checked);
  INFO("eigenvalues compared: " << checked[0] << ", " << checked[1] << ", " << checked[2]);
  for (int r = 0; r < 3; ++r) CHECK(checked[r] >= 6);
}

TEST_CASE("box [0, pi]^3: the first 1-form eigenvalues of the mesh complex converge at order 2",
          "[volume-apps][volume-form-spectrum]") {
  // Natural boundary conditions: the eigenforms are sin(m_i x_i) dx_i times cos(m_j x_j) in the other
  // axes (m_i >= 1, m_j >= 0), eigenvalue |m|^2 (docs/feec.md): 1 three times (exact, d cos x_i), then 2
  // six times (three exact, d(cos x_i cos x_j); three co-exact). Hex grids n = 4 and 8 (lumped M0):
  // largest relative errors 0.120 and 0.0316 (the exact ones, 4 / h^2 sin^2(h / 2) per axis), co-exact
  // 0.052 and 0.0129: ratios 3.8 and 4.0 for h halved.
  const double analytic[9] = {1, 1, 1, 2, 2, 2, 2, 2, 2};
  double error[2] = {0, 0}, coexact_error[2] = {0, 0};
  const int sizes[2] = {4, 8};
  for (int run = 0; run < 2; ++run) {
    const int n = sizes[run];
    INFO("n = " << n);
    const VolumeMesh grid = hex_grid_volume(n, n, n);
    const VolumeMesh box = grid.with_positions(grid.positions() * M_PI);
    FormSpectrumOptions o;
    o.degree = 1;
    o.k = 10;
    o.complex = DecComplex::Mesh;
    const FormSpectrum s = volume_form_spectrum(box, o);
    REQUIRE(s.eigenvalues.size() == 10);
    // The tenth (lambda = 3) lies clearly above, so the first nine are the two whole clusters.
    CHECK(s.eigenvalues[9] > 1.1 * s.eigenvalues[8]);
    int exact = 0, coexact = 0;
    for (int i = 0; i < 9; ++i) {
      const double e = std::abs(s.eigenvalues[i] - analytic[i]) / analytic[i];
      error[run] = std::max(error[run], e);
      exact += s.kinds[size_t(i)] == FormKind::Exact;
      if (s.kinds[size_t(i)] == FormKind::Coexact) {
        ++coexact;
        CHECK(analytic[i] == 2.0);
        coexact_error[run] = std::max(coexact_error[run], e);
      }
    }
    CHECK(exact == 6);
    CHECK(coexact == 3);
  }
  INFO("largest relative errors " << error[0] << ", " << error[1] << "; co-exact " << coexact_error[0] << ", "
                                  << coexact_error[1]);
  CHECK(error[0] < 0.13);
  CHECK(coexact_error[0] < 0.06);
  CHECK(error[1] < error[0] / 3.5);
  CHECK(coexact_error[1] < coexact_error[0] / 3.5);
}

}  // namespace test_volume_applications
