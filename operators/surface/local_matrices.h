// operators/surface/local_matrices.h — per-face kernels: the coarsened stiffness and mass of one
// polygon, P_f^T S^f P_f and P_f^T M^f P_f (eq. 12-13), from its positions, its virtual-vertex
// weights and its fan-triangle classification. Pure functions; no mesh needed.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "polydec/dec/surface/refinement.h"

namespace polydec {

// Half cotangents of the angles of triangle (p0, p1, p2): c[a] = cot(angle at corner a) / 2.
// The cotangent stiffness of the triangle is S_ab = c[3 - a - b] for a != b (eq. 3).
Eigen::Vector3d triangle_half_cotangents(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                         const Eigen::Vector3d& p2);

// Coarsened local stiffness S_f (n x n, negative semi-definite) and Galerkin mass M_f (n x n)
// of a polygon with corners X (n x 3), weights w and virtual point xf. Fan triangle k is
// (x_k, x_{k+1}, xf); fan[k] says whether it is degenerate (then it adds no stiffness).
// Either output may be null.
void polygon_matrices(const PolygonPositions& X, const Eigen::VectorXd& w, const Eigen::Vector3d& xf,
                      const FanTriangle* fan, Eigen::MatrixXd* S, Eigen::MatrixXd* M);

// The same matrices in compact, rank-structured form, without allocating. With P_f = [I; w^T]
// and a fan matrix A^f = [T a; a^T alpha] (T cyclic tridiagonal over the corners),
// P_f^T A^f P_f = T + t w^T + w t^T with t = a + alpha w / 2. Writes 3n doubles per requested
// matrix: T's diagonal d[0..n), T's cyclic off-diagonal o[k] = T(k, k+1 mod n), then t.
// x holds the n corners row by row; S or M may be null.
void polygon_matrices_compact(const double* x, int n, const double* w, const double* xf, const FanTriangle* fan,
                              double* S, double* M);

// Column b of the local matrix from its compact form c (3n doubles) and the weights w:
// out[a] = t_a w_b + w_a t_b, plus d_b on the diagonal and o on the two cyclic neighbours.
// Every assembly path uses this one expression, so results are bitwise reproducible.
void expand_local_column(int n, int b, const double* w, const double* c, double* out);

// The n column sums (= row sums: the matrix is symmetric) of the local matrix from its compact
// form: out[b] = t_b sum(w) + w_b sum(t) + d_b + o_b + o_{b-1}, for any weights w.
void local_column_sums(int n, const double* w, const double* c, double* out);

namespace detail {

// The kernels behind the two functions above, for a face size N fixed at compile time
// (N = 0: the size n given at run time), so that the assembly's inner loops unroll.
template <int N>
inline void polygon_compact(const double* x, int n_dyn, const double* w, const double* xf, const FanTriangle* fan,
                            double* S, double* M) {
  const int n = N > 0 ? N : n_dyn;
  double sigma = 0.0, mu = 0.0;
  if (S)
    for (int k = 0; k < 3 * n; ++k) S[k] = 0.0;
  if (M)
    for (int k = 0; k < 3 * n; ++k) M[k] = 0.0;
  for (int k = 0; k < n; ++k) {
    const int l = k + 1 == n ? 0 : k + 1;
    const double* p = x + 3 * k;
    const double* q = x + 3 * l;
    // Fan triangle (x_k, x_l, x_f): a = x_k - x_f, b = x_l - x_f, u = x_l - x_k.
    const double a[3] = {p[0] - xf[0], p[1] - xf[1], p[2] - xf[2]};
    const double b[3] = {q[0] - xf[0], q[1] - xf[1], q[2] - xf[2]};
    const double cr[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    const double twice_area = std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
    if (S && fan[k] != FanTriangle::Degenerate) {
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const double h = 0.5 / twice_area;  // half cotangent = <edges leaving the corner> / (2 |cross|)
      const double ck = -(u[0] * a[0] + u[1] * a[1] + u[2] * a[2]) * h;  // at x_k, opposite edge (l, f)
      const double cl = (u[0] * b[0] + u[1] * b[1] + u[2] * b[2]) * h;   // at x_l, opposite edge (k, f)
      const double cf = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) * h;   // at x_f, opposite edge (k, l)
      S[n + k] = cf;
      S[k] -= cf + cl;
      S[l] -= cf + ck;
      S[2 * n + l] += ck;
      S[2 * n + k] += cl;
      sigma -= ck + cl;
    }
    if (M) {
      const double a12 = twice_area / 24.0;  // area / 12
      M[k] += 2 * a12;
      M[l] += 2 * a12;
      M[n + k] = a12;
      M[2 * n + k] += a12;
      M[2 * n + l] += a12;
      mu += 2 * a12;
    }
  }
  for (int k = 0; k < n; ++k) {
    if (S) S[2 * n + k] += 0.5 * sigma * w[k];
    if (M) M[2 * n + k] += 0.5 * mu * w[k];
  }
}

template <int N>
[[gnu::always_inline]] inline void expand_column(int n_dyn, int b, const double* w, const double* c, double* out) {
  const int n = N > 0 ? N : n_dyn;
  const double* d = c;
  const double* o = c + n;
  const double* t = c + 2 * n;
  for (int a = 0; a < n; ++a) out[a] = t[a] * w[b] + w[a] * t[b];
  const int next = b + 1 == n ? 0 : b + 1, prev = b == 0 ? n - 1 : b - 1;
  out[b] += d[b];
  out[next] += o[b];
  out[prev] += o[prev];
}

template <int N>
[[gnu::always_inline]] inline void column_sums(int n_dyn, const double* w, const double* c, double* out) {
  const int n = N > 0 ? N : n_dyn;
  const double* d = c;
  const double* o = c + n;
  const double* t = c + 2 * n;
  double sw = 0.0, st = 0.0;
  for (int a = 0; a < n; ++a) {
    sw += w[a];
    st += t[a];
  }
  for (int b = 0; b < n; ++b) out[b] = t[b] * sw + w[b] * st + d[b] + o[b] + o[b == 0 ? n - 1 : b - 1];
}

}  // namespace detail

}  // namespace polydec
