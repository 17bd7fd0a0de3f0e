// dec/virtual_vertex.cpp — virtual-vertex weights of a single polygon (paper Appendix A, section
// 4.2 variants, Bunge et al. 2024 trace minimizer).
#include "dec/virtual_vertex.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace polydec {

namespace {

// Relative eigenvalue cut-off for the rank decisions below. Eigenvalues of a 3x3 matrix of
// squared lengths below kRankTolerance times the largest are treated as zero: a polygon whose
// out-of-plane extent is below ~1e-5 of its size counts as planar. The least-norm weights of
// eq. (16) jump between the planar and the non-planar case (the virtual point does not), so the
// decision must not be left to round-off: mesh files store coordinates with 6 to 9 digits, which
// makes planar polygons (e.g. a UV sphere's trapezoids) non-planar at the 1e-6 level.
constexpr double kRankTolerance = 1e-10;

// Pseudo-inverse solve of a symmetric positive semi-definite 3x3 system.
Eigen::Vector3d psd_solve(const Eigen::Matrix3d& A, const Eigen::Vector3d& b) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(A);
  const Eigen::Vector3d lambda = es.eigenvalues();
  const double cut = kRankTolerance * lambda.cwiseAbs().maxCoeff();
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
    if (lambda[i] > cut && lambda[i] > 0)
      x += es.eigenvectors().col(i) * (es.eigenvectors().col(i).dot(b) / lambda[i]);
  return x;
}

// Least-norm w with sum w = 1 and Y^T w = y, for centred positions Y. Because Y is centred, the
// row of ones is orthogonal to the columns of Y, so w = 1/n + pinv(Y^T) y. The pseudo-inverse
// comes from the SVD of Y itself (not of Y^T Y, which would square the condition number of nearly
// planar polygons); singular values below sqrt(kRankTolerance) of the largest count as zero.
Eigen::VectorXd least_norm_affine_weights(const PolygonPositions& Y, const Eigen::Vector3d& y) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(Y), Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::Vector3d sigma = svd.singularValues();
  const double cut = std::sqrt(kRankTolerance) * sigma[0];
  Eigen::Vector3d z = svd.matrixV().transpose() * y;
  for (int i = 0; i < 3; ++i) z[i] = sigma[i] > cut ? z[i] / sigma[i] : 0.0;
  return Eigen::VectorXd::Constant(Y.rows(), 1.0 / double(Y.rows())) + svd.matrixU() * z;
}

PolygonPositions centred(const PolygonPositions& X) { return X.rowwise() - X.colwise().mean(); }

// Squared diameter proxy of a polygon: the largest squared distance of a corner from the centroid.
double scale2(const PolygonPositions& Y) { return Y.rowwise().squaredNorm().maxCoeff(); }


// The allocation-free route below (squared_area_weights on raw corners, used by refine()) solves
// the same two systems through closed forms where they are provably well posed and falls back
// to psd_solve / least_norm_affine_weights otherwise, so both routes make the same rank
// decisions and agree to round-off:
// - LDL^T when the smallest eigenvalue provably exceeds kDirect* times the largest
//   (lambda_min >= 4 det / tr^2 and lambda_max <= tr, so lambda_min / lambda_max >= 4 det / tr^3);
//   the relative difference is then at most ~ machine epsilon / kDirect*;
// - a 2x2 solve in the plane orthogonal to the null direction when the Rayleigh quotient of
//   that direction is below kRankTolerance * tr / 3 <= kRankTolerance * lambda_max, i.e. when
//   the reference route drops it too (planar polygons).
constexpr double kDirectA = 1e-8;  // A = sum_k |e_k|^2 I - e_k e_k^T
constexpr double kDirectC = 1e-6;  // C = Y^T Y squares Y's condition number: stricter

// Symmetric 3x3 matrix (upper triangle).
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
  Eigen::Matrix3d full() const {
    Eigen::Matrix3d M;
    M << a00, a01, a02, a01, a11, a12, a02, a12, a22;
    return M;
  }
  bool direct_solve(const double* b, double* x, double tolerance) const {
    const double tr = a00 + a11 + a22;
    if (!(a00 > 0)) return false;
    const double l10 = a01 / a00, l20 = a02 / a00;
    const double d1 = a11 - l10 * a01;
    if (!(d1 > 0)) return false;
    const double l21 = (a12 - l20 * a01) / d1;
    const double d2 = a22 - l20 * a02 - l21 * l21 * d1;
    if (!(d2 > 0 && 4 * a00 * d1 * d2 > tolerance * tr * tr * tr)) return false;
    const double y0 = b[0], y1 = b[1] - l10 * y0, y2 = b[2] - l20 * y0 - l21 * y1;
    x[2] = y2 / d2;
    x[1] = y1 / d1 - l21 * x[2];
    x[0] = y0 / a00 - l10 * x[1] - l20 * x[2];
    return true;
  }
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
    if (!(det > kDirectC * trB * trB)) return false;
    const double c1 = u1[0] * b[0] + u1[1] * b[1] + u1[2] * b[2], c2 = u2[0] * b[0] + u2[1] * b[1] + u2[2] * b[2];
    const double s1 = (B11 * c1 - B01 * c2) / det, s2 = (B00 * c2 - B01 * c1) / det;
    for (int i = 0; i < 3; ++i) x[i] = s1 * u1[i] + s2 * u2[i];
    return true;
  }
};

// The squared-area weights for N corners (0: n given at run time), loops unrolled for fixed N.
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
  if (!A.direct_solve(b, y, kDirectA) && !A.rank2_solve(b, y)) {
    const Eigen::Vector3d ys = psd_solve(A.full(), Eigen::Vector3d(b[0], b[1], b[2]));
    for (int d = 0; d < 3; ++d) y[d] = ys[d];
  }
  if (C.direct_solve(y, z, kDirectC) || C.rank2_solve(y, z)) {
    for (int k = 0; k < n; ++k) w[k] = 1.0 / n + (Y[3 * k] * z[0] + Y[3 * k + 1] * z[1] + Y[3 * k + 2] * z[2]);
    return;
  }
  const PolygonPositions Ym = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(Y, n, 3);
  const Eigen::VectorXd ws = least_norm_affine_weights(Ym, Eigen::Vector3d(y[0], y[1], y[2]));
  for (int k = 0; k < n; ++k) w[k] = ws[k];
}

}  // namespace

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

Eigen::VectorXd squared_area_weights(const PolygonPositions& X) {
  const int n = int(X.rows());
  const Eigen::RowVector3d c = X.colwise().mean();
  const PolygonPositions Y = X.rowwise() - c;  // centred positions

  // Minimizer over R^3 of E(y) = 1/2 sum_k |e_k x (y - y_k)|^2: A y = b with
  // A = sum_k (|e_k|^2 I - e_k e_k^T), b = sum_k (|e_k|^2 I - e_k e_k^T) y_k.
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d e = (Y.row((k + 1) % n) - Y.row(k)).transpose();
    const Eigen::Matrix3d B = e.squaredNorm() * Eigen::Matrix3d::Identity() - e * e.transpose();
    A += B;
    b += B * Y.row(k).transpose();
  }
  const Eigen::Vector3d y = psd_solve(A, b);

  return least_norm_affine_weights(Y, y);
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
    case VirtualVertexRule::SquaredArea:
      return squared_area_weights(X);
    case VirtualVertexRule::Centroid:
      return centroid_weights(int(X.rows()));
    case VirtualVertexRule::AbsArea:
      return abs_area_weights(X);
    case VirtualVertexRule::Convex:
      return convex_weights(X);
    case VirtualVertexRule::TraceMin:
      return trace_min_weights(X);
  }
  throw std::invalid_argument("unknown virtual-vertex rule");
}

}  // namespace polydec

namespace polydec {

// ---- absolute-area minimizer -------------------------------------------------------------

Eigen::VectorXd abs_area_weights(const PolygonPositions& X) {
  const int n = int(X.rows());
  const PolygonPositions Y = centred(X);
  const double floor = 1e-14 * scale2(Y);
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
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  // the centroid
  double f = objective(x);
  for (int it = 0; it < 200; ++it) {
    // Minimize sum_i omega_i |a_i + [e_i]x x|^2: (sum omega_i B_i) x = -sum omega_i [e_i]x^T a_i with
    // B_i = [e_i]x^T [e_i]x = |e_i|^2 I - e_i e_i^T.
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (int i = 0; i < n; ++i) {
      const double omega = 1.0 / std::max((a[i] + e[i].cross(x)).norm(), floor);
      A += omega * (e[i].squaredNorm() * Eigen::Matrix3d::Identity() - e[i] * e[i].transpose());
      b += omega * e[i].cross(a[i]);  // -[e]x^T a = [e]x a = e x a
    }
    const Eigen::Vector3d x_new = psd_solve(A, b);
    const double f_new = objective(x_new);
    if (!(f_new < f - 1e-12 * f)) break;
    x = x_new;
    f = f_new;
  }
  return least_norm_affine_weights(Y, x);
}

// ---- convex squared-area weights -----------------------------------------------------------

Eigen::VectorXd convex_weights(const PolygonPositions& X) {
  const int n = int(X.rows());
  const PolygonPositions Y = centred(X);
  // E(w) = 1/2 sum_k |e_k x (Y^T w - y_k)|^2 = 1/2 w^T H w + g^T w + const with
  // H = Y A Y^T, g = -Y b (A, b as in squared_area_weights).
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d e = (Y.row((k + 1) % n) - Y.row(k)).transpose();
    const Eigen::Matrix3d B = e.squaredNorm() * Eigen::Matrix3d::Identity() - e * e.transpose();
    A += B;
    b += B * Y.row(k).transpose();
  }
  Eigen::MatrixXd H = Y * A * Y.transpose();
  const Eigen::VectorXd g = -(Y * b);
  const double mu = 1e-9 * std::max(H.diagonal().mean(), std::numeric_limits<double>::min());
  H.diagonal().array() += mu;
  const double tol = 1e-12 * (H.cwiseAbs().maxCoeff() + g.cwiseAbs().maxCoeff());

  Eigen::VectorXd w = Eigen::VectorXd::Constant(n, 1.0 / n);
  std::vector<char> free_(n, 1);
  for (int it = 0; it < 10 * n + 10; ++it) {
    // Equality-constrained minimizer on the free set: H_FF w_F + g_F = nu 1, sum w_F = 1.
    std::vector<int> F;
    for (int i = 0; i < n; ++i)
      if (free_[i]) F.push_back(i);
    const int m = int(F.size());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(m + 1, m + 1);
    Eigen::VectorXd r(m + 1);
    for (int p = 0; p < m; ++p) {
      for (int q = 0; q < m; ++q) K(p, q) = H(F[p], F[q]);
      K(p, m) = K(m, p) = -1.0;
      r[p] = -g[F[p]];
    }
    r[m] = -1.0;
    const Eigen::VectorXd sol = K.fullPivLu().solve(r);
    const double nu = sol[m];
    Eigen::VectorXd target = Eigen::VectorXd::Zero(n);
    for (int p = 0; p < m; ++p) target[F[p]] = sol[p];
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
    // Optimal on this face of the simplex; free the fixed weight with the most negative multiplier.
    const Eigen::VectorXd grad = H * w + g;
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

Eigen::VectorXd trace_min_weights(const PolygonPositions& X) {
  const int n = int(X.rows());
  const PolygonPositions Y = centred(X);
  const Eigen::VectorXd w_area = squared_area_weights(X);
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
