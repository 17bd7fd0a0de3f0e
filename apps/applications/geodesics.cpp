// apps/applications/geodesics.cpp — heat-method geodesic distances.
#include "polydec/apps/applications/geodesics.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numeric>

#include "polydec/dec/detail/huge_pages.h"

namespace polydec {

namespace {

// Component id per vertex by flood fill over the non-zero off-diagonal entries of S (symmetric);
// -1 for vertices S does not couple to any other (unreferenced vertices, and vertices that only
// zero-area faces hold: their fan triangles are degenerate and carry no stiffness). Faces alone
// would not do: a zero-area face joins its vertices in the mesh but not in S.
std::vector<int> vertex_components(const SparseMatrix& S) {
  const int n = int(S.rows());
  std::vector<int> comp(n, -1);
  auto coupled = [&](int v) {
    for (SparseMatrix::InnerIterator it(S, v); it; ++it)
      if (it.row() != v && it.value() != 0) return true;
    return false;
  };
  std::vector<int> stack;
  int next = 0;
  for (int s = 0; s < n; ++s) {
    if (comp[s] >= 0 || !coupled(s)) continue;
    comp[s] = next;
    stack.push_back(s);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (SparseMatrix::InnerIterator it(S, v); it; ++it)
        if (it.value() != 0 && comp[it.row()] < 0) {
          comp[it.row()] = next;
          stack.push_back(int(it.row()));
        }
    }
    ++next;
  }
  return comp;
}

// `src` moved into a new set without copying its sparse matrices: Eigen 3.4's SparseMatrix has
// no move constructor, so std::move(OperatorSet) deep-copies S, M, G and D (~0.3 s on FINE SPHERE).
OperatorSet take(OperatorSet& src) {
  SparseMatrix S, M, G, D;
  S.swap(src.S);
  M.swap(src.M);
  G.swap(src.G);
  D.swap(src.D);
  OperatorSet dst = std::move(src);  // the other members move; the matrices are empty here
  dst.S.swap(S);
  dst.M.swap(M);
  dst.G.swap(G);
  dst.D.swap(D);
  return dst;
}

// Eq. (32) on one element's gradient block: x (n rows of `stride` apart) becomes -x / |x|, zero
// where the gradient vanishes or is not finite. Rescaled first: far from the source |grad u|
// underflows when squared. No allocation.
void normalize_block(double* x, int n, int stride) {
  double m = 0;
  for (int i = 0; i < n; ++i) m = std::max(m, std::abs(x[i * stride]));
  if (!(m > 0) || !std::isfinite(m)) {
    for (int i = 0; i < n; ++i) x[i * stride] = 0;
    return;
  }
  double s2 = 0;
  for (int i = 0; i < n; ++i) {
    x[i * stride] /= m;
    s2 += x[i * stride] * x[i * stride];
  }
  const double norm = std::sqrt(s2);  // >= 1: the largest entry is now 1
  for (int i = 0; i < n; ++i) x[i * stride] = -x[i * stride] / norm;
}

}  // namespace

HeatGeodesics::HeatGeodesics(const Mesh& mesh, const HeatGeodesicsOptions& options)
    : HeatGeodesics(build_operators(mesh, parse_laplacian("ours")), mesh.mean_edge_length(), options) {}

HeatGeodesics::HeatGeodesics(OperatorSet operators, double mean_edge_length, const HeatGeodesicsOptions& options)
    : ops_(take(operators)), options_(options) {
  // By shape, not by emptiness: a mesh without faces has a 0 x |V| gradient. |V| is S's size, so
  // that an operator set without a surface domain (a volume mesh's, operators/registry/volume_laplacians.h)
  // works the same way.
  const int nv = int(ops_.S.rows());
  if (ops_.G.cols() != nv || ops_.D.rows() != nv)
    throw std::invalid_argument("heat geodesics: Laplacian '" + ops_.name + "' defines no gradient/divergence");
  if (!options.lumped_mass && ops_.M.rows() != nv)
    throw std::invalid_argument("heat geodesics: Laplacian '" + ops_.name + "' defines no unlumped mass");
  t_ = options.time_step_factor * mean_edge_length * mean_edge_length;
  component_ = vertex_components(ops_.S);

  // Heat operator M - t S; vertices without stiffness (unreferenced, or only in zero-area faces:
  // zero rows) are pinned to keep it definite.
  pinned_.assign(nv, 0);
  for (int v = 0; v < nv; ++v)
    if (component_[v] < 0) pinned_[v] = 1;
  SparseMatrix heat;
  if (options.lumped_mass) {
    SparseMatrix Md(nv, nv);
    Md.setIdentity();
    Md.diagonal() = ops_.M_lumped;
    heat = Md - t_ * ops_.S;
  } else {
    heat = ops_.M - t_ * ops_.S;
  }
  // CHOLMOD's default supernodes: each source costs two solves, and a solve is ~30% faster than
  // with the relaxed amalgamation (FINE SPHERE: 10.1 vs 14.0 ms) for a somewhat slower
  // factorization (docs/benchmarks.md).
  CholeskyOptions copt;
  copt.relaxed_supernodes = false;
  heat_ = std::make_unique<SparseCholesky>(pin_to_identity(heat, pinned_), "heat operator M - t S", copt);

  // Poisson operator -S with one vertex pinned per component (S has constants per component in
  // its null space; the right-hand side D g sums to zero on each, so pinning loses nothing).
  std::vector<unsigned char> seen(
      component_.empty() ? 0 : std::max(0, *std::max_element(component_.begin(), component_.end()) + 1), 0);
  for (int v = 0; v < nv; ++v)
    if (component_[v] >= 0 && !seen[component_[v]]) {
      seen[component_[v]] = 1;
      pinned_[v] = 1;
    }
  poisson_ = std::make_unique<SparseCholesky>(pin_to_identity(-ops_.S, pinned_), "Poisson operator -S", copt);
}

// The reach follows the implicit heat step, not the continuous exp(-d / sqrt(t)): on a chain of
// edges of length h with lumped mass, (M - t S) u = 0 away from the sources gives u_k ~ exp(-kappa k)
// with 2 sinh(kappa / 2) = h / sqrt(t), i.e. kappa(f) = 2 asinh(1 / (2 sqrt(f))) per edge at
// t = f h^2 (0.96 at f = 1). For f >> 1 that is 1 / sqrt(f) (reach ~ sqrt(t)); for f << 1 it is
// ln(1 / f), so the reach grows only logarithmically there and scaling the resolved radius as
// sqrt(t) undershoots (from f = 1e-4 it suggested 0.13 where 15 was needed). The resolution level
// and the edge length cancel: the resolved radius times kappa(factor) is what the solve resolves,
// and the suggestion is the factor whose kappa carries that to 1.25 extent.
double suggested_time_factor(double factor, const HeatDiagnostics& diagnostics, double extent) {
  if (diagnostics.unresolved_vertices == 0) return factor;
  const double r = diagnostics.resolved_radius > 0 ? diagnostics.resolved_radius : extent / 1e3;
  const double half_kappa = std::asinh(0.5 / std::sqrt(factor)) * r / (1.25 * extent);
  const double s = std::sinh(half_kappa);
  return std::max(factor, 0.25 / (s * s));
}

void HeatGeodesics::check_sources(std::span<const int> sources) const {
  const int n_out = ops_.n_input_vertices;
  if (sources.empty()) throw std::out_of_range("heat geodesics: no source vertex given");
  for (int s : sources) {
    if (s < 0 || s >= n_out)
      throw std::out_of_range(fmt::format("heat geodesics: source vertex {} out of range [0, {})", s, n_out));
    if (component_[s] < 0)
      throw std::out_of_range(fmt::format("heat geodesics: source vertex {} carries no stiffness (unreferenced, or only in zero-area faces)", s));
  }
}

Eigen::VectorXd HeatGeodesics::distance(std::span<const int> sources, HeatDiagnostics* diagnostics) const {
  const int nv = int(ops_.S.rows()), n_out = ops_.n_input_vertices;
  check_sources(sources);
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(nv);
  std::vector<unsigned char> reached_component(nv + 1, 0);
  for (int s : sources) {
    delta[s] = 1.0;
    reached_component[component_[s]] = 1;
  }
  // (31): (M - t S) u = M delta
  Eigen::VectorXd rhs = !options_.mass_weighted_source ? delta
                        : options_.lumped_mass        ? Eigen::VectorXd(ops_.M_lumped.cwiseProduct(delta))
                                                      : Eigen::VectorXd(ops_.M * delta);
  for (int v = 0; v < nv; ++v)
    if (component_[v] < 0) rhs[v] = 0;
  const Eigen::VectorXd u = heat_->solve(rhs);

  // (32): g = -grad u / |grad u| per element (fan triangle; or the blocks the operator set names);
  // zero where the gradient vanishes.
  Eigen::VectorXd g = ops_.G * u;
  const int n_blocks = ops_.G_blocks.empty() ? int(g.size() / 3) : int(ops_.G_blocks.size()) - 1;
  for (int h = 0; h < n_blocks; ++h) {
    const int b0 = ops_.G_blocks.empty() ? 3 * h : ops_.G_blocks[h];
    const int b1 = ops_.G_blocks.empty() ? 3 * h + 3 : ops_.G_blocks[h + 1];
    normalize_block(g.data() + b0, b1 - b0, 1);
  }
  // (33): S d = D g, solved as (-S) d = -D g with pinned vertices.
  Eigen::VectorXd b = -(ops_.D * g);
  for (int v = 0; v < nv; ++v)
    if (pinned_[v]) b[v] = 0;
  Eigen::VectorXd d = poisson_->solve(b).head(n_out);

  const int nc = int(reached_component.size());
  std::vector<double> cmin(nc, std::numeric_limits<double>::infinity());
  for (int v = 0; v < n_out; ++v)
    if (component_[v] >= 0) cmin[component_[v]] = std::min(cmin[component_[v]], d[v]);
  for (int v = 0; v < n_out; ++v) {
    const int c = component_[v];
    d[v] = (c >= 0 && reached_component[c]) ? d[v] - cmin[c] : std::numeric_limits<double>::infinity();
  }
  if (diagnostics) {
    // Resolution of the direct solve: double precision's range (see HeatDiagnostics).
    double umax = 0;
    for (int v = 0; v < n_out; ++v)
      if (std::isfinite(d[v])) umax = std::max(umax, u[v]);
    *diagnostics = {};
    for (int v = 0; v < n_out; ++v) {
      if (!std::isfinite(d[v])) continue;
      if (u[v] > 1e-280 * umax)
        diagnostics->resolved_radius = std::max(diagnostics->resolved_radius, d[v]);
      else
        ++diagnostics->unresolved_vertices;
    }
  }
  return d;
}

Eigen::MatrixXd HeatGeodesics::distances(std::span<const int> sources, int block) const {
  const int nv = int(ops_.S.rows()), n_out = ops_.n_input_vertices, k = int(sources.size());
  if (block < 1) throw std::invalid_argument(fmt::format("heat geodesics: block size {} must be positive", block));
  check_sources(sources);
  // G row by row (a gather per gradient entry) and D column by column (a scatter into the small
  // right-hand side): one pass over both for all columns of a block.
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Gr = ops_.G;
  const int n_blocks = ops_.G_blocks.empty() ? int(Gr.rows() / 3) : int(ops_.G_blocks.size()) - 1;
  int widest = 3;
  for (int h = 0; h < n_blocks && !ops_.G_blocks.empty(); ++h)
    widest = std::max(widest, ops_.G_blocks[h + 1] - ops_.G_blocks[h]);
  Eigen::MatrixXd out(n_out, k);
  for (int c0 = 0; c0 < k; c0 += block) {
    const int m = std::min(block, k - c0);
    // (31) for m sources at once.
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nv, m);
    for (int c = 0; c < m; ++c) {
      const int s = sources[size_t(c0 + c)];
      if (!options_.mass_weighted_source)
        rhs(s, c) = 1.0;
      else if (options_.lumped_mass)
        rhs(s, c) = ops_.M_lumped[s];
      else
        for (SparseMatrix::InnerIterator it(ops_.M, s); it; ++it)
          if (component_[it.row()] >= 0) rhs(it.row(), c) = it.value();
    }
    // Vertex-major copies (the m values of a vertex contiguous) for the fused pass.
    const Eigen::MatrixXd Ut = heat_->solve(rhs).transpose();
    Eigen::MatrixXd Bt = Eigen::MatrixXd::Zero(m, nv);
    const double* U = Ut.data();  // vertex v's m values at U + v m
    double* Bv = Bt.data();
    std::vector<double> g(size_t(widest) * size_t(m));  // block row i's m values at g + i m
    for (int h = 0; h < n_blocks; ++h) {
      const int b0 = ops_.G_blocks.empty() ? 3 * h : ops_.G_blocks[h];
      const int b1 = ops_.G_blocks.empty() ? 3 * h + 3 : ops_.G_blocks[h + 1];
      for (int r = b0; r < b1; ++r) {
        double* gr = g.data() + size_t(r - b0) * m;
        std::fill(gr, gr + m, 0.0);
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Gr, r); it; ++it) {
          const double a = it.value();
          const double* u = U + it.col() * long(m);
          for (int c = 0; c < m; ++c) gr[c] += a * u[c];
        }
      }
      for (int c = 0; c < m; ++c) normalize_block(g.data() + c, b1 - b0, m);  // (32)
      for (int r = b0; r < b1; ++r) {
        const double* gr = g.data() + size_t(r - b0) * m;
        for (SparseMatrix::InnerIterator it(ops_.D, r); it; ++it) {
          const double a = it.value();
          double* b = Bv + it.row() * long(m);
          for (int c = 0; c < m; ++c) b[c] -= a * gr[c];
        }
      }
    }
    // (33) for the m right-hand sides.
    Eigen::MatrixXd B = Bt.transpose();
    for (int v = 0; v < nv; ++v)
      if (pinned_[v]) B.row(v).setZero();
    const Eigen::MatrixXd D = poisson_->solve(B);
    for (int c = 0; c < m; ++c) {
      const int reached = component_[sources[size_t(c0 + c)]];
      double cmin = std::numeric_limits<double>::infinity();
      for (int v = 0; v < n_out; ++v)
        if (component_[v] == reached) cmin = std::min(cmin, D(v, c));
      for (int v = 0; v < n_out; ++v)
        out(v, c0 + c) = component_[v] == reached ? D(v, c) - cmin : std::numeric_limits<double>::infinity();
    }
  }
  return out;
}

double rmse(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() == 0) return 0.0;
  return std::sqrt((a - b).squaredNorm() / double(a.size()));
}

}  // namespace polydec
