// dec/virtual_vertex.cpp — virtual-vertex weights of a single polygon (paper Appendix A).
#include "dec/virtual_vertex.h"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace polydec {

namespace {

// Relative eigenvalue cut-off for the rank decisions below. Eigenvalues of a 3x3 matrix of
// squared lengths below kRankTolerance times the largest are treated as zero: a polygon whose
// out-of-plane extent is below ~1e-7 of its size counts as planar, which matches where a
// complete orthogonal decomposition of eq. (38) makes the same decision.
constexpr double kRankTolerance = 1e-14;

// Pseudo-inverse solve of a symmetric positive semi-definite 3x3 system (eigenvalues below
// kRankTolerance times the largest are dropped).
void eigen_psd_solve(const Eigen::Matrix3d& A, const Eigen::Vector3d& b, double* x_out) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(A);
  const Eigen::Vector3d lambda = es.eigenvalues();
  const double cut = kRankTolerance * lambda.cwiseAbs().maxCoeff();
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
    if (lambda[i] > cut && lambda[i] > 0) x += es.eigenvectors().col(i) * (es.eigenvectors().col(i).dot(b) / lambda[i]);
  for (int i = 0; i < 3; ++i) x_out[i] = x[i];
}

// The LDL^T route is taken when the smallest eigenvalue provably exceeds kDirectTolerance
// times the largest (lambda_min >= 4 det / tr^2, lambda_max <= tr): then no eigenvalue is
// dropped by the eigen route, both solve the same regular system and agree to round-off
// (relative difference at most ~ machine epsilon / kDirectTolerance).
constexpr double kDirectTolerance = 1e-10;

// Symmetric 3x3 matrix (upper triangle) with a pseudo-inverse solve: LDL^T when well
// conditioned, the eigen decomposition otherwise (planar polygons: rank 2).
struct Sym3 {
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0;
  void add_outer(const double* v, double s) {
    a00 += s * v[0] * v[0];
    a01 += s * v[0] * v[1];
    a02 += s * v[0] * v[2];
    a11 += s * v[1] * v[1];
    a12 += s * v[1] * v[2];
    a22 += s * v[2] * v[2];
  }
  void add_diagonal(double s) {
    a00 += s;
    a11 += s;
    a22 += s;
  }
  void psd_solve(const double* b, double* x) const {
    const double tr = a00 + a11 + a22;
    if (a00 > 0) {
      const double l10 = a01 / a00, l20 = a02 / a00;
      const double d1 = a11 - l10 * a01;
      if (d1 > 0) {
        const double l21 = (a12 - l20 * a01) / d1;
        const double d2 = a22 - l20 * a02 - l21 * l21 * d1;
        if (d2 > 0 && 4 * a00 * d1 * d2 > kDirectTolerance * tr * tr * tr) {
          const double y0 = b[0], y1 = b[1] - l10 * y0, y2 = b[2] - l20 * y0 - l21 * y1;
          x[2] = y2 / d2;
          x[1] = y1 / d1 - l21 * x[2];
          x[0] = y0 / a00 - l10 * x[1] - l20 * x[2];
          return;
        }
      }
    }
    if (rank2_solve(b, x)) return;
    Eigen::Matrix3d M;
    M << a00, a01, a02, a01, a11, a12, a02, a12, a22;
    eigen_psd_solve(M, Eigen::Vector3d(b[0], b[1], b[2]), x);
  }

  // Planar case (centred positions of a planar polygon): when the Rayleigh quotient of the
  // null direction v (cross product of two rows) is below the cut for the largest eigenvalue
  // (lambda_max >= tr / 3), the eigen route would drop that direction: solve the 2x2 system in
  // the plane orthogonal to v instead, which is the same pseudo-inverse up to round-off.
  // Returns false when the case is not clear-cut (then the eigen route decides).
  bool rank2_solve(const double* b, double* x) const {
    const double r[3][3] = {{a00, a01, a02}, {a01, a11, a12}, {a02, a12, a22}};
    double v[3] = {0, 0, 0}, best = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) {
        const double c[3] = {r[i][1] * r[j][2] - r[i][2] * r[j][1], r[i][2] * r[j][0] - r[i][0] * r[j][2],
                             r[i][0] * r[j][1] - r[i][1] * r[j][0]};
        const double c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        if (c2 > best) {
          best = c2;
          v[0] = c[0], v[1] = c[1], v[2] = c[2];
        }
      }
    if (!(best > 0)) return false;
    const double inv = 1.0 / std::sqrt(best);
    for (double& vi : v) vi *= inv;
    auto quad = [&](const double* p, const double* q) {
      double s = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s += p[i] * r[i][j] * q[j];
      return s;
    };
    const double tr = a00 + a11 + a22;
    if (!(quad(v, v) <= kRankTolerance * tr / 3)) return false;
    // Orthonormal basis (u1, u2) of the plane orthogonal to v.
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(v[i]) < std::abs(v[k])) k = i;
    double e[3] = {0, 0, 0};
    e[k] = 1;
    double u1[3] = {v[1] * e[2] - v[2] * e[1], v[2] * e[0] - v[0] * e[2], v[0] * e[1] - v[1] * e[0]};
    const double n1 = 1.0 / std::sqrt(u1[0] * u1[0] + u1[1] * u1[1] + u1[2] * u1[2]);
    for (double& ui : u1) ui *= n1;
    const double u2[3] = {v[1] * u1[2] - v[2] * u1[1], v[2] * u1[0] - v[0] * u1[2], v[0] * u1[1] - v[1] * u1[0]};
    const double B00 = quad(u1, u1), B01 = quad(u1, u2), B11 = quad(u2, u2);
    const double det = B00 * B11 - B01 * B01, trB = B00 + B11;
    if (!(det > kDirectTolerance * trB * trB)) return false;
    const double c1 = u1[0] * b[0] + u1[1] * b[1] + u1[2] * b[2], c2 = u2[0] * b[0] + u2[1] * b[1] + u2[2] * b[2];
    const double s1 = (B11 * c1 - B01 * c2) / det, s2 = (B00 * c2 - B01 * c1) / det;
    for (int i = 0; i < 3; ++i) x[i] = s1 * u1[i] + s2 * u2[i];
    return true;
  }
};

// The weights for N corners (0: n given at run time), loops unrolled for fixed N.
template <int N>
void squared_area_weights_n(const double* x, int n_dyn, double* w, double* work) {
  const int n = N > 0 ? N : n_dyn;
  double c[3] = {0, 0, 0};
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) c[d] += x[3 * k + d];
  for (int d = 0; d < 3; ++d) c[d] /= n;
  double* Y = work;  // centred positions, n x 3 row-major
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) Y[3 * k + d] = x[3 * k + d] - c[d];

  // Minimizer over R^3 of E(y) = 1/2 sum_k |e_k x (y - y_k)|^2: A y = b with
  // A = sum_k (|e_k|^2 I - e_k e_k^T), b = sum_k (|e_k|^2 I - e_k e_k^T) y_k.
  // C = Y^T Y accumulated in the same pass.
  Sym3 A, C;
  double b[3] = {0, 0, 0};
  for (int k = 0; k < n; ++k) {
    const double* p = Y + 3 * k;
    const double* q = Y + 3 * (k + 1 == n ? 0 : k + 1);
    const double e[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    const double ep = e[0] * p[0] + e[1] * p[1] + e[2] * p[2];
    A.add_outer(e, -1.0);
    A.add_diagonal(ee);
    for (int d = 0; d < 3; ++d) b[d] += ee * p[d] - ep * e[d];
    C.add_outer(p, 1.0);
  }
  double y[3], z[3];
  A.psd_solve(b, y);
  // Least-norm w with sum w = 1 and Y^T w = y. Because Y is centred, the row of ones is
  // orthogonal to the columns of Y, so w = 1/n + Y (Y^T Y)^+ y.
  C.psd_solve(y, z);
  for (int k = 0; k < n; ++k) w[k] = 1.0 / n + (Y[3 * k] * z[0] + Y[3 * k + 1] * z[1] + Y[3 * k + 2] * z[2]);
}

}  // namespace

VirtualVertexRule parse_virtual_vertex_rule(const std::string& name) {
  if (name == "squared-area" || name == "affine") return VirtualVertexRule::SquaredArea;
  if (name == "centroid") return VirtualVertexRule::Centroid;
  throw std::invalid_argument("unknown virtual-vertex rule '" + name + "' (squared-area, centroid)");
}

std::string to_string(VirtualVertexRule rule) {
  switch (rule) {
    case VirtualVertexRule::SquaredArea: return "squared-area";
    case VirtualVertexRule::Centroid: return "centroid";
  }
  return "unknown";
}

Eigen::VectorXd centroid_weights(int n) { return Eigen::VectorXd::Constant(n, 1.0 / n); }

Eigen::VectorXd squared_area_weights(const PolygonPositions& X) {
  const int n = int(X.rows());
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> x = X;
  Eigen::VectorXd w(n), work(3 * n);
  squared_area_weights(x.data(), n, w.data(), work.data());
  return w;
}

void squared_area_weights(const double* x, int n, double* w, double* work) {
  switch (n) {
    case 3: squared_area_weights_n<3>(x, n, w, work); break;
    case 4: squared_area_weights_n<4>(x, n, w, work); break;
    case 5: squared_area_weights_n<5>(x, n, w, work); break;
    case 6: squared_area_weights_n<6>(x, n, w, work); break;
    default: squared_area_weights_n<0>(x, n, w, work); break;
  }
}

Eigen::VectorXd virtual_vertex_weights(const PolygonPositions& X, VirtualVertexRule rule) {
  switch (rule) {
    case VirtualVertexRule::SquaredArea: return squared_area_weights(X);
    case VirtualVertexRule::Centroid: return centroid_weights(int(X.rows()));
  }
  throw std::invalid_argument("unknown virtual-vertex rule");
}

}  // namespace polydec
