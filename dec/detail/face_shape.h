// dec/detail/face_shape.h — two small facts about one polygon that validation (dec/mesh/mesh_checks.h) and
// repair (dec/mesh/repair.h) both decide: its vertex cycle up to rotation and direction, and the
// singular values of its centred corners (zero area and thinness, relative to its own size).
#pragma once

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <span>
#include <vector>

namespace polydec {

// The face's vertex cycle rotated to start at its smallest index, read in the direction whose
// sequence is lexicographically smaller, written to out[0 .. face.size()); returns whether the
// backward direction was taken. Two faces with the same cycle in either direction get the same key.
inline bool canonical_cycle(std::span<const int> face, int* out) {
  const size_t n = face.size();
  if (n == 0) return false;
  const size_t m = size_t(std::min_element(face.begin(), face.end()) - face.begin());
  // The first position where the two directions differ decides (both start at face[m]).
  bool reversed = false;
  for (size_t k = 1; k < n; ++k) {
    const int f = face[(m + k) % n], b = face[(m + n - k) % n];
    if (f != b) {
      reversed = b < f;
      break;
    }
  }
  for (size_t k = 0; k < n; ++k) out[k] = reversed ? face[(m + n - k) % n] : face[(m + k) % n];
  return reversed;
}

// The same key as a vector; `reversed` says that the backward direction was taken.
inline std::vector<int> canonical_cycle(std::span<const int> face, bool& reversed) {
  std::vector<int> key(face.size());
  reversed = canonical_cycle(face, key.data());
  return key;
}

// Singular values (descending, zero-padded to 3) of the corners (k x 3) minus their mean:
// sigma[1] <= tol * sigma[0] means the corners are collinear (zero area) relative to the face's size.
// As Eigen's JacobiSVD computes them for a tall matrix (a column-pivoting QR decomposition, then the
// Jacobi SVD of the 3 x 3 triangle), in storage on the stack for faces of 3 to 16 corners.
template <class Derived>
Eigen::Vector3d centred_singular_values(const Eigen::MatrixBase<Derived>& corners) {
  const Eigen::Index k = corners.rows();
  if (k >= 3 && k <= 16 && corners.cols() == 3) {
    using Small = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::ColMajor, 16, 3>;
    const Small Y = corners.rowwise() - corners.colwise().mean();
    const Eigen::ColPivHouseholderQR<Small> qr(Y);
    const Eigen::Matrix3d R = qr.matrixQR().template topRows<3>().template triangularView<Eigen::Upper>();
    return Eigen::JacobiSVD<Eigen::Matrix3d>(R).singularValues();
  }
  const Eigen::MatrixXd Y = corners.rowwise() - corners.colwise().mean();
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(Y).singularValues();
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();
  sigma.head(std::min<long>(3, s.size())) = s.head(std::min<long>(3, s.size()));
  return sigma;
}

}  // namespace polydec
