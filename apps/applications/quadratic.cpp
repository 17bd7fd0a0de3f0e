// apps/applications/quadratic.cpp — the quadratic operator set, spectra, and the Franke study with
// order 2 elements.
#include "polydec/apps/applications/quadratic.h"

#include <cmath>
#include <stdexcept>

#include "polydec/apps/applications/convergence.h"
#include "polydec/apps/applications/poisson.h"
#include "polydec/dec/mesh/generators.h"

namespace polydec {

OperatorSet quadratic_operator_set(const Mesh& mesh, const RefinementOptions& options) {
  return quadratic_operator_set(mesh, refine(mesh, options));
}

OperatorSet quadratic_operator_set(const Mesh& mesh, const Refinement& refinement) {
  QuadraticLaplacian Q = assemble_quadratic_laplacian(mesh, refinement);
  OperatorSet ops;
  ops.name = "quadratic";
  ops.domain = mesh;
  ops.n_input_vertices = mesh.n_vertices();
  ops.S.swap(Q.S);
  ops.M.swap(Q.M);
  ops.M_lumped = std::move(Q.M_lumped);
  ops.quality = Q.quality;
  ops.mean_edge_length = mesh.mean_edge_length();
  QuadraticGradient G = quadratic_gradient(mesh, refinement);
  ops.G.swap(G.G);
  ops.D.swap(G.D);
  return ops;
}

Spectrum quadratic_spectrum(const Mesh& mesh, const SpectrumOptions& options) {
  return laplacian_spectrum(quadratic_operator_set(mesh), options);
}

QuadraticPoissonError franke_poisson_quadratic(const Mesh& mesh) {
  const Refinement r = refine(mesh);
  const OperatorSet ops = quadratic_operator_set(mesh, r);
  const Eigen::MatrixX3d D = quadratic_dof_positions(mesh);
  const int nv = mesh.n_vertices(), nd = int(D.rows());
  Eigen::VectorXd exact(nd), b(nd);
  for (int i = 0; i < nd; ++i) {
    exact[i] = franke(D(i, 0), D(i, 1));
    b[i] = franke_laplacian(D(i, 0), D(i, 1));
  }
  std::vector<int> fixed;
  for (int v = 0; v < nv; ++v)
    if (mesh.is_boundary_vertex(v)) fixed.push_back(v);
  for (int e = 0; e < mesh.n_edges(); ++e)
    if (mesh.is_boundary_edge(e)) fixed.push_back(nv + e);
  if (fixed.empty()) throw std::invalid_argument("Franke Poisson problem: the mesh has no boundary");
  const Eigen::VectorXd u = solve_dirichlet_poisson(ops, b, fixed, exact, false);
  // Errors by Dunavant's 7-point rule (degree 5) on every fan triangle.
  static const double w[3] = {0.225, 0.132394152788506, 0.125939180544827};
  static const double l[3][2] = {
      {1.0 / 3, 1.0 / 3}, {0.059715871789770, 0.470142064105115}, {0.797426985353087, 0.101286507323456}};
  double l2 = 0, h1 = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const int h0 = mesh.face_offsets()[f], n = mesh.face_offsets()[f + 1] - h0;
    const PolygonPositions X = face_positions(mesh, f);
    const Eigen::Vector3d xf = r.virtual_points.row(f).transpose();
    const Eigen::MatrixXd W = quadratic_face_weights(X, xf);
    Eigen::VectorXd coarse(2 * n);
    for (int k = 0; k < n; ++k) {
      coarse[k] = u[mesh.halfedge_source(h0 + k)];
      coarse[n + k] = u[nv + mesh.halfedge_edge(h0 + k)];
    }
    const Eigen::VectorXd inner = W * coarse;  // x_f, then the spoke midpoints
    for (int k = 0; k < n; ++k) {
      if (r.fan[size_t(h0 + k)] == FanTriangle::Degenerate) continue;
      const int k1 = (k + 1) % n;
      const Eigen::Vector3d p0 = X.row(k).transpose(), p1 = X.row(k1).transpose();
      Eigen::Matrix<double, 6, 1> U;
      U << coarse[k], coarse[k1], inner[0], coarse[n + k], inner[1 + k1], inner[1 + k];
      const double area = 0.5 * (p1 - p0).cross(xf - p0).norm();
      for (int s = 0; s < 3; ++s)
        for (int perm = 0; perm < (s == 0 ? 1 : 3); ++perm) {
          Eigen::Vector3d bary = Eigen::Vector3d::Constant(l[s][1]);
          bary[perm] = l[s][0];
          const Eigen::Vector3d x = bary[0] * p0 + bary[1] * p1 + bary[2] * xf;
          const double uh = p2_basis(bary).dot(U);
          const Eigen::Vector3d guh = p2_basis_gradients(bary, p0, p1, xf).transpose() * U;
          const Eigen::Vector2d g = franke_gradient(x[0], x[1]);
          l2 += w[s] * area * std::pow(uh - franke(x[0], x[1]), 2);
          h1 += w[s] * area * (std::pow(guh[0] - g[0], 2) + std::pow(guh[1] - g[1], 2) + guh[2] * guh[2]);
        }
    }
  }
  return {mesh.mean_edge_length(), std::sqrt(l2), std::sqrt(h1), nd};
}

std::vector<QuadraticConvergenceSeries> franke_convergence_quadratic(const std::vector<int>& resolutions) {
  if (resolutions.size() < 2) throw std::invalid_argument("convergence study: need two or more resolutions");
  std::vector<QuadraticConvergenceSeries> out;
  for (const std::string family : {"triangles", "quads", "hexagons", "non-convex"}) {
    QuadraticConvergenceSeries s;
    s.family = family;
    std::vector<double> h, l2, h1;
    for (int n : resolutions) {
      if (n < 1) throw std::invalid_argument("convergence study: resolutions must be >= 1");
      const Mesh mesh = family == "triangles"  ? triangle_grid(n, n)
                        : family == "quads"    ? quad_grid(n, n)
                        : family == "hexagons" ? hex_grid(n, n)
                                               : chevron_grid(n, n);
      const QuadraticPoissonError e = franke_poisson_quadratic(mesh);
      h.push_back(e.h);
      l2.push_back(e.l2_error);
      h1.push_back(e.h1_error);
      s.resolutions.push_back(n);
      s.errors.push_back(e);
    }
    s.l2_slope = loglog_slope(h, l2);
    s.h1_slope = loglog_slope(h, h1);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace polydec
