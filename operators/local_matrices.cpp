// operators/local_matrices.cpp — coarsened local stiffness and mass of one polygon.
#include "operators/local_matrices.h"

#include <cmath>
#include <vector>

namespace polydec {

Eigen::Vector3d triangle_half_cotangents(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                         const Eigen::Vector3d& p2) {
  const Eigen::Vector3d e0 = p2 - p1, e1 = p0 - p2, e2 = p1 - p0;  // edge opposite each corner
  const double twice_area = e2.cross(-e1).norm();
  // cot(angle at a) = <u, v> / |u x v| with u, v the edges leaving a.
  return Eigen::Vector3d(e2.dot(-e1), e0.dot(-e2), e1.dot(-e0)) / (2.0 * twice_area);
}

void polygon_matrices_compact(const double* x, int n, const double* w, const double* xf, const FanTriangle* fan,
                              double* S, double* M) {
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

void polygon_matrices(const PolygonPositions& X, const Eigen::VectorXd& w, const Eigen::Vector3d& xf,
                      const FanTriangle* fan, Eigen::MatrixXd* S, Eigen::MatrixXd* M) {
  const int n = int(X.rows());
  std::vector<double> x(3 * n), cs(S ? 3 * n : 0), cm(M ? 3 * n : 0);
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) x[3 * k + d] = X(k, d);
  polygon_matrices_compact(x.data(), n, w.data(), xf.data(), fan, S ? cs.data() : nullptr, M ? cm.data() : nullptr);
  if (S) {
    S->resize(n, n);
    for (int b = 0; b < n; ++b) expand_local_column(n, b, w.data(), cs.data(), S->col(b).data());
  }
  if (M) {
    M->resize(n, n);
    for (int b = 0; b < n; ++b) expand_local_column(n, b, w.data(), cm.data(), M->col(b).data());
  }
}

}  // namespace polydec
