// dec/surface/virtual_vertex.cpp — virtual-vertex weights of a single polygon (paper Appendix A, section
// 4.2 variants, Bunge et al. 2024 trace minimizer).
#include "polydec/dec/surface/virtual_vertex.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace polydec {

namespace {

// Relative eigenvalue cut-off for psd_solve(): eigenvalues of a 3x3 matrix of squared lengths
// below kRankTolerance times the largest count as zero. Used for the squared-area system A, which
// is singular only for degenerate polygons (all edges parallel), and the absolute-area steps.
constexpr double kRankTolerance = 1e-10;

// The least-norm weights divide the polygon's out-of-plane part by its smallest singular value
// sigma_min, so round-off costs them about eps sigma_max / sigma_min. In double they are kept
// when sigma_min >= kDoubleCertified sigma_max (error ~1e-10) and recomputed in long double
// otherwise; flatter than kResolution sigma_max, long double cannot promise 1e-6 either
// (~1e-19 / 1e-11 times a small constant), so such a polygon counts as planar whatever its data.
constexpr double kDoubleCertified = 1e-6;
constexpr double kResolution = 1e-11;

// Singular values of the centred corners at or below which the polygon counts as planar
// (absolute, in the units of the coordinates): with a relative override, that fraction of the
// largest singular value sigma_max; otherwise the largest perturbation the corners' uncertainty
// allows (n x 3 entries of at most `noise` each: spectral norm <= sqrt(3n) noise) plus
// kResolution sigma_max.
template <class T>
T planarity_cut(const PlanarityCut& p, int n, T sigma_max) {
  if (p.relative > 0) return T(p.relative) * sigma_max;
  return std::sqrt(T(3 * n)) * T(std::max(p.noise, 0.0)) + T(kResolution) * sigma_max;
}

// Double round-off of the corners x (n x 3, row by row): half an ulp of the largest coordinate.
double roundoff_noise(const double* x, int n) {
  double m = 0;
  for (int k = 0; k < 3 * n; ++k) m = std::max(m, std::abs(x[k]));
  return 0x1p-53 * m;
}

// Pseudo-inverse solve of a symmetric positive semi-definite 3x3 system.
template <class T>
Eigen::Matrix<T, 3, 1> psd_solve(const Eigen::Matrix<T, 3, 3>& A, const Eigen::Matrix<T, 3, 1>& b) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<T, 3, 3>> es(A);
  const Eigen::Matrix<T, 3, 1> lambda = es.eigenvalues();
  const T cut = T(kRankTolerance) * lambda.cwiseAbs().maxCoeff();
  Eigen::Matrix<T, 3, 1> x = Eigen::Matrix<T, 3, 1>::Zero();
  for (int i = 0; i < 3; ++i)
    if (lambda[i] > cut && lambda[i] > 0)
      x += es.eigenvectors().col(i) * (es.eigenvectors().col(i).dot(b) / lambda[i]);
  return x;
}

// Least-norm w with sum w = 1 and Y^T w = y, for the n centred corners Y (row by row, 3n
// entries; overwritten), with the rank decided by `planarity` (planarity_cut()); w has n entries.
// Because Y is centred, the row of ones is orthogonal to the columns of Y, so
// w = 1/n + pinv(Y^T) y. Y = Q R by Householder reflections (backward stable: the normal
// equations Y^T Y would square the condition number of nearly planar polygons); singular values
// of R (those of Y) at or below the cut count as zero. When the bound sigma_min >= 1 / |R^-1|_F
// clears kDoubleCertified |R|_F (>= sigma_max), R is full rank and w = 1/n + Q R^-T y without
// an SVD; otherwise the SVD of the 3x3 R decides the rank. Returns false (w not written) when
// `certify` is set and the polygon is full rank with sigma_min < kDoubleCertified sigma_max:
// then the caller recomputes in higher precision.
// N > 0: the corner count fixed at compile time (loops unrolled); N = 0: n_dyn corners.
template <int N, class T>
inline bool least_norm_affine_weights(T* Y, int n_dyn, const T y[3], T* w, const PlanarityCut& planarity,
                                      bool certify) {
  const int n = N > 0 ? N : n_dyn;
  T R[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, beta[3] = {0, 0, 0};
  const int m = std::min(n, 3);
  for (int j = 0; j < m; ++j) {
    T norm2 = 0;
    for (int k = j; k < n; ++k) norm2 += Y[3 * k + j] * Y[3 * k + j];
    const T x0 = Y[3 * j + j], alpha = x0 > 0 ? -std::sqrt(norm2) : std::sqrt(norm2);
    const T v0 = x0 - alpha, vv = norm2 - x0 * x0 + v0 * v0;
    Y[3 * j + j] = v0;  // v = (x0 - alpha, x1, ...) stored in column j, rows j..n-1
    beta[j] = vv > 0 ? T(2) / vv : T(0);
    R[j][j] = vv > 0 ? alpha : x0;
    for (int c = j + 1; c < 3; ++c) {
      T dot = 0;
      for (int k = j; k < n; ++k) dot += Y[3 * k + j] * Y[3 * k + c];
      dot *= beta[j];
      for (int k = j; k < n; ++k) Y[3 * k + c] -= dot * Y[3 * k + j];
      R[j][c] = Y[3 * j + c];
    }
  }
  // z = pinv(R^T) y (3 entries, the rest of Q^T's range is zero).
  T z[3] = {0, 0, 0};
  const T Rf = std::sqrt(R[0][0] * R[0][0] + R[0][1] * R[0][1] + R[0][2] * R[0][2] + R[1][1] * R[1][1] +
                         R[1][2] * R[1][2] + R[2][2] * R[2][2]);
  bool full_rank = false;
  if (m == 3 && R[0][0] != 0 && R[1][1] != 0 && R[2][2] != 0) {
    // Inverse of the upper-triangular R.
    const T i00 = 1 / R[0][0], i11 = 1 / R[1][1], i22 = 1 / R[2][2];
    const T i01 = -R[0][1] * i00 * i11, i12 = -R[1][2] * i11 * i22;
    const T i02 = -(R[0][1] * i12 + R[0][2] * i22) * i00;
    const T Rinv_f = std::sqrt(i00 * i00 + i11 * i11 + i22 * i22 + i01 * i01 + i12 * i12 + i02 * i02);
    if (Rf * Rinv_f * T(kDoubleCertified) < 1 && planarity_cut<T>(planarity, n, Rf) * Rinv_f < 1) {
      full_rank = true;
      // R^T z = y: forward substitution with the lower-triangular R^T.
      z[0] = y[0] / R[0][0];
      z[1] = (y[1] - R[0][1] * z[0]) / R[1][1];
      z[2] = (y[2] - R[0][2] * z[0] - R[1][2] * z[1]) / R[2][2];
    }
  }
  if (!full_rank && Rf > 0) {
    // R = U S V^T: pinv(R^T) y = U S^+ V^T y.
    using M3 = Eigen::Matrix<T, 3, 3>;
    M3 Rm;
    Rm << R[0][0], R[0][1], R[0][2], 0, R[1][1], R[1][2], 0, 0, R[2][2];
    Eigen::JacobiSVD<M3> svd(Rm, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Matrix<T, 3, 1> sigma = svd.singularValues();
    const T cut = planarity_cut<T>(planarity, n, sigma[0]);
    if (certify && sigma[2] > cut && sigma[2] < T(kDoubleCertified) * sigma[0]) return false;
    Eigen::Matrix<T, 3, 1> t = svd.matrixV().transpose() * Eigen::Matrix<T, 3, 1>(y[0], y[1], y[2]);
    for (int i = 0; i < 3; ++i) t[i] = sigma[i] > cut ? t[i] / sigma[i] : T(0);
    const Eigen::Matrix<T, 3, 1> u = svd.matrixU() * t;
    for (int i = 0; i < m; ++i) z[i] = u[i];
  }
  // w = 1/n + Q (z, 0, ..., 0): apply the reflections in reverse order.
  for (int k = 0; k < n; ++k) w[k] = k < m ? z[k] : T(0);
  for (int j = m - 1; j >= 0; --j) {
    T dot = 0;
    for (int k = j; k < n; ++k) dot += Y[3 * k + j] * w[k];
    dot *= beta[j];
    for (int k = j; k < n; ++k) w[k] -= dot * Y[3 * k + j];
  }
  for (int k = 0; k < n; ++k) w[k] += T(1) / T(n);
  return true;
}

// The plane of a polygon that is planar to round-off, for least_norm_affine_weights() without the
// QR and the SVD: its unit normal v (Newell's vector area) leaves |Y v| <= 64 eps |Y|_F, which
// bounds sigma_min and is below the cut, so the SVD would drop exactly that direction; the weights
// are then w = 1/n + Y2 (Y2^T Y2)^-1 (p, q)^T y with Y2 = Y (p, q) the corners in an orthonormal
// basis (p, q) of the plane. Taken only when that 2x2 Gram matrix G is well conditioned
// (det >= 1e-4 trace^2: its round-off ~eps cond^2 stays near the SVD's) and its smaller
// eigenvalue is certainly above the cut (sigma_2 kept, as the SVD would).
struct PlaneFrame {
  double p[3], q[3];
  double g00, g01, g11, det, inv_det;  // G
  double a00, a01, a11, b0, b1;  // the in-plane squared-area system (planar_squared_area_point())
};

// Corner k of Y in the frame's plane coordinates (Y_k . p, Y_k . q).
inline void in_plane(const PlaneFrame& fr, const double* a, double& s, double& t) {
  s = a[0] * fr.p[0] + a[1] * fr.p[1] + a[2] * fr.p[2];
  t = a[0] * fr.q[0] + a[1] * fr.q[1] + a[2] * fr.q[2];
}

// The frame of the n centred corners Y when the polygon qualifies (above); false otherwise.
template <int N>
inline bool plane_frame(const double* Y, int n_dyn, const PlanarityCut& planarity, PlaneFrame& fr) {
  const int n = N > 0 ? N : n_dyn;
  if (n < 3) return false;
  double v0 = 0, v1 = 0, v2 = 0, F2 = 0;
  for (int k = 0; k < n; ++k) {
    const double *a = Y + 3 * k, *b = Y + 3 * (k + 1 == n ? 0 : k + 1);
    v0 += a[1] * b[2] - a[2] * b[1], v1 += a[2] * b[0] - a[0] * b[2], v2 += a[0] * b[1] - a[1] * b[0];
    F2 += a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  }
  const double vn2 = v0 * v0 + v1 * v1 + v2 * v2, F = std::sqrt(F2);
  const double eps = std::numeric_limits<double>::epsilon();
  if (!(vn2 > 0)) return false;
  // p = e x v normalized, with e the z axis unless |v_z| >= 0.9 |v|, then the x axis (so
  // |e x v| >= sqrt(0.19) |v|), and q = v x p / |v|. p needs no normalized v, so its square root
  // and the one of |v| run side by side (the frame is on the weights' critical path).
  double* p = fr.p;
  if (v2 * v2 < 0.81 * vn2) {
    const double s = 1 / std::sqrt(v0 * v0 + v1 * v1);
    p[0] = -v1 * s, p[1] = v0 * s, p[2] = 0;
  } else {
    const double s = 1 / std::sqrt(v1 * v1 + v2 * v2);
    p[0] = 0, p[1] = -v2 * s, p[2] = v1 * s;
  }
  const double inv = 1 / std::sqrt(vn2);
  v0 *= inv, v1 *= inv, v2 *= inv;
  fr.q[0] = v1 * p[2] - v2 * p[1], fr.q[1] = v2 * p[0] - v0 * p[2], fr.q[2] = v0 * p[1] - v1 * p[0];
  double h2 = 0;
  for (int k = 0; k < n; ++k) {
    const double h = Y[3 * k] * v0 + Y[3 * k + 1] * v1 + Y[3 * k + 2] * v2;
    h2 += h * h;
  }
  // sigma_min <= |Y v|; sigma_max >= |Y|_F / sqrt(3), so the cut is at least planarity_cut(F / sqrt 3).
  const double h = std::sqrt(h2);
  if (!(h <= 64 * eps * F) || !(h + 16 * eps * F <= planarity_cut<double>(planarity, n, F / std::sqrt(3.0))))
    return false;
  // G and, from the edges e_k in plane coordinates turned by 90 degrees (e_k' = (-e_t, e_s)), the
  // in-plane squared-area system A = sum_k e_k' e_k'^T, b = sum_k e_k' (e_k' . y_k).
  fr.g00 = fr.g01 = fr.g11 = fr.a00 = fr.a01 = fr.a11 = fr.b0 = fr.b1 = 0;
  double s0, t0;
  in_plane(fr, Y + 3 * (n - 1), s0, t0);
  for (int k = 0; k < n; ++k) {
    double s1, t1;
    in_plane(fr, Y + 3 * k, s1, t1);
    fr.g00 += s1 * s1, fr.g01 += s1 * t1, fr.g11 += t1 * t1;
    const double ns = t0 - t1, nt = s1 - s0, ny = ns * s0 + nt * t0;
    fr.a00 += ns * ns, fr.a01 += ns * nt, fr.a11 += nt * nt;
    fr.b0 += ns * ny, fr.b1 += nt * ny;
    s0 = s1, t0 = t1;
  }
  const double tr = fr.g00 + fr.g11;
  fr.det = fr.g00 * fr.g11 - fr.g01 * fr.g01;
  fr.inv_det = 1 / fr.det;
  // lambda_min(G) >= det / trace must clear (2 cut)^2, the cut taken at its largest (sigma_max <= |Y|_F).
  const double cut = planarity_cut<double>(planarity, n, F);
  return fr.det >= 1e-4 * tr * tr && fr.det > 4 * cut * cut * tr;
}

// The squared-area minimizer (eq. 38) in the plane from the frame's system (the in-plane block of
// squared_area_system(), whose normal direction decouples for a planar polygon). False (nothing
// written) when a pivot of its LDL^T is at most 1e-3 of the trace (nearly parallel edges); the
// solution itself by the 2 x 2 inverse (one division instead of three in a row).
inline bool planar_squared_area_point(const PlaneFrame& fr, double& ys, double& yt) {
  const double tau = 1e-3 * (fr.a00 + fr.a11);
  const double det = fr.a00 * fr.a11 - fr.a01 * fr.a01;  // a00 times the second pivot
  if (!(fr.a00 > tau) || !(det > tau * fr.a00)) return false;
  const double inv = 1 / det;
  ys = (fr.a11 * fr.b0 - fr.a01 * fr.b1) * inv;
  yt = (fr.a00 * fr.b1 - fr.a01 * fr.b0) * inv;
  return true;
}

// w_k = 1/n + Y_k . (c0 p + c1 q) with (c0, c1) = G^-1 (ys, yt): the least-norm affine weights of
// the in-plane point (ys, yt).
inline void planar_weights(const double* Y, int n, const PlaneFrame& fr, double ys, double yt, double* w) {
  const double c0 = (fr.g11 * ys - fr.g01 * yt) * fr.inv_det, c1 = (fr.g00 * yt - fr.g01 * ys) * fr.inv_det;
  const double z0 = c0 * fr.p[0] + c1 * fr.q[0], z1 = c0 * fr.p[1] + c1 * fr.q[1], z2 = c0 * fr.p[2] + c1 * fr.q[2];
  for (int k = 0; k < n; ++k) w[k] = Y[3 * k] * z0 + Y[3 * k + 1] * z1 + Y[3 * k + 2] * z2 + 1.0 / double(n);
}

// Corners row by row (x[3k..3k+2]), the layout of the pointer routines.
using RowCorners = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

Eigen::VectorXd least_norm_affine_weights(const PolygonPositions& Y, const Eigen::Vector3d& y,
                                          const PlanarityCut& planarity) {
  RowCorners Yr = Y;
  Eigen::VectorXd w(Y.rows());
  least_norm_affine_weights<0, double>(Yr.data(), int(Y.rows()), y.data(), w.data(), planarity, false);
  return w;
}

// The planarity decision for the corners X (n x 3): double round-off when no noise is given.
PlanarityCut resolved(const PlanarityCut& p, const PolygonPositions& X) {
  if (p.relative > 0 || p.noise >= 0) return p;
  const RowCorners x = X;
  return {roundoff_noise(x.data(), int(X.rows())), 0.0};
}

// Centred corners, two passes (see squared_area_weights_n: the least-norm weights need sum Y = 0
// to ~eps |Y|, not ~eps |X|).
PolygonPositions centred(const PolygonPositions& X) {
  const PolygonPositions Y = X.rowwise() - X.colwise().mean();
  return Y.rowwise() - Y.colwise().mean();
}

// The normal equations A y = b of the squared fan area E(y) = 1/2 sum_k |e_k x (y - y_k)|^2 of the
// n corners Y (row by row; eq. 38): A = sum_k (|e_k|^2 I - e_k e_k^T), b = sum_k (|e_k|^2 I - e_k e_k^T) y_k.
template <int N = 0, class T = double>
inline std::pair<Eigen::Matrix<T, 3, 3>, Eigen::Matrix<T, 3, 1>> squared_area_system(const T* Y, int n_dyn) {
  const int n = N > 0 ? N : n_dyn;
  T a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0, b0 = 0, b1 = 0, b2 = 0;
  for (int k = 0; k < n; ++k) {
    const T *p = Y + 3 * k, *q = Y + 3 * (k + 1 == n ? 0 : k + 1);
    const T e0 = q[0] - p[0], e1 = q[1] - p[1], e2 = q[2] - p[2];
    const T s0 = e0 * e0, s1 = e1 * e1, s2 = e2 * e2, ee = s0 + s1 + s2, ep = e0 * p[0] + e1 * p[1] + e2 * p[2];
    a00 += s1 + s2, a11 += s0 + s2, a22 += s0 + s1;  // |e|^2 - e_d^2
    a01 -= e0 * e1, a02 -= e0 * e2, a12 -= e1 * e2;
    b0 += ee * p[0] - e0 * ep, b1 += ee * p[1] - e1 * ep, b2 += ee * p[2] - e2 * ep;
  }
  Eigen::Matrix<T, 3, 3> A;
  A << a00, a01, a02, a01, a11, a12, a02, a12, a22;
  return {A, Eigen::Matrix<T, 3, 1>(b0, b1, b2)};
}

// Squared diameter proxy of a polygon: the largest squared distance of a corner from the centroid.
double scale2(const PolygonPositions& Y) { return Y.rowwise().squaredNorm().maxCoeff(); }


}  // namespace

PlanarityCut planarity_cut(double tolerance, double noise, const double* x, int n) {
  if (tolerance > 0) return {0.0, tolerance};
  return {std::max(noise, roundoff_noise(x, n)), 0.0};
}

VirtualVertexRule parse_virtual_vertex_rule(const std::string& name) {
  if (name == "squared-area" || name == "affine") return VirtualVertexRule::SquaredArea;
  if (name == "centroid") return VirtualVertexRule::Centroid;
  if (name == "abs-area") return VirtualVertexRule::AbsArea;
  if (name == "convex") return VirtualVertexRule::Convex;
  if (name == "trace-min") return VirtualVertexRule::TraceMin;
  throw std::invalid_argument("unknown virtual-vertex rule '" + name +
                              "' (squared-area, centroid, abs-area, convex, trace-min)");
}

std::string to_string(VirtualVertexRule rule) {
  switch (rule) {
    case VirtualVertexRule::SquaredArea:
      return "squared-area";
    case VirtualVertexRule::Centroid:
      return "centroid";
    case VirtualVertexRule::AbsArea:
      return "abs-area";
    case VirtualVertexRule::Convex:
      return "convex";
    case VirtualVertexRule::TraceMin:
      return "trace-min";
  }
  return "unknown";
}

Eigen::VectorXd centroid_weights(int n) { return Eigen::VectorXd::Constant(n, 1.0 / n); }

Eigen::VectorXd squared_area_weights(const PolygonPositions& X, const PlanarityCut& planarity) {
  const RowCorners x = X;
  RowCorners work(X.rows(), 3);
  Eigen::VectorXd w(X.rows());
  squared_area_weights(x.data(), int(X.rows()), w.data(), work.data(), planarity);
  return w;
}

namespace {

// The minimizer y of the squared fan area of the n centred corners Y: A y = b (eq. 38).
template <int N, class T>
void squared_area_point(const T* Y, int n, T* y) {
  // A is positive semi-definite and singular only for degenerate polygons (all edges parallel).
  // LDL^T when every pivot exceeds 1e-3 of the trace: then lambda_min >= 1e-9 lambda_max (the
  // pivots' product is det A), above the eigenvalue cut of psd_solve(), which handles the rest.
  const auto [A, b] = squared_area_system<N, T>(Y, n);
  const T tau = T(1e-3) * A.trace();
  bool solved = false;
  if (A(0, 0) > tau) {
    const T l10 = A(1, 0) / A(0, 0), l20 = A(2, 0) / A(0, 0);
    const T d1 = A(1, 1) - l10 * A(1, 0), a21 = A(2, 1) - l10 * A(2, 0);
    if (d1 > tau) {
      const T l21 = a21 / d1, d2 = A(2, 2) - l20 * A(2, 0) - l21 * a21;
      if (d2 > tau) {
        const T f0 = b[0], f1 = b[1] - l10 * f0, f2 = b[2] - l20 * f0 - l21 * f1;
        y[2] = f2 / d2;
        y[1] = f1 / d1 - l21 * y[2];
        y[0] = f0 / A(0, 0) - l10 * y[1] - l20 * y[2];
        solved = true;
      }
    }
  }
  if (!solved) {
    const Eigen::Matrix<T, 3, 1> ys = psd_solve<T>(A, b);
    for (int d = 0; d < 3; ++d) y[d] = ys[d];
  }
}

// The weights of the n corners x in arithmetic T, Y and w scratch of 3n and n entries of T.
// With `certify`, false when the polygon is too flat for T (least_norm_affine_weights()).
template <int N, class T>
bool squared_area_weights_t(const double* x, int n_dyn, T* Y, T* w, const PlanarityCut& planarity,
                            bool certify) {
  const int n = N > 0 ? N : n_dyn;
  // Centred corners Y (so that nothing depends on where the polygon sits), in two passes: far
  // from the origin the rounded mean c leaves a residual mean of ~eps |c| in Y, which the
  // least-norm weights below (they assume sum_k Y_k = 0) would amplify by the inverse of the
  // polygon's out-of-plane extent; the second pass removes it down to ~eps |Y|.
  for (int pass = 0; pass < 2; ++pass) {
    T c[3] = {0, 0, 0};
    for (int k = 0; k < n; ++k)
      for (int d = 0; d < 3; ++d) c[d] += pass == 0 ? T(x[3 * k + d]) : Y[3 * k + d];
    for (int d = 0; d < 3; ++d) c[d] /= T(n);
    for (int k = 0; k < n; ++k)
      for (int d = 0; d < 3; ++d) Y[3 * k + d] = (pass == 0 ? T(x[3 * k + d]) : Y[3 * k + d]) - c[d];
  }
  // A polygon planar to round-off: the minimizer and the weights in its plane (plane_frame()).
  if constexpr (std::is_same_v<T, double>) {
    PlaneFrame frame;
    if (certify && plane_frame<N>(Y, n, planarity, frame)) {
      double ys, yt;
      if (!planar_squared_area_point(frame, ys, yt)) {
        double y[3];
        squared_area_point<N, T>(Y, n, y);
        in_plane(frame, y, ys, yt);
      }
      planar_weights(Y, n, frame, ys, yt, w);
      return true;
    }
  }
  T y[3];
  squared_area_point<N, T>(Y, n, y);
  return least_norm_affine_weights<N, T>(Y, n, y, w, planarity, certify);
}

// Double first; a polygon too flat for double's round-off again in long double.
template <int N>
void squared_area_weights_n(const double* x, int n_dyn, double* w, double* work, PlanarityCut planarity) {
  const int n = N > 0 ? N : n_dyn;
  if (planarity.relative <= 0 && planarity.noise < 0) planarity.noise = roundoff_noise(x, n);
  if (squared_area_weights_t<N, double>(x, n, work, w, planarity, true)) return;
  std::vector<long double> buffer(4 * size_t(n));
  long double* wl = buffer.data() + 3 * size_t(n);
  squared_area_weights_t<N, long double>(x, n, buffer.data(), wl, planarity, false);
  for (int k = 0; k < n; ++k) w[k] = double(wl[k]);
}

}  // namespace

void squared_area_weights(const double* x, int n, double* w, double* work, const PlanarityCut& planarity) {
  switch (n) {
    case 3: squared_area_weights_n<3>(x, n, w, work, planarity); break;
    case 4: squared_area_weights_n<4>(x, n, w, work, planarity); break;
    case 5: squared_area_weights_n<5>(x, n, w, work, planarity); break;
    case 6: squared_area_weights_n<6>(x, n, w, work, planarity); break;
    default: squared_area_weights_n<0>(x, n, w, work, planarity); break;
  }
}

Eigen::VectorXd virtual_vertex_weights(const PolygonPositions& X, VirtualVertexRule rule,
                                       const PlanarityCut& planarity) {
  switch (rule) {
    case VirtualVertexRule::SquaredArea:
      return squared_area_weights(X, planarity);
    case VirtualVertexRule::Centroid:
      return centroid_weights(int(X.rows()));
    case VirtualVertexRule::AbsArea:
      return abs_area_weights(X, planarity);
    case VirtualVertexRule::Convex:
      return convex_weights(X);
    case VirtualVertexRule::TraceMin:
      return trace_min_weights(X, planarity);
  }
  throw std::invalid_argument("unknown virtual-vertex rule");
}

}  // namespace polydec

namespace polydec {

// ---- absolute-area minimizer -------------------------------------------------------------

Eigen::VectorXd abs_area_weights(const PolygonPositions& X, const PlanarityCut& planarity) {
  const int n = int(X.rows());
  const PolygonPositions Y = centred(X);
  // Twice the area vector of fan triangle i: c_i(x) = (y_i - x) x e_i = y_i x e_i + e_i x x.
  std::vector<Eigen::Vector3d> e(n), a(n);
  for (int i = 0; i < n; ++i) {
    e[i] = (Y.row((i + 1) % n) - Y.row(i)).transpose();
    a[i] = Y.row(i).transpose().cross(e[i]);
  }
  auto objective = [&](const Eigen::Vector3d& x) {
    double f = 0;
    for (int i = 0; i < n; ++i) f += (a[i] + e[i].cross(x)).norm();
    return f;
  };
  // IRLS on the smoothed objective sum_i sqrt(|c_i|^2 + eps^2) (each step minimizes a quadratic
  // majorizer, so the smoothed objective never increases), with eps decreasing from 1e-2 to 1e-7
  // of the polygon's squared size: a small eps from the start would pin the point to the line of
  // an edge whose fan triangle happens to be degenerate at the start. The best point by the true
  // objective is kept; the centroid is only left for a gain above 1e-12 of the objective.
  const double s2 = scale2(Y);
  Eigen::Vector3d x = Eigen::Vector3d::Zero(), best = x;  // the centroid
  double f_best = objective(x);
  for (double eps = 1e-2 * s2; eps >= 1e-7 * s2 * (1 - 1e-9); eps *= 0.1) {
    auto smoothed = [&](const Eigen::Vector3d& y) {
      double f = 0;
      for (int i = 0; i < n; ++i) f += std::sqrt((a[i] + e[i].cross(y)).squaredNorm() + eps * eps);
      return f;
    };
    double fs = smoothed(x);
    for (int it = 0; it < 100; ++it) {
      Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
      Eigen::Vector3d b = Eigen::Vector3d::Zero();
      for (int i = 0; i < n; ++i) {
        const double omega = 1.0 / std::sqrt((a[i] + e[i].cross(x)).squaredNorm() + eps * eps);
        A += omega * (e[i].squaredNorm() * Eigen::Matrix3d::Identity() - e[i] * e[i].transpose());
        b += omega * e[i].cross(a[i]);  // -[e]x^T a = [e]x a = e x a
      }
      const Eigen::Vector3d x_new = psd_solve(A, b);
      const double fs_new = smoothed(x_new);
      if (!(fs_new < fs)) break;
      const bool done = fs_new > fs - 1e-13 * fs;
      x = x_new;
      fs = fs_new;
      const double f = objective(x);
      if (f < f_best - 1e-12 * f_best) {
        f_best = f;
        best = x;
      }
      if (done) break;
    }
  }
  return least_norm_affine_weights(Y, best, resolved(planarity, X));
}

// ---- convex squared-area weights -----------------------------------------------------------

Eigen::VectorXd convex_weights(const PolygonPositions& X) {
  const int n = int(X.rows());
  const PolygonPositions Y = centred(X);
  // E(w) = 1/2 sum_k |e_k x (Y^T w - y_k)|^2 = 1/2 |C w - r|^2 + const with A = L L^T, A y* = b
  // (A, b as in squared_area_weights; b lies in the range of A), C = L^T Y^T (3 x n), r = L^T y*.
  const RowCorners Yr = Y;
  const auto [A, b] = squared_area_system(Yr.data(), n);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(A);
  const Eigen::Matrix3d Lt = es.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() * es.eigenvectors().transpose();
  const Eigen::MatrixXd C = Lt * Y.transpose();
  const Eigen::Vector3d r = Lt * psd_solve(A, b);
  const double mu = 1e-9 * C.colwise().squaredNorm().mean();  // Tikhonov: 1e-9 mean(diag H), H = C^T C
  const double tol = 1e-12 * C.norm() * (C.norm() + r.norm());
  auto gradient = [&](const Eigen::VectorXd& w) -> Eigen::VectorXd { return C.transpose() * (C * w - r) + mu * w; };

  Eigen::VectorXd w = Eigen::VectorXd::Constant(n, 1.0 / n);
  std::vector<char> free_(n, 1);
  for (int it = 0; it < 10 * n + 10; ++it) {
    // Minimizer on the free set F with sum w_F = 1: w_F = 1/m + Q z (Q an orthonormal basis of
    // the sum-zero vectors), z the Tikhonov least-squares solution of C_F Q z = r - C_F 1/m. Solved
    // by the SVD of the 3 x (m-1) factor, not the normal equations: their condition ~1/1e-9 let
    // the weights move by 1e-7 under a rescaling of the polygon.
    std::vector<int> F;
    for (int i = 0; i < n; ++i)
      if (free_[i]) F.push_back(i);
    const int m = int(F.size());
    Eigen::MatrixXd CF(3, m);
    for (int p = 0; p < m; ++p) CF.col(p) = C.col(F[p]);
    Eigen::VectorXd wF = Eigen::VectorXd::Constant(m, 1.0 / m);
    if (m > 1) {
      const Eigen::MatrixXd Q = Eigen::MatrixXd(Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::Ones(m, 1))
                                                    .householderQ())
                                    .rightCols(m - 1);
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(CF * Q, Eigen::ComputeThinU | Eigen::ComputeThinV);
      Eigen::VectorXd c = svd.matrixU().transpose() * (r - CF * wF);
      for (int i = 0; i < c.size(); ++i) {
        const double sigma = svd.singularValues()[i];
        c[i] = sigma > 0 ? c[i] * sigma / (sigma * sigma + mu) : 0.0;
      }
      wF += Q * (svd.matrixV() * c);
    }
    Eigen::VectorXd target = Eigen::VectorXd::Zero(n);
    for (int p = 0; p < m; ++p) target[F[p]] = wF[p];
    // Blocking constraint: the first free weight that the step w -> target drives below zero.
    double alpha = 1.0;
    int block = -1;
    for (int i : F)
      if (target[i] < 0 && w[i] - target[i] > 0) {
        const double t = w[i] / (w[i] - target[i]);
        if (t < alpha) {
          alpha = t;
          block = i;
        }
      }
    w += alpha * (target - w);
    if (block >= 0) {
      w[block] = 0.0;
      free_[block] = 0;
      continue;
    }
    // Optimal on this face of the simplex (gradient nu 1 on F); free the fixed weight with the
    // most negative multiplier.
    const Eigen::VectorXd grad = gradient(w);
    double nu = 0;
    for (int i : F) nu += grad[i] / m;
    int enter = -1;
    double most = -tol;
    for (int i = 0; i < n; ++i)
      if (!free_[i] && grad[i] - nu < most) {
        most = grad[i] - nu;
        enter = i;
      }
    if (enter < 0) break;
    free_[enter] = 1;
  }
  w = w.cwiseMax(0.0);
  return w / w.sum();
}

// ---- trace minimizer (Bunge et al. 2024) ---------------------------------------------------

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Fan-trace energy sum_i (|a|^2 + |b|^2 + |e|^2) / (4 A_i) of the 2D polygon P around p, with
// gradient and Hessian; +infinity when a fan triangle is not positively oriented (relative test).
double fan_trace(const Eigen::MatrixX2d& P, const Eigen::Vector2d& p, Eigen::Vector2d* grad,
                 Eigen::Matrix2d* hess) {
  const int n = int(P.rows());
  double E = 0;
  if (grad) grad->setZero();
  if (hess) hess->setZero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d a = P.row(i).transpose() - p, b = P.row((i + 1) % n).transpose() - p, e = b - a;
    const double A = 0.5 * cross2(a, b);
    const double longest2 = std::max({a.squaredNorm(), b.squaredNorm(), e.squaredNorm()});
    if (!(2 * A > 1e-10 * longest2)) return std::numeric_limits<double>::infinity();
    const double N = a.squaredNorm() + b.squaredNorm() + e.squaredNorm();
    E += N / (4 * A);
    if (grad || hess) {
      const Eigen::Vector2d dN = -2.0 * (a + b), dA = 0.5 * Eigen::Vector2d(-e.y(), e.x());
      if (grad) *grad += dN / (4 * A) - N * dA / (4 * A * A);
      if (hess)
        *hess += Eigen::Matrix2d::Identity() / A - (dN * dA.transpose() + dA * dN.transpose()) / (4 * A * A) +
                 N * dA * dA.transpose() / (2 * A * A * A);
    }
  }
  return E;
}

// Kernel of a counter-clockwise 2D polygon (intersection of the left half-planes of its edges),
// by clipping its bounding box; empty when the polygon is not star-shaped.
std::vector<Eigen::Vector2d> polygon_kernel(const Eigen::MatrixX2d& P) {
  const int n = int(P.rows());
  const Eigen::Vector2d lo = P.colwise().minCoeff().transpose(), hi = P.colwise().maxCoeff().transpose();
  std::vector<Eigen::Vector2d> K = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  for (int i = 0; i < n && !K.empty(); ++i) {
    const Eigen::Vector2d p = P.row(i).transpose(), e = P.row((i + 1) % n).transpose() - p;
    auto side = [&](const Eigen::Vector2d& q) { return cross2(e, q - p); };
    std::vector<Eigen::Vector2d> out;
    for (size_t k = 0; k < K.size(); ++k) {
      const Eigen::Vector2d &u = K[k], &v = K[(k + 1) % K.size()];
      const double su = side(u), sv = side(v);
      if (su >= 0) out.push_back(u);
      if ((su >= 0) != (sv >= 0)) out.push_back(u + (v - u) * (su / (su - sv)));
    }
    K = std::move(out);
  }
  return K;
}

// Area centroid and area of a convex 2D polygon.
std::pair<Eigen::Vector2d, double> area_centroid(const std::vector<Eigen::Vector2d>& K) {
  double A = 0;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (size_t k = 0; k < K.size(); ++k) {
    const Eigen::Vector2d &u = K[k], &v = K[(k + 1) % K.size()];
    const double t = cross2(u, v);
    A += t;
    c += t * (u + v);
  }
  return {A != 0 ? Eigen::Vector2d(c / (3 * A)) : Eigen::Vector2d::Zero(), 0.5 * A};
}

}  // namespace

double coarse_stiffness_trace(const PolygonPositions& X, const Eigen::VectorXd& w) {
  const int n = int(X.rows());
  const PolygonPositions Y = centred(X);
  const Eigen::Vector3d xf = Y.transpose() * w;
  // Refined fan stiffness (positive version) in blocks: corner diagonal d, corner-virtual
  // coupling s (off-diagonal, negative), virtual diagonal sigma. trace(P^T K P) with P = [I; w^T]
  // = sum_i d_i + 2 w^T s + sigma |w|^2.
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n), s = Eigen::VectorXd::Zero(n);
  double sigma = 0;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const Eigen::Vector3d p = Y.row(i).transpose(), q = Y.row(j).transpose();
    const double twice_area = (q - p).cross(xf - p).norm();
    if (!(twice_area > 0)) return std::numeric_limits<double>::infinity();
    // half cotangents at p, q, xf
    const double cp = 0.5 * (q - p).dot(xf - p) / twice_area, cq = 0.5 * (p - q).dot(xf - q) / twice_area,
                 cf = 0.5 * (p - xf).dot(q - xf) / twice_area;
    d[i] += cf + cq;  // edges (i,j) opposite xf and (i,f) opposite q
    d[j] += cf + cp;
    s[i] -= cq;
    s[j] -= cp;
    sigma += cp + cq;
  }
  return d.sum() + 2 * w.dot(s) + sigma * w.squaredNorm();
}

Eigen::VectorXd trace_min_weights(const PolygonPositions& X, const PlanarityCut& planarity) {
  const int n = int(X.rows());
  const PolygonPositions Y = centred(X);
  const Eigen::VectorXd w_area = squared_area_weights(X, planarity);
  Eigen::Vector3d N = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) N += Y.row(i).transpose().cross(Y.row((i + 1) % n).transpose());
  if (!(N.norm() > 1e-12 * scale2(Y))) return w_area;  // no plane to work in
  N.normalize();
  const Eigen::Vector3d u = N.unitOrthogonal(), v = N.cross(u);
  Eigen::MatrixX2d P(n, 2);
  P.col(0) = Y * u;
  P.col(1) = Y * v;

  const Eigen::Vector3d x_area = Y.transpose() * w_area;
  Eigen::Vector2d p(x_area.dot(u), x_area.dot(v));
  double E = fan_trace(P, p, nullptr, nullptr);
  if (!std::isfinite(E)) {
    const auto K = polygon_kernel(P);
    if (K.size() < 3) return w_area;
    const auto [c, area] = area_centroid(K);
    if (!(area > 1e-12 * scale2(Y))) return w_area;
    p = c;
    E = fan_trace(P, p, nullptr, nullptr);
    if (!std::isfinite(E)) return w_area;
  }
  // Damped Newton on the convex barrier E (backtracking keeps p in the kernel).
  for (int it = 0; it < 100; ++it) {
    Eigen::Vector2d grad;
    Eigen::Matrix2d hess;
    fan_trace(P, p, &grad, &hess);
    const Eigen::Vector2d step = -hess.ldlt().solve(grad);
    const double decrement = -grad.dot(step);
    if (!(decrement > 1e-14 * E)) break;
    double t = 1.0;
    bool moved = false;
    for (int ls = 0; ls < 60; ++ls, t *= 0.5) {
      const double E_new = fan_trace(P, p + t * step, nullptr, nullptr);
      if (E_new <= E - 0.25 * t * decrement) {
        p += t * step;
        E = E_new;
        moved = true;
        break;
      }
    }
    if (!moved) break;
  }
  // Harmonic weights: the cotangent weight of each spoke (p, x_i) in the fan, normalized.
  Eigen::VectorXd w(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d xm = P.row((i + n - 1) % n).transpose(), xi = P.row(i).transpose(),
                          xp = P.row((i + 1) % n).transpose();
    const Eigen::Vector2d a1 = xi - xm, b1 = p - xm;  // angle at x_{i-1} in (x_{i-1}, x_i, p)
    const Eigen::Vector2d a2 = xi - xp, b2 = p - xp;  // angle at x_{i+1} in (x_i, x_{i+1}, p)
    w[i] = 0.5 * (a1.dot(b1) / std::abs(cross2(a1, b1)) + a2.dot(b2) / std::abs(cross2(a2, b2)));
  }
  w /= w.sum();
  if (!w.allFinite() || coarse_stiffness_trace(X, w) > coarse_stiffness_trace(X, w_area)) return w_area;
  return w;
}

}  // namespace polydec
