// tests/apps/applications/test_quadratic.cpp — applications with quadratic elements: Franke's gradient
// against differences, Dirichlet solves exact for quadratic solutions on every grid family, the
// Figure 9 convergence study with order 2 (L2 slope about 3, H1 about 2), and the sphere's
// eigenvalues approaching l(l+1).
#include <cmath>

#include "polydec/apps/applications/poisson.h"
#include "polydec/apps/applications/quadratic.h"
#include "polydec/dec/mesh/generators.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_quadratic_apps {

TEST_CASE("quadratic: Franke's gradient matches central differences", "[quadratic][apps]") {
  const double d = 1e-6;
  for (double x : {0.1, 0.35, 0.5, 0.8})
    for (double y : {0.05, 0.4, 0.7, 0.95}) {
      const Eigen::Vector2d g = franke_gradient(x, y);
      CHECK(g[0] == Approx((franke(x + d, y) - franke(x - d, y)) / (2 * d)).epsilon(1e-7).margin(1e-7));
      CHECK(g[1] == Approx((franke(x, y + d) - franke(x, y - d)) / (2 * d)).epsilon(1e-7).margin(1e-7));
    }
}

TEST_CASE("quadratic: Dirichlet solves are exact for quadratic solutions on every grid family",
          "[quadratic][apps]") {
  for (const Mesh& mesh : {triangle_grid(4, 4), quad_grid(4, 3), hex_grid(4, 4), chevron_grid(4, 4)}) {
    const OperatorSet ops = quadratic_operator_set(mesh);
    const Eigen::MatrixX3d D = quadratic_dof_positions(mesh);
    const int nv = mesh.n_vertices(), nd = int(D.rows());
    Eigen::VectorXd exact(nd);
    for (int i = 0; i < nd; ++i)
      exact[i] = D(i, 0) * D(i, 0) - 2 * D(i, 0) * D(i, 1) + 3 * D(i, 1) * D(i, 1) + D(i, 0);
    std::vector<int> fixed;
    for (int v = 0; v < nv; ++v)
      if (mesh.is_boundary_vertex(v)) fixed.push_back(v);
    for (int e = 0; e < mesh.n_edges(); ++e)
      if (mesh.is_boundary_edge(e)) fixed.push_back(nv + e);
    // Laplace(u) = 2 + 6 = 8; with the Galerkin mass the solve reproduces u at every dof.
    const Eigen::VectorXd f =
        solve_dirichlet_poisson(ops, Eigen::VectorXd::Constant(nd, 8.0), fixed, exact, false);
    CHECK((f - exact).cwiseAbs().maxCoeff() <= 1e-11 * exact.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("quadratic: Franke convergence, L2 slope about 3 and H1 slope about 2 (Figure 9 with order 2)",
          "[quadratic][apps]") {
  const auto series = franke_convergence_quadratic({8, 16, 32});
  REQUIRE(series.size() == 4);
  for (const auto& s : series) {
    INFO(s.family << ": L2 slope " << s.l2_slope << ", H1 slope " << s.h1_slope);
    CHECK(s.l2_slope > 2.7);
    CHECK(s.l2_slope < 3.6);
    CHECK(s.h1_slope > 1.8);
    CHECK(s.h1_slope < 2.5);
    for (size_t i = 1; i < s.errors.size(); ++i) CHECK(s.errors[i].l2_error < s.errors[i - 1].l2_error);
  }
}

}  // namespace test_quadratic_apps

namespace test_quadratic_apps {

TEST_CASE("quadratic: sphere eigenvalues approach l(l+1), limited by the flat faces", "[quadratic][apps]") {
  // Relative errors of the means of the l = 1 (3 copies) and l = 2 (5 copies) clusters with the
  // Galerkin mass, order 2 and order 1, on hex_sphere(1..3) (h halves per level).
  SpectrumOptions o;
  o.k = 9;
  o.lumped_mass = false;
  double prev[2] = {1.0, 1.0};
  for (int level = 1; level <= 3; ++level) {
    const Mesh mesh = hex_sphere(level);
    const Spectrum q = quadratic_spectrum(mesh, o);
    const Spectrum p = laplacian_spectrum(mesh, o);
    for (int l = 1; l <= 2; ++l) {
      const int first = l * l, count = 2 * l + 1;
      const double exact = l * (l + 1);
      const double eq = std::abs(q.eigenvalues.segment(first, count).mean() - exact) / exact;
      const double ep = std::abs(p.eigenvalues.segment(first, count).mean() - exact) / exact;
      INFO("level " << level << ", l = " << l << ": order 2 error " << eq << ", order 1 error " << ep);
      CHECK(eq < ep);
      CHECK(eq < prev[l - 1] / 3);  // about h^2: the inscribed polyhedron's geometric error
      prev[l - 1] = eq;
    }
  }
}

}  // namespace test_quadratic_apps
