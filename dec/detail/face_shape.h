// dec/detail/face_shape.h — two small facts about one polygon that validation (dec/mesh/mesh_checks.h) and
// repair (dec/mesh/repair.h) both decide: its vertex cycle up to rotation and direction, and the
// singular values of its centred corners (zero area and thinness, relative to its own size).
#pragma once

#include <Eigen/SVD>
#include <algorithm>
#include <span>
#include <vector>

namespace polydec {

// The face's vertex cycle rotated to start at its smallest index, read in the direction whose
// sequence is lexicographically smaller; `reversed` says that the backward direction was taken.
// Two faces with the same cycle in either direction get the same key.
inline std::vector<int> canonical_cycle(std::span<const int> face, bool& reversed) {
  const size_t n = face.size();
  const size_t m = size_t(std::min_element(face.begin(), face.end()) - face.begin());
  std::vector<int> fwd(n), bwd(n);
  for (size_t k = 0; k < n; ++k) {
    fwd[k] = face[(m + k) % n];
    bwd[k] = face[(m + n - k) % n];
  }
  reversed = bwd < fwd;
  return reversed ? bwd : fwd;
}

// Singular values (descending, zero-padded to 3) of the corners (k x 3) minus their mean:
// sigma[1] <= tol * sigma[0] means the corners are collinear (zero area) relative to the face's size.
inline Eigen::Vector3d centred_singular_values(const Eigen::MatrixXd& corners) {
  const Eigen::VectorXd s =
      Eigen::JacobiSVD<Eigen::MatrixXd>(Eigen::MatrixXd(corners.rowwise() - corners.colwise().mean())).singularValues();
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();
  sigma.head(std::min<long>(3, s.size())) = s.head(std::min<long>(3, s.size()));
  return sigma;
}

}  // namespace polydec
