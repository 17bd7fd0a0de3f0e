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

namespace test_quadratic_apps {

TEST_CASE("quadratic: the gradient is exact for quadratics, its divergence integrates against it",
          "[quadratic][apps]") {
  // Planar meshes: the prolongation reproduces quadratics, so on every fan triangle the prolonged
  // function is q itself and G u is grad q at the triangle's centroid.
  for (const Mesh& mesh : {quad_grid(4, 3), hex_grid(4, 3), triangle_grid(3, 3), chevron_grid(3, 3)}) {
    const Refinement r = refine(mesh);
    const OperatorSet ops = quadratic_operator_set(mesh, r);
    const Eigen::MatrixX3d X = quadratic_dof_positions(mesh);
    const int nd = int(X.rows()), nh = mesh.n_halfedges();
    REQUIRE(ops.G.rows() == 3 * nh);
    REQUIRE(ops.G.cols() == nd);
    Eigen::VectorXd u(nd);
    for (int i = 0; i < nd; ++i) {
      const double x = X(i, 0), y = X(i, 1);
      u[i] = 1 + 2 * x - y + 0.7 * x * x - 1.3 * x * y + 0.4 * y * y;
    }
    const Eigen::VectorXd g = ops.G * u;
    double worst = 0, scale = 0;
    Eigen::VectorXd area(nh);
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const int h0 = mesh.face_offsets()[f], n = mesh.face_size(f);
      for (int k = 0; k < n; ++k) {
        const int h = h0 + k;
        const Eigen::Vector3d a = mesh.position(mesh.halfedge_source(h)), b = mesh.position(mesh.halfedge_target(h));
        const Eigen::Vector3d xf = r.virtual_points.row(f).transpose(), c = (a + b + xf) / 3;
        area[h] = 0.5 * (b - a).cross(xf - a).norm();
        const Eigen::Vector3d exact(2 + 1.4 * c.x() - 1.3 * c.y(), -1 - 1.3 * c.x() + 0.8 * c.y(), 0);
        worst = std::max(worst, (g.segment<3>(3 * h) - exact).norm());
        scale = std::max(scale, exact.norm());
      }
    }
    CHECK(worst <= 1e-12 * scale);
    // -u^T D g = sum over fan triangles of area (grad u . g) for g constant per triangle, and the
    // divergence of any such g sums to zero (constants have no gradient).
    Eigen::VectorXd field(3 * nh);
    for (int k = 0; k < 3 * nh; ++k) field[k] = std::sin(0.7 * k + 0.2);
    const Eigen::VectorXd div = ops.D * field;
    double integral = 0;
    for (int h = 0; h < nh; ++h) integral += area[h] * g.segment<3>(3 * h).dot(field.segment<3>(3 * h));
    CHECK(std::abs(-u.dot(div) - integral) <= 1e-12 * (std::abs(integral) + div.cwiseAbs().sum()));
    CHECK(std::abs(div.sum()) <= 1e-12 * div.cwiseAbs().sum());
  }
}

}  // namespace test_quadratic_apps
