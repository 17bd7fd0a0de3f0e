// dec/virtual_vertex.cpp — virtual-vertex weights of a single polygon (paper Appendix A).
#include "dec/virtual_vertex.h"

#include <Eigen/Dense>
#include <stdexcept>

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
  // orthogonal to the columns of Y, so w = 1/n + pinv(Y^T) y. The pseudo-inverse comes from the
  // SVD of Y itself (not of Y^T Y, which would square the condition number of nearly planar
  // polygons); singular values below sqrt(kRankTolerance) of the largest count as zero.
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(Y), Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::Vector3d sigma = svd.singularValues();
  const double cut = std::sqrt(kRankTolerance) * sigma[0];
  Eigen::Vector3d z = svd.matrixV().transpose() * y;
  for (int i = 0; i < 3; ++i) z[i] = sigma[i] > cut ? z[i] / sigma[i] : 0.0;
  return Eigen::VectorXd::Constant(n, 1.0 / n) + svd.matrixU() * z;
}

Eigen::VectorXd virtual_vertex_weights(const PolygonPositions& X, VirtualVertexRule rule) {
  switch (rule) {
    case VirtualVertexRule::SquaredArea: return squared_area_weights(X);
    case VirtualVertexRule::Centroid: return centroid_weights(int(X.rows()));
  }
  throw std::invalid_argument("unknown virtual-vertex rule");
}

}  // namespace polydec
