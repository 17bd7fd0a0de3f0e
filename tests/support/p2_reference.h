// tests/support/p2_reference.h — an independent quadratic Lagrange (P2) triangle for the tests: the
// basis from the inverse Vandermonde matrix of the monomials 1, u, v, u^2, uv, v^2 in an
// orthonormal frame of the triangle's plane, integrated by Dunavant's 6-point rule (exact for
// degree 4, so for both the stiffness and the mass). Node order as dec/surface/quadratic.h.
#pragma once

#include <Eigen/Dense>

namespace polydec::test {

struct P2Reference {
  Eigen::Matrix<double, 6, 6> K, M;  // int grad phi_a . grad phi_b, int phi_a phi_b
};

inline P2Reference p2_reference(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                const Eigen::Vector3d& p2) {
  const Eigen::Vector3d e1 = (p1 - p0).normalized();
  const Eigen::Vector3d nrm = (p1 - p0).cross(p2 - p0);
  const Eigen::Vector3d e2 = nrm.normalized().cross(e1);
  const double area = 0.5 * nrm.norm();
  auto uv = [&](const Eigen::Vector3d& x) { return Eigen::Vector2d((x - p0).dot(e1), (x - p0).dot(e2)); };
  const Eigen::Vector2d c[3] = {uv(p0), uv(p1), uv(p2)};
  const Eigen::Vector2d nodes[6] = {
      c[0], c[1], c[2], (c[0] + c[1]) / 2, (c[1] + c[2]) / 2, (c[2] + c[0]) / 2};
  auto mono = [](const Eigen::Vector2d& x) {
    Eigen::Matrix<double, 6, 1> m;
    m << 1, x[0], x[1], x[0] * x[0], x[0] * x[1], x[1] * x[1];
    return m;
  };
  auto mono_grad = [](const Eigen::Vector2d& x) {
    Eigen::Matrix<double, 6, 2> g;
    g << 0, 0, 1, 0, 0, 1, 2 * x[0], 0, x[1], x[0], 0, 2 * x[1];
    return g;
  };
  Eigen::Matrix<double, 6, 6> V;
  for (int a = 0; a < 6; ++a) V.row(a) = mono(nodes[a]).transpose();
  const Eigen::Matrix<double, 6, 6> C = V.inverse();  // column a: the coefficients of phi_a
  const double w[2] = {0.223381589678011, 0.109951743655322};
  const double l[2][2] = {{0.108103018168070, 0.445948490915965}, {0.816847572980459, 0.091576213509771}};
  P2Reference r;
  r.K.setZero();
  r.M.setZero();
  for (int s = 0; s < 2; ++s)
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d b = Eigen::Vector3d::Constant(l[s][1]);
      b[k] = l[s][0];
      const Eigen::Vector2d x = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
      const Eigen::Matrix<double, 6, 1> phi = C.transpose() * mono(x);
      const Eigen::Matrix<double, 6, 2> g = C.transpose() * mono_grad(x);
      r.K += w[s] * area * g * g.transpose();
      r.M += w[s] * area * phi * phi.transpose();
    }
  return r;
}

}  // namespace polydec::test
