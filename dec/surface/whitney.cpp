// dec/surface/whitney.cpp — closed-form Whitney-form kernels on one triangle.
#include "polydec/dec/surface/whitney.h"

#include <Eigen/Geometry>

namespace polydec {

Eigen::Matrix3d hat_gradients(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                              const Eigen::Vector3d& p2) {
  // grad lambda_a = n x e_a / (2 area), e_a the edge opposite corner a, counter-clockwise about n.
  const Eigen::Vector3d e0 = p2 - p1, e1 = p0 - p2, e2 = p1 - p0;
  const Eigen::Vector3d N = e2.cross(-e1);  // 2 area * unit normal
  const double n2 = N.squaredNorm();        // (2 area)^2
  Eigen::Matrix3d g;
  g.col(0) = N.cross(e0) / n2;
  g.col(1) = N.cross(e1) / n2;
  g.col(2) = N.cross(e2) / n2;
  return g;
}

Eigen::Matrix3d whitney0_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                              const Eigen::Vector3d& p2) {
  const double a12 = 0.5 * (p1 - p0).cross(p2 - p0).norm() / 12.0;
  Eigen::Matrix3d m = Eigen::Matrix3d::Constant(a12);
  m.diagonal().array() += a12;
  return m;
}

Eigen::Matrix3d whitney1_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                              const Eigen::Vector3d& p2) {
  // The gradient Gram matrix from the opposite edges: G_ab = e_a . e_b / (2 area)^2.
  Eigen::Matrix3d E;
  E << p2 - p1, p0 - p2, p1 - p0;
  const double four_a2 = (p1 - p0).cross(p2 - p0).squaredNorm();
  const Eigen::Matrix3d G = E.transpose() * E / four_a2;
  const double a12 = 0.5 * std::sqrt(four_a2) / 12.0;
  static constexpr int edge[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  auto dlt = [](int x, int y) { return x == y ? 2.0 : 1.0; };  // 1 + delta
  Eigen::Matrix3d M;
  for (int r = 0; r < 3; ++r)
    for (int s = r; s < 3; ++s) {
      const int a = edge[r][0], b = edge[r][1], c = edge[s][0], d = edge[s][1];
      M(r, s) = M(s, r) =
          a12 * (dlt(a, c) * G(b, d) - dlt(a, d) * G(b, c) - dlt(b, c) * G(a, d) + dlt(b, d) * G(a, c));
    }
  return M;
}

double whitney2_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
  return 2.0 / (p1 - p0).cross(p2 - p0).norm();
}

Eigen::Vector3d whitney1_value(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                               const Eigen::Vector3d& p2, const Eigen::Vector3d& c,
                               const Eigen::Vector3d& bary) {
  const Eigen::Matrix3d g = hat_gradients(p0, p1, p2);
  auto w = [&](int a, int b) { return Eigen::Vector3d(bary[a] * g.col(b) - bary[b] * g.col(a)); };
  return c[0] * w(0, 1) + c[1] * w(0, 2) + c[2] * w(1, 2);
}

}  // namespace polydec
