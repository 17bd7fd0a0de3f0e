// operators/local_matrices.h — per-face kernels: the coarsened stiffness and mass of one
// polygon, P_f^T S^f P_f and P_f^T M^f P_f (eq. 12-13), from its positions, its virtual-vertex
// weights and its fan-triangle classification. Pure functions; no mesh needed.
#pragma once

#include "dec/refinement.h"

#include <Eigen/Core>

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
inline void expand_local_column(int n, int b, const double* w, const double* c, double* out) {
  const double* d = c;
  const double* o = c + n;
  const double* t = c + 2 * n;
  for (int a = 0; a < n; ++a) out[a] = t[a] * w[b] + w[a] * t[b];
  const int next = b + 1 == n ? 0 : b + 1, prev = b == 0 ? n - 1 : b - 1;
  out[b] += d[b];
  out[next] += o[b];
  out[prev] += o[prev];
}

}  // namespace polydec
