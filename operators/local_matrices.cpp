// operators/local_matrices.cpp — coarsened local stiffness and mass of one polygon.
#include "operators/local_matrices.h"

namespace polydec {

Eigen::Vector3d triangle_half_cotangents(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                         const Eigen::Vector3d& p2) {
  const Eigen::Vector3d e0 = p2 - p1, e1 = p0 - p2, e2 = p1 - p0;  // edge opposite each corner
  const double twice_area = e2.cross(-e1).norm();
  // cot(angle at a) = <u, v> / |u x v| with u, v the edges leaving a.
  return Eigen::Vector3d(e2.dot(-e1), e0.dot(-e2), e1.dot(-e0)) / (2.0 * twice_area);
}

void polygon_matrices(const PolygonPositions& X, const Eigen::VectorXd& w, const Eigen::Vector3d& xf,
                      const FanTriangle* fan, Eigen::MatrixXd* S, Eigen::MatrixXd* M) {
  const int n = int(X.rows());
  // Refined fan matrices over (x_0 .. x_{n-1}, x_f), stored as the n x n corner block Sc
  // (cyclic tridiagonal), the corner-virtual column s and the virtual diagonal sigma.
  Eigen::MatrixXd Sc = Eigen::MatrixXd::Zero(n, n), Mc = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd s = Eigen::VectorXd::Zero(n), m = Eigen::VectorXd::Zero(n);
  double sigma = 0.0, mu = 0.0;
  for (int k = 0; k < n; ++k) {
    const int l = (k + 1) % n;
    const Eigen::Vector3d p = X.row(k).transpose(), q = X.row(l).transpose();
    if (S && fan[k] != FanTriangle::Degenerate) {
      const Eigen::Vector3d c = triangle_half_cotangents(p, q, xf);  // corners k, l, f
      // edge (k,l) opposite f: c[2]; edge (l,f) opposite k: c[0]; edge (k,f) opposite l: c[1]
      Sc(k, l) += c[2];
      Sc(l, k) += c[2];
      Sc(k, k) -= c[2] + c[1];
      Sc(l, l) -= c[2] + c[0];
      s[l] += c[0];
      s[k] += c[1];
      sigma -= c[0] + c[1];
    }
    if (M) {
      const double a12 = 0.5 * (q - p).cross(xf - p).norm() / 12.0;
      Mc(k, k) += 2 * a12;
      Mc(l, l) += 2 * a12;
      Mc(k, l) += a12;
      Mc(l, k) += a12;
      m[k] += a12;
      m[l] += a12;
      mu += 2 * a12;
    }
  }
  // P_f = [I; w^T]:  P^T A P = A_cc + a w^T + w a^T + alpha w w^T.
  if (S) *S = Sc + s * w.transpose() + w * s.transpose() + sigma * w * w.transpose();
  if (M) *M = Mc + m * w.transpose() + w * m.transpose() + mu * w * w.transpose();
}

}  // namespace polydec
