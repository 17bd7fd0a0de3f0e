// operators/surface/local_matrices.cpp — coarsened local stiffness and mass of one polygon.
#include "polydec/operators/surface/local_matrices.h"

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
  detail::polygon_compact<0>(x, n, w, xf, fan, S, M);
}

void expand_local_column(int n, int b, const double* w, const double* c, double* out) {
  detail::expand_column<0>(n, b, w, c, out);
}

void local_column_sums(int n, const double* w, const double* c, double* out) {
  detail::column_sums<0>(n, w, c, out);
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
