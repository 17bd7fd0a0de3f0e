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

// The normal equations A y = b of the squared fan area E(y) = 1/2 sum_k |e_k x (y - y_k)|^2 of the
// corners Y (eq. 38): A = sum_k (|e_k|^2 I - e_k e_k^T), b = sum_k (|e_k|^2 I - e_k e_k^T) y_k.
std::pair<Eigen::Matrix3d, Eigen::Vector3d> squared_area_system(const PolygonPositions& Y) {
  const int n = int(Y.rows());
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d e = (Y.row((k + 1) % n) - Y.row(k)).transpose();
    const Eigen::Matrix3d B = e.squaredNorm() * Eigen::Matrix3d::Identity() - e * e.transpose();
    A += B;
    b += B * Y.row(k).transpose();
  }
  return {A, b};
}

// Squared diameter proxy of a polygon: the largest squared distance of a corner from the centroid.
double scale2(const PolygonPositions& Y) { return Y.rowwise().squaredNorm().maxCoeff(); }


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
  const Eigen::RowVector3d c = X.colwise().mean();
  const PolygonPositions Y = X.rowwise() - c;  // centred positions

  // Minimizer over R^3 of the squared fan area: A y = b.
  const auto [A, b] = squared_area_system(Y);
  const Eigen::Vector3d y = psd_solve(A, b);

  return least_norm_affine_weights(Y, y);
}

void squared_area_weights(const double* x, int n, double* w, double* /*work*/) {
  // The same computation as the Eigen route above, so that refine() and squared_area_weights(X)
  // agree bit for bit. (An unrolled closed-form route was faster but lost accuracy far from the
  // origin: M changed by 2.5e-9 under a translation by 1e3 on noisy-sphere.off.)
  PolygonPositions X(n, 3);
  for (int k = 0; k < n; ++k) X.row(k) << x[3 * k], x[3 * k + 1], x[3 * k + 2];
  const Eigen::VectorXd wv = squared_area_weights(X);
  for (int k = 0; k < n; ++k) w[k] = wv[k];
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
  return least_norm_affine_weights(Y, best);
}

// ---- convex squared-area weights -----------------------------------------------------------

Eigen::VectorXd convex_weights(const PolygonPositions& X) {
  const int n = int(X.rows());
  const PolygonPositions Y = centred(X);
  // E(w) = 1/2 sum_k |e_k x (Y^T w - y_k)|^2 = 1/2 |C w - r|^2 + const with A = L L^T, A y* = b
  // (A, b as in squared_area_weights; b lies in the range of A), C = L^T Y^T (3 x n), r = L^T y*.
  const auto [A, b] = squared_area_system(Y);
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
