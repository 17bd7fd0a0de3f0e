// dec/volume/whitney.cpp — closed-form Whitney inner products on one tetrahedron.
#include "polydec/dec/volume/whitney.h"

#include <Eigen/Dense>
#include <cmath>

#include "polydec/dec/detail/scale.h"

namespace polydec {

namespace volume_whitney_detail {
namespace {

constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
constexpr int kTriangles[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};

double delta(int a, int b) { return a == b ? 1.0 : 0.0; }

// x times 2^power, entry by entry (exact unless the result leaves the normal range).
template <class M>
M scaled(const M& x, int power) {
  if (power == 0) return x;
  return x.unaryExpr([power](double v) { return std::ldexp(v, power); });
}
inline double scaled(double x, int power) { return power == 0 ? x : std::ldexp(x, power); }

// The edges p1 - p0, p2 - p0, p3 - p0 scaled by 2^-k (k = 0 for ordinary sizes, dec/detail/scale.h):
// every kernel below works on them and scales its result back by the power of 2^k its units
// carry, so that volumes (cubes) and inverse volumes hold wherever the result is representable.
struct Edges {
  Eigen::Vector3d e1, e2, e3;
  int k = 0;
  Edges(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3)
      : e1(p1 - p0), e2(p2 - p0), e3(p3 - p0) {
    const double extent = std::fmax(e1.cwiseAbs().maxCoeff(), std::fmax(e2.cwiseAbs().maxCoeff(), e3.cwiseAbs().maxCoeff()));
    k = detail::normalizing_exponent(extent);
    if (k != 0) e1 = scaled(e1, -k), e2 = scaled(e2, -k), e3 = scaled(e3, -k);
  }
};

// Hat gradients and det [e1 e2 e3] in the scaled units of `e`.
Matrix34d scaled_hat_gradients(const Edges& e, double& det) {
  det = e.e1.dot(e.e2.cross(e.e3));
  // Rows of [e1 e2 e3]^-1 are the gradients of lambda_1..3: (e2 x e3, e3 x e1, e1 x e2) / det.
  Matrix34d G;
  G.col(1) = e.e2.cross(e.e3) / det;
  G.col(2) = e.e3.cross(e.e1) / det;
  G.col(3) = e.e1.cross(e.e2) / det;
  G.col(0) = -(G.col(1) + G.col(2) + G.col(3));
  return G;
}

}  // namespace
}  // namespace volume_whitney_detail

double tet_signed_volume(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                         const Eigen::Vector3d& p3) {
  using namespace volume_whitney_detail;
  const Edges e(p0, p1, p2, p3);
  return scaled(e.e1.dot(e.e2.cross(e.e3)) / 6.0, 3 * e.k);
}

Matrix34d tet_hat_gradients(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                            const Eigen::Vector3d& p3, double* signed_volume) {
  using namespace volume_whitney_detail;
  const Edges e(p0, p1, p2, p3);
  double det = 0;
  const Matrix34d G = scaled_hat_gradients(e, det);
  if (signed_volume) *signed_volume = scaled(det / 6.0, 3 * e.k);
  return scaled(G, -e.k);
}

Eigen::Matrix4d tet_stiffness(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                              const Eigen::Vector3d& p3) {
  using namespace volume_whitney_detail;
  const Edges e(p0, p1, p2, p3);
  double det = 0;
  const Matrix34d G = scaled_hat_gradients(e, det);
  const Eigen::Matrix4d S = -std::abs(det / 6.0) * (G.transpose() * G);
  return scaled(S, e.k);
}

Eigen::Matrix4d tet_whitney0_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                  const Eigen::Vector3d& p2, const Eigen::Vector3d& p3) {
  const double v = std::abs(tet_signed_volume(p0, p1, p2, p3)) / 20.0;
  return v * (Eigen::Matrix4d::Ones() + Eigen::Matrix4d::Identity());
}

Matrix6d tet_whitney1_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                           const Eigen::Vector3d& p3) {
  using namespace volume_whitney_detail;
  const Edges e(p0, p1, p2, p3);
  double det = 0;
  const Matrix34d Gr = scaled_hat_gradients(e, det);
  const Eigen::Matrix4d G = Gr.transpose() * Gr;
  const double s = std::abs(det / 6.0) / 20.0;
  Matrix6d M;
  for (int r = 0; r < 6; ++r)
    for (int q = 0; q < 6; ++q) {
      const int a = kEdges[r][0], b = kEdges[r][1], c = kEdges[q][0], d = kEdges[q][1];
      M(r, q) = s * ((1 + delta(a, c)) * G(b, d) - (1 + delta(a, d)) * G(b, c) - (1 + delta(b, c)) * G(a, d) +
                     (1 + delta(b, d)) * G(a, c));
    }
  return scaled(M, e.k);
}

Eigen::Matrix4d tet_whitney2_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                  const Eigen::Vector3d& p2, const Eigen::Vector3d& p3) {
  using namespace volume_whitney_detail;
  const Edges e(p0, p1, p2, p3);
  double det = 0;
  const Matrix34d G = scaled_hat_gradients(e, det);
  // Triangle t = (a, b, c): phi = 2 (lambda_a v_a + lambda_b v_b + lambda_c v_c).
  int idx[4][3];
  Eigen::Vector3d v[4][3];
  for (int t = 0; t < 4; ++t) {
    const int a = kTriangles[t][0], b = kTriangles[t][1], c = kTriangles[t][2];
    idx[t][0] = a, idx[t][1] = b, idx[t][2] = c;
    v[t][0] = G.col(b).cross(G.col(c));
    v[t][1] = G.col(c).cross(G.col(a));
    v[t][2] = G.col(a).cross(G.col(b));
  }
  const double s = 4.0 * std::abs(det / 6.0) / 20.0;
  Eigen::Matrix4d M;
  for (int t = 0; t < 4; ++t)
    for (int u = 0; u < 4; ++u) {
      double sum = 0;
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) sum += (1 + delta(idx[t][p], idx[u][q])) * v[t][p].dot(v[u][q]);
      M(t, u) = s * sum;
    }
  return scaled(M, -e.k);
}

double tet_whitney3_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                         const Eigen::Vector3d& p3) {
  using namespace volume_whitney_detail;
  const Edges e(p0, p1, p2, p3);
  return scaled(1.0 / std::abs(e.e1.dot(e.e2.cross(e.e3)) / 6.0), -3 * e.k);
}

}  // namespace polydec
