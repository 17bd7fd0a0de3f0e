// dec/virtual_vertex.cpp — virtual-vertex weights of a single polygon (paper Appendix A).
#include "dec/virtual_vertex.h"

#include <Eigen/Dense>
#include <stdexcept>

namespace polydec {

namespace {

// Relative eigenvalue cut-off for the rank decisions below. Eigenvalues of a 3x3 matrix of
// squared lengths below kRankTolerance times the largest are treated as zero: a polygon whose
// out-of-plane extent is below ~1e-7 of its size counts as planar, which matches where a
// complete orthogonal decomposition of eq. (38) makes the same decision.
constexpr double kRankTolerance = 1e-14;

// Pseudo-inverse solve of a symmetric positive semi-definite 3x3 system.
Eigen::Vector3d psd_solve(const Eigen::Matrix3d& A, const Eigen::Vector3d& b) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(A);
  const Eigen::Vector3d lambda = es.eigenvalues();
  const double cut = kRankTolerance * lambda.cwiseAbs().maxCoeff();
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
    if (lambda[i] > cut && lambda[i] > 0) x += es.eigenvectors().col(i) * (es.eigenvectors().col(i).dot(b) / lambda[i]);
  return x;
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

  // Least-norm w with sum w = 1 and Y^T w = y. Because Y is centred, the row of ones is
  // orthogonal to the columns of Y, so w = 1/n + Y (Y^T Y)^+ y.
  const Eigen::Matrix3d C = Y.transpose() * Y;
  return Eigen::VectorXd::Constant(n, 1.0 / n) + Y * psd_solve(C, y);
}

Eigen::VectorXd virtual_vertex_weights(const PolygonPositions& X, VirtualVertexRule rule) {
  switch (rule) {
    case VirtualVertexRule::SquaredArea: return squared_area_weights(X);
    case VirtualVertexRule::Centroid: return centroid_weights(int(X.rows()));
  }
  throw std::invalid_argument("unknown virtual-vertex rule");
}

}  // namespace polydec
