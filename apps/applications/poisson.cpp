// apps/applications/poisson.cpp — Dirichlet Poisson solves and the Franke convergence study (section 5.8).
#include "polydec/apps/applications/poisson.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "polydec/apps/applications/convergence.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/sawtooth_grid.h"
#include "polydec/operators/solvers/cholesky.h"

namespace polydec {

namespace {

// One Gaussian term c * exp(-(p (9x - a)^2 + q (9y - b)) ...) is handled term by term below.
struct FrankeTerms {
  double g1, g2, g3, g4;
  FrankeTerms(double x, double y)
      : g1(0.75 * std::exp(-(std::pow(9 * x - 2, 2) + std::pow(9 * y - 2, 2)) / 4)),
        g2(0.75 * std::exp(-std::pow(9 * x + 1, 2) / 49 - (9 * y + 1) / 10)),
        g3(0.5 * std::exp(-(std::pow(9 * x - 7, 2) + std::pow(9 * y - 3, 2)) / 4)),
        g4(-0.2 * std::exp(-std::pow(9 * x - 4, 2) - std::pow(9 * y - 7, 2))) {}
};

}  // namespace

double franke(double x, double y) {
  const FrankeTerms t(x, y);
  return t.g1 + t.g2 + t.g3 + t.g4;
}

double franke_laplacian(double x, double y) {
  const FrankeTerms t(x, y);
  // exp(-(a^2 + b^2)/4), a = 9x - x0, b = 9y - y0: Laplacian = 81 (a^2/4 + b^2/4 - 1) * term.
  const double a1 = 9 * x - 2, b1 = 9 * y - 2, a3 = 9 * x - 7, b3 = 9 * y - 3;
  const double l1 = 81 * ((a1 * a1 + b1 * b1) / 4 - 1) * t.g1;
  const double l3 = 81 * ((a3 * a3 + b3 * b3) / 4 - 1) * t.g3;
  // exp(-(9x+1)^2/49 - (9y+1)/10): d2/dx2 = ((18 (9x+1)/49)^2 - 162/49) term, d2/dy2 = 0.81 term.
  const double c2 = 18 * (9 * x + 1) / 49;
  const double l2 = (c2 * c2 - 162.0 / 49 + 0.81) * t.g2;
  // exp(-a^2 - b^2), a = 9x - 4, b = 9y - 7: Laplacian = (324 (a^2 + b^2) - 324) * term.
  const double a4 = 9 * x - 4, b4 = 9 * y - 7;
  const double l4 = 324 * (a4 * a4 + b4 * b4 - 1) * t.g4;
  return l1 + l2 + l3 + l4;
}

Eigen::Vector2d franke_gradient(double x, double y) {
  const FrankeTerms t(x, y);
  // Each term's exponent differentiated: d/dx exp(-(9x - a)^2 / 4) = -9 (9x - a) / 2 exp(...), etc.
  const double fx = -4.5 * (9 * x - 2) * t.g1 - 18.0 / 49 * (9 * x + 1) * t.g2 - 4.5 * (9 * x - 7) * t.g3 -
                    18 * (9 * x - 4) * t.g4;
  const double fy = -4.5 * (9 * y - 2) * t.g1 - 0.9 * t.g2 - 4.5 * (9 * y - 3) * t.g3 - 18 * (9 * y - 7) * t.g4;
  return {fx, fy};
}

PoissonBlock poisson_free_block(const OperatorSet& ops, const std::vector<int>& fixed) {
  const int nv = int(ops.S.rows());
  PoissonBlock block;
  block.index.assign(nv, -1);
  std::vector<unsigned char> is_fixed(nv, 0);
  for (int v : fixed) {
    if (v < 0 || v >= nv)
      throw std::out_of_range(fmt::format("Dirichlet Poisson: fixed vertex {} out of range", v));
    is_fixed[v] = 1;
  }
  int n = 0;
  for (int v = 0; v < nv; ++v)
    if (!is_fixed[v] && ops.M_lumped[v] > 0) block.index[v] = n++;
  block.A = -principal_submatrix(ops.S, block.index);
  return block;
}

Eigen::VectorXd solve_dirichlet_poisson(const OperatorSet& ops, const Eigen::VectorXd& b,
                                        const std::vector<int>& fixed, const Eigen::VectorXd& values,
                                        bool lumped_mass) {
  const int nv = int(ops.S.rows());
  if (b.size() != nv || values.size() != nv)
    throw std::invalid_argument("Dirichlet Poisson: b and values need one entry per vertex");
  if (!lumped_mass && ops.M.size() == 0)
    throw std::invalid_argument("Dirichlet Poisson: Laplacian '" + ops.name + "' defines no unlumped mass");
  const PoissonBlock block = poisson_free_block(ops, fixed);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(nv);
  for (int v : fixed) f[v] = values[v];
  const int n = int(block.A.rows());
  if (n == 0) return f;
  const Eigen::VectorXd Mb =
      lumped_mass ? Eigen::VectorXd(ops.M_lumped.cwiseProduct(b)) : Eigen::VectorXd(ops.M * b);
  // -S_II f_I = -(M b)_I + S_IB f_B (f is zero away from the fixed vertices).
  const Eigen::VectorXd Sf = ops.S * f;
  Eigen::VectorXd rhs(n);
  for (int v = 0; v < nv; ++v)
    if (block.index[v] >= 0) rhs[block.index[v]] = Sf[v] - Mb[v];
  const Eigen::VectorXd fI =
      SparseCholesky(block.A, "-S restricted to the free vertices (Dirichlet Poisson)").solve(rhs);
  for (int v = 0; v < nv; ++v)
    if (block.index[v] >= 0) f[v] = fI[block.index[v]];
  return f;
}

PoissonError franke_poisson(const OperatorSet& ops, bool lumped_mass) {
  const Mesh& mesh = ops.domain;
  const int nv = mesh.n_vertices();
  PoissonError e;
  e.n_vertices = nv;
  e.h = mesh.mean_edge_length();
  e.exact.resize(nv);
  Eigen::VectorXd b(nv);
  for (int v = 0; v < nv; ++v) {
    const double x = mesh.positions()(v, 0), y = mesh.positions()(v, 1);
    e.exact[v] = franke(x, y);
    b[v] = franke_laplacian(x, y);
  }
  std::vector<int> fixed;
  for (int v = 0; v < nv; ++v)
    if (mesh.is_boundary_vertex(v)) fixed.push_back(v);
  if (fixed.empty()) throw std::invalid_argument("Franke Poisson problem: the mesh has no boundary");
  e.solution = solve_dirichlet_poisson(ops, b, fixed, e.exact, lumped_mass);
  const Eigen::VectorXd d = e.solution - e.exact;
  e.l2_error = std::sqrt(lumped_mass ? d.dot(ops.M_lumped.cwiseProduct(d)) : d.dot(ops.M * d));
  return e;
}

PoissonError franke_poisson(const Mesh& mesh, bool lumped_mass) {
  return franke_poisson(build_operators(mesh, parse_laplacian("ours"), false), lumped_mass);
}

std::vector<ConvergenceSeries> franke_convergence(const ConvergenceOptions& options) {
  if (options.resolutions.size() < 2)
    throw std::invalid_argument("convergence study: need two or more resolutions");
  std::vector<ConvergenceSeries> out;
  for (const std::string& family : options.families) {
    if (family != "triangles" && family != "quads" && family != "hexagons" && family != "sawtooth")
      throw std::invalid_argument("convergence study: unknown family '" + family +
                                  "' (triangles, quads, hexagons, sawtooth)");
    ConvergenceSeries s;
    s.family = family;
    std::vector<double> h, err;
    for (int n : options.resolutions) {
      if (n < 1) throw std::invalid_argument("convergence study: resolutions must be >= 1");
      const Mesh mesh = family == "triangles" ? triangle_grid(n, n)
                        : family == "quads"   ? quad_grid(n, n)
                        : family == "sawtooth" ? sawtooth_grid(n, n)
                                              : hex_grid(n, n);
      PoissonError e = franke_poisson(build_operators(mesh, options.laplacian, false), options.lumped_mass);
      e.solution.resize(0);
      e.exact.resize(0);
      h.push_back(e.h);
      err.push_back(e.l2_error);
      s.resolutions.push_back(n);
      s.errors.push_back(std::move(e));
    }
    s.slope = loglog_slope(h, err);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace polydec
