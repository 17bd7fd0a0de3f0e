// apps/applications/geodesics.cpp — heat-method geodesic distances.
#include "polydec/apps/applications/geodesics.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numeric>
#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/detail/simd.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec {

namespace {

using FanTable = detail::HeatFanTable;

// Subnormal numbers flushed to zero (operands and results) on the calling thread while it lives,
// the thread's previous mode restored after (x86's MXCSR; nothing elsewhere). Far from the sources
// the heat step's solution underflows (HeatDiagnostics: below 1e-280 of its maximum, ~650 edge
// lengths at the default time step); there every operation on a subnormal value takes a slow
// microcode path. On the 1.5M-quad sphere that made the face-wise pass of distances(64) ~6.7 s of
// a ~9.7 s call (docs/benchmarks.md). The solution is near 1 at the sources (right-hand side M
// delta), so only values far below the resolution, whose distances are unresolved anyway, change.
class FlushSubnormals {
 public:
  FlushSubnormals() {
#if defined(__SSE__) || defined(__x86_64__)
    saved_ = _mm_getcsr();
    _mm_setcsr(saved_ | 0x8040);  // flush-to-zero (bit 15) and denormals-are-zero (bit 6)
#endif
  }
  ~FlushSubnormals() {
#if defined(__SSE__) || defined(__x86_64__)
    _mm_setcsr(saved_);
#endif
  }
  FlushSubnormals(const FlushSubnormals&) = delete;
  FlushSubnormals& operator=(const FlushSubnormals&) = delete;

 private:
  [[maybe_unused]] unsigned saved_ = 0;
};

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

// Eq. (32) on one element's gradient block: x (n rows of `stride` apart) becomes -x / |x|, zero
// where the gradient vanishes or is not finite. One square root and one division when |x|^2 is
// well inside double's range; else rescaled first (far from the source |grad u| underflows when
// squared). No allocation.
void normalize_block(double* x, int n, int stride) {
  double q = 0;
  for (int i = 0; i < n; ++i) q += x[i * stride] * x[i * stride];
  if (q > 1e-280 && q < 1e280) {
    const double f = -1.0 / std::sqrt(q);
    for (int i = 0; i < n; ++i) x[i * stride] *= f;
    return;
  }
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

// Eqs. (32)-(33) on a fan triangle (x_i, x_j, x_f) from the vectors r_i = x_f - x_i and
// r_j = x_f - x_j alone. With u_f = sum_k w_k u_k, di = u_i - u_f and dj = u_j - u_f, the gradient
// is N x w / |N|^2 for w = di r_j - dj r_i and N the triangle's normal (twice its area); its hat
// gradients are N x r_j / |N|^2 and -N x r_i / |N|^2. So the divergence of -grad u / |grad u|
// times the area sends si = -(w . r_j) / (2 |w|) to corner i and sj = (w . r_i) / (2 |w|) to
// corner j (and minus their sum to the virtual vertex): no normal, area or hat gradient is needed.
// Only inner products of r_i, r_j and w enter, so they are taken in the triangle's own plane, in
// the frame where r_i = (p, 0) and r_j = (q, s): p = |r_i|, q = r_i . r_j / p, s = |r_i x r_j| / p
// (fan_frame, 3 values per fan triangle). Then w = (x, y) with x = di q - dj p, y = di s, and
// si = -(x q + y s) / (2 |w|), sj = x p / (2 |w|).
[[gnu::always_inline]] inline void fan_frame(const double* ri, const double* rj, double* pqs) {
  const double p = std::sqrt(ri[0] * ri[0] + ri[1] * ri[1] + ri[2] * ri[2]);
  const double c[3] = {ri[1] * rj[2] - ri[2] * rj[1], ri[2] * rj[0] - ri[0] * rj[2], ri[0] * rj[1] - ri[1] * rj[0]};
  const bool flat = !(p > 0);  // the virtual vertex on corner i: a degenerate fan triangle
  pqs[0] = flat ? 0.0 : p;
  pqs[1] = flat ? 0.0 : (ri[0] * rj[0] + ri[1] * rj[1] + ri[2] * rj[2]) / p;
  pqs[2] = flat ? 0.0 : std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / p;
}

// si and sj of one fan triangle from its frame (p, q, s), in two steps without branches, so that
// loops of them vectorize (the library is built with -fno-math-errno -fno-trapping-math, so
// std::sqrt, the division and the selects do). fan_shares_direct adds them where |w|^2 lies in
// [1e-280, 1e280] and returns whether w != 0 lies outside: far from the source u underflows. Then
// fan_shares_rescaled adds those, with w divided by max(|x|, |y|) first (nothing where w is not
// finite). The shares accumulate into si, sj; each step adds nothing where the other one applies,
// and nothing where u is not finite.
[[gnu::always_inline]] inline bool fan_shares_direct(double di, double dj, double p, double q, double s, double& si,
                                                     double& sj) {
  const double x = di * q - dj * p, y = di * s;
  const double ww = x * x + y * y;
  const bool in_range = ww > 1e-280 && ww < 1e280;
  const double h = 0.5 / std::sqrt(ww);
  si -= in_range ? h * (x * q + y * s) : 0.0;
  sj += in_range ? h * x * p : 0.0;
  return !in_range && (x != 0 || y != 0);
}
[[gnu::always_inline]] inline void fan_shares_rescaled(double di, double dj, double p, double q, double s, double& si,
                                                       double& sj) {
  const double x = di * q - dj * p, y = di * s;
  const double ww = x * x + y * y;
  const double mx = std::max(std::abs(x), std::abs(y));
  const bool take = !(ww > 1e-280 && ww < 1e280) && mx > 0 && mx <= std::numeric_limits<double>::max();
  const double d = take ? mx : 1.0;
  const double xs = x / d, ys = y / d;
  const double h = 0.5 / std::sqrt(xs * xs + ys * ys);
  si -= take ? h * (xs * q + ys * s) : 0.0;
  sj += take ? h * xs * p : 0.0;
}

// One fan triangle for m columns (frame pqs), added to b_i, b_j and the virtual vertex's acc: a
// loop of fan_shares_direct, and one of fan_shares_rescaled only if some column needs it (far
// from the sources many do: a scalar loop over them took three quarters of the pass on a 1.5M-quad
// sphere). The arrays do not overlap (i != j on a fan triangle of non-zero area).
[[gnu::always_inline]] inline void fan_columns(int m, const double* pqs, const double* __restrict ui,
                                               const double* __restrict uj, const double* __restrict uf,
                                               double* __restrict bi, double* __restrict bj, double* __restrict acc) {
  const double p = pqs[0], q = pqs[1], s = pqs[2];
  long rescale = 0;
  for (int c = 0; c < m; ++c) {
    double si = 0, sj = 0;
    rescale |= long(fan_shares_direct(ui[c] - uf[c], uj[c] - uf[c], p, q, s, si, sj));
    bi[c] += si;
    bj[c] += sj;
    acc[c] -= si + sj;
  }
  if (rescale == 0) return;
  for (int c = 0; c < m; ++c) {
    double si = 0, sj = 0;
    fan_shares_rescaled(ui[c] - uf[c], uj[c] - uf[c], p, q, s, si, sj);
    bi[c] += si;
    bj[c] += sj;
    acc[c] -= si + sj;
  }
}

// One face of the one-column pass, n corners: R holds the frames of its fan triangles (fan_frame,
// 3 n values), skip[k] marks degenerate fan triangles (no gradient, no divergence). Each corner's
// u is read once and its b written once (N > 0: n = N, unrolled). Each fan triangle branches to
// the rescaled step only when it needs it: lanes of four fan triangles, both steps whenever one
// needed it, took 12-19% longer on the 1.5M-quad sphere (docs/benchmarks.md).
template <int N>
[[gnu::always_inline]] inline void fan_face([[maybe_unused]] int n, const double* R, const unsigned char* skip,
                                            const int* idx, const double* w, const double* u, double* b) {
  if constexpr (N == 0) {  // any size: a fan triangle at a time
    double uf = 0, acc = 0;
    for (int k = 0; k < n; ++k) uf += w[k] * u[idx[k]];
    for (int k = 0; k < n; ++k) {
      if (skip[k]) continue;
      const int k1 = k + 1 == n ? 0 : k + 1;
      const double di = u[idx[k]] - uf, dj = u[idx[k1]] - uf, *f = R + 3 * k;
      double si = 0, sj = 0;
      if (fan_shares_direct(di, dj, f[0], f[1], f[2], si, sj)) fan_shares_rescaled(di, dj, f[0], f[1], f[2], si, sj);
      b[idx[k]] += si;
      b[idx[k1]] += sj;
      acc -= si + sj;  // the virtual vertex's hat gradient is -(g_i + g_j)
    }
    for (int k = 0; k < n; ++k) b[idx[k]] += w[k] * acc;
  } else {
    double uk[N], si[N], sj[N];
    for (int k = 0; k < N; ++k) uk[k] = u[idx[k]];
    double uf = 0;
    for (int k = 0; k < N; ++k) uf += w[k] * uk[k];
    for (int k = 0; k < N; ++k) {
      const int k1 = k + 1 == N ? 0 : k + 1;
      const double di = uk[k] - uf, dj = uk[k1] - uf, *f = R + 3 * k;
      si[k] = sj[k] = 0;
      if (!skip[k] && fan_shares_direct(di, dj, f[0], f[1], f[2], si[k], sj[k]))
        fan_shares_rescaled(di, dj, f[0], f[1], f[2], si[k], sj[k]);
    }
    double acc = 0;
    for (int k = 0; k < N; ++k) acc -= si[k] + sj[k];
    // Corner k: fan triangle k's share as its first corner, triangle k - 1's as its second, and
    // its weight's share of the virtual vertex's.
    for (int k = 0; k < N; ++k) b[idx[k]] += (si[k] + sj[k == 0 ? N - 1 : k - 1]) + w[k] * acc;
  }
}

// fan_gradient_divergence for one column (distance()): face by face, unrolled for 3 to 6 corners.
[[gnu::always_inline]] inline void fan_gradient_divergence_one_body(const FanTable& fan, const int* fi, const double* u,
                                                                    double* b) {
  const int* fo = fan.offsets.data();
  const double* w = fan.weights.data();
  const unsigned char* skip = fan.degenerate.data();
  const int nf = int(fan.offsets.size()) - 1;
  for (int f = 0; f < nf; ++f) {
    const int h0 = fo[f], n = fo[f + 1] - h0;
    const double* R = fan.frames.data() + 3 * size_t(h0);
    switch (n) {
      case 4: fan_face<4>(n, R, skip + h0, fi + h0, w + h0, u, b); break;
      case 3: fan_face<3>(n, R, skip + h0, fi + h0, w + h0, u, b); break;
      case 5: fan_face<5>(n, R, skip + h0, fi + h0, w + h0, u, b); break;
      case 6: fan_face<6>(n, R, skip + h0, fi + h0, w + h0, u, b); break;
      default: fan_face<0>(n, R, skip + h0, fi + h0, w + h0, u, b); break;
    }
  }
}

// The one-column pass has no AVX-512 variant: built so it took 5-10% longer per source here
// (docs/benchmarks.md, "Heat geodesics: AVX-512 block kernels").
POLYDEC_SIMD_VARIANTS(fan_gradient_divergence_one, (const FanTable& fan, const int* fi, const double* u, double* b),
                      (fan, fi, u, b), fan_gradient_divergence_one_body)

// b += -D g for g = -grad u / |grad u| on every fan triangle (eqs. 32-33; D = -G^T W), face by
// face from HeatGeodesics' fan table (fan_frame per fan triangle, fan_shares): m columns at once,
// row-major (the m values of u and b at corner h of the table at U + fi[h] m and B + fi[h] m: fi
// the table's corners, or their rows in another order). The virtual vertex's share goes to the
// corners by the weights. `scratch` holds 2 m values.
constexpr int kPrefetchFaces = 2;
template <int Bytes>
[[gnu::always_inline]] inline void fan_gradient_divergence_body(const FanTable& fan, const int* fi, const double* U,
                                                                int m, double* B, std::vector<double>& scratch) {
  if (m == 1) return fan_gradient_divergence_one_body(fan, fi, U, B);
  scratch.assign(2 * size_t(m), 0.0);
  double* uf = scratch.data();
  double* acc = uf + m;
  const int* fo = fan.offsets.data();
  const int nf = int(fan.offsets.size()) - 1;
  for (int f = 0; f < nf; ++f) {
    const int b0 = fo[f], n = fo[f + 1] - b0;
    // The rows of the face kPrefetchFaces ahead, scattered over the blocks.
    if (f + kPrefetchFaces < nf)
      for (int e = fo[f + kPrefetchFaces]; e < fo[f + kPrefetchFaces + 1]; ++e)
        for (int c = 0; c < m; c += 8) {
          __builtin_prefetch(U + size_t(fi[e]) * m + c);
          __builtin_prefetch(B + size_t(fi[e]) * m + c, 1);
        }
    std::fill(uf, uf + 2 * m, 0.0);
    for (int k = 0; k < n; ++k) {
      const double w = fan.weights[size_t(b0 + k)];
      const double* u = U + size_t(fi[b0 + k]) * m;
      for (int c = 0; c < m; ++c) uf[c] += w * u[c];
    }
    for (int k = 0; k < n; ++k) {
      if (fan.degenerate[size_t(b0 + k)]) continue;  // no gradient, no divergence
      const int k1 = (k + 1) % n;
      const int i = fi[b0 + k], j = fi[b0 + k1];
      fan_columns(m, fan.frames.data() + 3 * size_t(b0 + k), U + size_t(i) * m, U + size_t(j) * m, uf,
                  B + size_t(i) * m, B + size_t(j) * m, acc);
    }
    for (int k = 0; k < n; ++k) {
      const double w = fan.weights[size_t(b0 + k)];
      double* b = B + size_t(fi[b0 + k]) * m;
      for (int c = 0; c < m; ++c) b[c] += w * acc[c];
    }
  }
}
POLYDEC_SIMD_WIDE_VARIANTS(fan_gradient_divergence,
                           (const FanTable& fan, const int* fi, const double* U, int m, double* B,
                            std::vector<double>& scratch),
                           (fan, fi, U, m, B, scratch), fan_gradient_divergence_body)

}  // namespace

HeatGeodesics::HeatGeodesics(const Mesh& mesh, const HeatGeodesicsOptions& options)
    : HeatGeodesics(build_operators(mesh, parse_laplacian("ours"), {.gradient_with_refinement = false}),
                    mesh.mean_edge_length(), options) {}

HeatGeodesics::HeatGeodesics(OperatorSet operators, double mean_edge_length, const HeatGeodesicsOptions& options)
    : ops_(take_operators(operators)), options_(options) {
  // By shape, not by emptiness: a mesh without faces has a 0 x |V| gradient. |V| is S's size, so
  // that an operator set without a surface domain (a volume mesh's, operators/registry/volume_laplacians.h)
  // works the same way.
  const int nv = int(ops_.S.rows());
  // Operators with one virtual vertex per face carry the refinement G and D are built from: the
  // face-wise pass reads its fan triangles, the same ones as G and D (tests/apps/applications/
  // test_geodesics.cpp compares the two routes), without refining again, and needs no G and D.
  const Mesh& domain = ops_.domain;
  const bool face_wise = ops_.refinement && domain.n_vertices() == nv &&
                         (ops_.G.rows() == 3 * domain.n_halfedges() || (ops_.G.size() == 0 && ops_.D.size() == 0));
  if (!face_wise && (ops_.G.cols() != nv || ops_.D.rows() != nv))
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
  // factorization. The ordering with the smaller factor of AMD and nested dissection: every solve
  // reads the whole factor, and the one analysis serves both matrices (docs/benchmarks.md).
  CholeskyOptions copt;
  copt.relaxed_supernodes = false;
  copt.ordering = CholeskyOrdering::BestFill;
  // Both matrices on the pattern of M - t S (pinned entries kept as zeros), so that the Poisson
  // operator is factored with the heat operator's analysis.
  heat_ = std::make_unique<SparseCholesky>(pin_to_identity(heat, pinned_, true), "heat operator M - t S", copt);

  // Poisson operator -S with one vertex pinned per component (S has constants per component in
  // its null space; the right-hand side D g sums to zero on each, so pinning loses nothing).
  std::vector<unsigned char> seen(
      component_.empty() ? 0 : std::max(0, *std::max_element(component_.begin(), component_.end()) + 1), 0);
  for (int v = 0; v < nv; ++v)
    if (component_[v] >= 0 && !seen[component_[v]]) {
      seen[component_[v]] = 1;
      pinned_[v] = 1;
    }
  const SparseMatrix poisson = 0.0 * heat - ops_.S;  // -S on the heat operator's pattern
  poisson_ = std::make_unique<SparseCholesky>(
      heat_->with_values(pin_to_identity(poisson, pinned_, true), "Poisson operator -S"));

  if (face_wise) {
    const Refinement& r = *ops_.refinement;
    check_refinement(domain, r, "HeatGeodesics");
    // The faces by their first row in the factors' order (a stable sort: ties keep the mesh's order).
    const int nf = domain.n_faces();
    const std::span<const int> order = heat_->factor_order();
    std::vector<int> row(static_cast<size_t>(nv)), first(static_cast<size_t>(nf), nv), faces(static_cast<size_t>(nf));
    for (int q = 0; q < nv; ++q) row[size_t(order.empty() ? q : order[size_t(q)])] = q;
    for (int f = 0; f < nf; ++f)
      for (int v : domain.face(f)) first[size_t(f)] = std::min(first[size_t(f)], row[size_t(v)]);
    std::iota(faces.begin(), faces.end(), 0);
    std::stable_sort(faces.begin(), faces.end(), [&](int a, int b) { return first[size_t(a)] < first[size_t(b)]; });
    const size_t nh = size_t(domain.n_halfedges());
    fan_.offsets.assign(size_t(nf) + 1, 0);
    fan_.corners.resize(nh);
    fan_.weights.resize(nh);
    fan_.degenerate.resize(nh);
    assign_on_huge_pages(fan_.frames, 3 * nh, 0.0);
    size_t h = 0;
    for (int q = 0; q < nf; ++q) {
      const int f = faces[size_t(q)];
      const auto face = domain.face(f);
      const int h0 = domain.face_offsets()[f], n = int(face.size());
      for (int k = 0; k < n; ++k, ++h) {
        const int k1 = k + 1 == n ? 0 : k + 1;
        double ri[3], rj[3];
        for (int c = 0; c < 3; ++c) {
          ri[c] = r.virtual_points(f, c) - domain.positions()(face[k], c);
          rj[c] = r.virtual_points(f, c) - domain.positions()(face[k1], c);
        }
        fan_frame(ri, rj, fan_.frames.data() + 3 * h);
        fan_.corners[h] = face[k];
        fan_.weights[h] = r.weights[size_t(h0 + k)];
        fan_.degenerate[h] = r.fan[size_t(h0 + k)] == FanTriangle::Degenerate;
      }
      fan_.offsets[size_t(q) + 1] = int(h);
    }
  }
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
  const std::lock_guard guard(*lock_);
  const FlushSubnormals flush;
  std::vector<unsigned char> reached_component(nv + 1, 0);
  for (int s : sources) reached_component[component_[s]] = 1;
  // (31): (M - t S) u = M delta, a right-hand side with few non-zeros (at the distinct sources,
  // or their mass matrix columns), solved forward over their reach only.
  std::vector<int>& rows = work_rows_;
  std::vector<double>& values = work_values_;
  rows.assign(sources.begin(), sources.end());
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  if (!options_.mass_weighted_source) {
    values.assign(rows.size(), 1.0);
  } else if (options_.lumped_mass) {
    values.resize(rows.size());
    for (size_t k = 0; k < rows.size(); ++k) values[k] = ops_.M_lumped[rows[k]];
  } else {
    // M delta: the sources' columns of M summed row by row in the order of the sources (as the
    // product M * delta sums them), rows without stiffness left out.
    std::vector<std::pair<int, double>> entries;
    for (int s : rows)
      for (SparseMatrix::InnerIterator it(ops_.M, s); it; ++it)
        if (component_[it.row()] >= 0) entries.emplace_back(int(it.row()), it.value());
    std::stable_sort(entries.begin(), entries.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    rows.clear();
    values.clear();
    for (const auto& [r, v] : entries) {
      if (!rows.empty() && rows.back() == r) {
        values.back() += v;
      } else {
        rows.push_back(r);
        values.push_back(v);
      }
    }
  }
  Eigen::VectorXd& u = work_u_;
  u.resize(nv);
  heat_->solve_sparse(rows, values, u.data());

  // (32): g = -grad u / |grad u| per element (fan triangle; or the blocks the operator set names);
  // zero where the gradient vanishes. (33): S d = D g, solved as (-S) d = -D g with pinned vertices.
  Eigen::VectorXd& b = work_b_;
  if (!fan_.frames.empty()) {
    b.setZero(nv);
    fan_gradient_divergence_one(fan_, fan_.corners.data(), u.data(), b.data());
  } else {
    Eigen::VectorXd g = ops_.G * u;
    const int n_blocks = ops_.G_blocks.empty() ? int(g.size() / 3) : int(ops_.G_blocks.size()) - 1;
    for (int h = 0; h < n_blocks; ++h) {
      const int b0 = ops_.G_blocks.empty() ? 3 * h : ops_.G_blocks[h];
      const int b1 = ops_.G_blocks.empty() ? 3 * h + 3 : ops_.G_blocks[h + 1];
      normalize_block(g.data() + b0, b1 - b0, 1);
    }
    b = -(ops_.D * g);
  }
  for (int v = 0; v < nv; ++v)
    if (pinned_[v]) b[v] = 0;
  Eigen::VectorXd d(n_out);
  if (n_out == nv) {
    poisson_->solve(b.data(), d.data(), 1);
  } else {
    work_d_.resize(nv);
    poisson_->solve(b.data(), work_d_.data(), 1);
    d = work_d_.head(n_out);
  }

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
  if (block < 1) throw std::invalid_argument(fmt::format("heat geodesics: block size {} must be positive", block));
  check_sources(sources);
  Eigen::MatrixXd out(ops_.n_input_vertices, Eigen::Index(sources.size()));
  advise_huge_pages(out.data(), sizeof(double) * size_t(out.size()));
  distances(sources, out, block);
  return out;
}

void HeatGeodesics::distances(std::span<const int> sources, Eigen::Ref<Eigen::MatrixXd> out, int block) const {
  const int nv = int(ops_.S.rows()), n_out = ops_.n_input_vertices, k = int(sources.size());
  if (block < 1) throw std::invalid_argument(fmt::format("heat geodesics: block size {} must be positive", block));
  check_sources(sources);
  if (out.rows() != n_out || out.cols() != k)
    throw std::invalid_argument(fmt::format("heat geodesics: the output is {} x {}, the distances from {} sources are "
                                            "{} x {}", out.rows(), out.cols(), k, n_out, k));
  const std::lock_guard guard(*lock_);
  const FlushSubnormals flush;
  // The blocks stay in the factors' row order (both factors share one analysis) from the
  // right-hand sides to the distances: row[v] is vertex v's row. The solves then need no copies
  // (SparseCholesky::solve_rows_in_factor_order), and the passes over faces read through row[].
  const std::span<const int> order = heat_->factor_order();
  const std::span<const int> poisson_order = poisson_->factor_order();
  const bool ordered =
      !order.empty() && std::equal(order.begin(), order.end(), poisson_order.begin(), poisson_order.end());
  std::vector<int> row(static_cast<size_t>(nv));
  for (int q = 0; q < nv; ++q) row[size_t(ordered ? order[size_t(q)] : q)] = q;
  auto solve = [&](const SparseCholesky& chol, double* X, int m, std::span<const int> nonzero_rows) {
    if (ordered)
      chol.solve_rows_in_factor_order(X, m, nonzero_rows);
    else
      chol.solve_rows(X, m);  // row[] is the identity
  };
  std::vector<int> corner_rows;
  if (!fan_.frames.empty()) {
    const std::vector<int>& fi = fan_.corners;
    corner_rows.resize(fi.size());
    for (size_t h = 0; h < fi.size(); ++h) corner_rows[h] = row[size_t(fi[h])];
  }
  // G row by row (a gather per gradient entry) and D column by column (a scatter into the small
  // right-hand side): one pass over both for all columns of a block. The paper's operator runs
  // face by face instead and needs no copy of G.
  Eigen::SparseMatrix<double, Eigen::RowMajor> Gr;
  if (fan_.frames.empty()) Gr = ops_.G;
  const int n_blocks = ops_.G_blocks.empty() ? int(ops_.G.rows() / 3) : int(ops_.G_blocks.size()) - 1;
  int widest = 3;
  for (int h = 0; h < n_blocks && !ops_.G_blocks.empty(); ++h)
    widest = std::max(widest, ops_.G_blocks[h + 1] - ops_.G_blocks[h]);
  // Two blocks of nv x width values, kept between calls, on huge pages (fresh 4 KB pages cost ~13
  // us each here: 49 MB a block of 64 columns on FINE SPHERE), row-major (the m values of a row
  // contiguous): U the heat step's right-hand sides and solutions, B the Poisson step's, both
  // solved in place and read by the fused pass.
  const int width = std::min(block, k);
  const size_t cells = size_t(nv) * size_t(width);
  if (block_cells_ != cells) {
    block_u_.reset();  // before the new ones: not both pairs at once
    block_b_.reset();
    block_u_ = uninitialized_on_huge_pages<double>(cells);
    block_b_ = uninitialized_on_huge_pages<double>(cells);
    block_cells_ = cells;
  }
  std::vector<double> g(size_t(widest) * size_t(width));  // block row i's m values at g + i m
  std::vector<double> cmin(static_cast<size_t>(width));
  std::vector<int> reached(static_cast<size_t>(width)), rhs_rows;
  for (int c0 = 0; c0 < k; c0 += block) {
    const int m = std::min(block, k - c0);
    double* U = block_u_.get();  // vertex v's m values at U + row[v] m
    double* Bv = block_b_.get();
    // (31) for m sources at once; the forward solve over the reach of the right-hand sides' rows.
    std::fill(U, U + size_t(nv) * size_t(m), 0.0);
    rhs_rows.clear();
    for (int c = 0; c < m; ++c) {
      const int s = sources[size_t(c0 + c)];
      if (!options_.mass_weighted_source || options_.lumped_mass) {
        rhs_rows.push_back(row[size_t(s)]);
        U[size_t(row[size_t(s)]) * m + c] = options_.mass_weighted_source ? ops_.M_lumped[s] : 1.0;
      } else {
        for (SparseMatrix::InnerIterator it(ops_.M, s); it; ++it)
          if (component_[it.row()] >= 0) {
            rhs_rows.push_back(row[size_t(it.row())]);
            U[size_t(row[size_t(it.row())]) * m + c] = it.value();
          }
      }
    }
    solve(*heat_, U, m, rhs_rows);
    std::fill(Bv, Bv + size_t(nv) * size_t(m), 0.0);
    if (!fan_.frames.empty()) fan_gradient_divergence(fan_, corner_rows.data(), U, m, Bv, g);
    for (int h = 0; h < n_blocks && fan_.frames.empty(); ++h) {
      const int b0 = ops_.G_blocks.empty() ? 3 * h : ops_.G_blocks[h];
      const int b1 = ops_.G_blocks.empty() ? 3 * h + 3 : ops_.G_blocks[h + 1];
      for (int r = b0; r < b1; ++r) {
        double* gr = g.data() + size_t(r - b0) * m;
        std::fill(gr, gr + m, 0.0);
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Gr, r); it; ++it) {
          const double a = it.value();
          const double* u = U + size_t(row[size_t(it.col())]) * m;
          for (int c = 0; c < m; ++c) gr[c] += a * u[c];
        }
      }
      for (int c = 0; c < m; ++c) normalize_block(g.data() + c, b1 - b0, m);  // (32)
      for (int r = b0; r < b1; ++r) {
        const double* gr = g.data() + size_t(r - b0) * m;
        for (SparseMatrix::InnerIterator it(ops_.D, r); it; ++it) {
          const double a = it.value();
          double* b = Bv + size_t(row[size_t(it.row())]) * m;
          for (int c = 0; c < m; ++c) b[c] -= a * gr[c];
        }
      }
    }
    // (33) for the m right-hand sides, pinned rows zero.
    for (int v = 0; v < nv; ++v)
      if (pinned_[v]) std::fill(Bv + size_t(row[size_t(v)]) * m, Bv + size_t(row[size_t(v)] + 1) * m, 0.0);
    solve(*poisson_, Bv, m, {});
    // Each column shifted to zero at its minimum over its source's component (one pass over the
    // rows for all columns), written column by column eight vertices at a time.
    for (int c = 0; c < m; ++c) reached[size_t(c)] = component_[sources[size_t(c0 + c)]];
    const bool one_component =
        std::all_of(reached.begin(), reached.begin() + m, [&](int r) { return r == reached[0]; });
    std::fill(cmin.begin(), cmin.begin() + m, std::numeric_limits<double>::infinity());
    for (int q = 0; q < nv; ++q) {  // in storage order
      const int v = ordered ? order[size_t(q)] : q;
      if (v >= n_out) continue;
      const int comp = component_[v];
      const double* x = Bv + size_t(q) * m;
      if (one_component) {
        if (comp == reached[0])
          for (int c = 0; c < m; ++c) cmin[size_t(c)] = std::min(cmin[size_t(c)], x[c]);
      } else {
        for (int c = 0; c < m; ++c)
          if (comp == reached[size_t(c)]) cmin[size_t(c)] = std::min(cmin[size_t(c)], x[c]);
      }
    }
    constexpr int kRun = 8;  // vertices per column run: one cache line of out
    for (int v0 = 0; v0 < n_out; v0 += kRun) {
      const int v1 = std::min(n_out, v0 + kRun);
      for (int v = v0 + kRun; v < std::min(n_out, v0 + 2 * kRun); ++v)  // the next run's rows
        for (int c = 0; c < m; c += 8) __builtin_prefetch(Bv + size_t(row[size_t(v)]) * m + c);
      for (int c = 0; c < m; ++c) {
        double* o = out.col(c0 + c).data();
        for (int v = v0; v < v1; ++v)
          o[v] = component_[v] == reached[size_t(c)] ? Bv[size_t(row[size_t(v)]) * m + c] - cmin[size_t(c)]
                                                     : std::numeric_limits<double>::infinity();
      }
    }
  }
}

void HeatGeodesics::release_blocks() const {
  const std::lock_guard guard(*lock_);
  block_u_.reset();
  block_b_.reset();
  block_cells_ = 0;
}

double rmse(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() == 0) return 0.0;
  return std::sqrt((a - b).squaredNorm() / double(a.size()));
}

}  // namespace polydec
