// tests/dec/detail/test_face_shape.cpp — the polygon facts that validation and repair share: the
// canonical vertex cycle against a search over every rotation and direction, and the centred
// singular values against Eigen's JacobiSVD of the whole corner matrix (dynamic sizes), down to the
// zero-area tolerance.
#include <Eigen/SVD>
#include <algorithm>
#include <catch2/catch.hpp>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "polydec/dec/detail/face_shape.h"

using namespace polydec;

namespace test_face_shape {
namespace {

// The smallest of all rotations of the cycle read forward and backward.
std::vector<int> smallest_rotation(const std::vector<int>& face) {
  const size_t n = face.size();
  std::vector<int> best;
  for (int direction : {1, -1})
    for (size_t start = 0; start < n; ++start) {
      std::vector<int> r(n);
      for (size_t k = 0; k < n; ++k) r[k] = face[(start + n + direction * long(k) % long(n)) % n];
      if (best.empty() || r < best) best = r;
    }
  return best;
}

// Singular values of the centred corners by the route the library used before: JacobiSVD of the
// dynamic k x 3 matrix, zero-padded to 3.
Eigen::Vector3d reference_singular_values(const Eigen::MatrixXd& X) {
  const Eigen::VectorXd s =
      Eigen::JacobiSVD<Eigen::MatrixXd>(Eigen::MatrixXd(X.rowwise() - X.colwise().mean())).singularValues();
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();
  sigma.head(std::min<long>(3, s.size())) = s.head(std::min<long>(3, s.size()));
  return sigma;
}

}  // namespace

TEST_CASE("canonical_cycle is the smallest rotation in either direction, and says which", "[face-shape]") {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + int(rng() % 9);
    // Distinct corners (as in a valid face), drawn from few labels.
    std::vector<int> labels(12);
    std::iota(labels.begin(), labels.end(), 0);
    std::shuffle(labels.begin(), labels.end(), rng);
    const std::vector<int> face(labels.begin(), labels.begin() + n);
    CAPTURE(face);
    bool reversed = false;
    const std::vector<int> key = canonical_cycle(face, reversed);
    CHECK(key == smallest_rotation(face));
    // `reversed`: the key is the backward reading from the first smallest corner, and the forward one differs.
    const size_t m = size_t(std::min_element(face.begin(), face.end()) - face.begin());
    std::vector<int> forward(face.size());
    for (size_t k = 0; k < face.size(); ++k) forward[k] = face[(m + k) % face.size()];
    CHECK(reversed == (key != forward));
    std::vector<int> out(face.size(), -1);
    CHECK(canonical_cycle(face, out.data()) == reversed);
    CHECK(out == key);
  }
}

TEST_CASE("centred singular values equal JacobiSVD of the whole corner matrix, also near zero area",
          "[face-shape]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 600; ++trial) {
    const int k = 3 + int(rng() % 18);  // 3 .. 20 corners: the stack route and the general one
    const int kind = trial % 4;          // general, planar, nearly collinear, collinear
    const double scale = std::ldexp(1.0, int(rng() % 200) - 100);
    Eigen::MatrixXd X(k, 3);
    const Eigen::Vector3d a = Eigen::Vector3d::Random(), b = Eigen::Vector3d::Random(), c = Eigen::Vector3d::Random();
    for (int i = 0; i < k; ++i) {
      const double s = normal(rng), t = normal(rng), u = normal(rng);
      Eigen::Vector3d x = s * a;
      if (kind != 3) x += (kind == 2 ? 1e-12 : 1.0) * t * b;
      if (kind == 0) x += u * c;
      X.row(i) = (scale * (x + Eigen::Vector3d(3, -2, 7))).transpose();
    }
    CAPTURE(k, kind, scale);
    const Eigen::Vector3d ours = centred_singular_values(X), ref = reference_singular_values(X);
    // Both backward stable: each value to a few units of round-off of the largest.
    CHECK((ours - ref).cwiseAbs().maxCoeff() <= 64 * std::numeric_limits<double>::epsilon() * ref[0]);
    CHECK(ours[0] >= ours[1]);
    CHECK(ours[1] >= ours[2]);
    // The classification validation makes: zero area at 1e-10 of the largest, never for a general face,
    // always for a collinear one; the 1e-12 band lies well inside.
    const bool zero_area = ours[1] <= 1e-10 * ours[0];
    CHECK(zero_area == (ref[1] <= 1e-10 * ref[0]));
    CHECK(zero_area == (kind >= 2));
  }
  // Fewer than three corners: the general route, zero-padded.
  Eigen::MatrixXd two(2, 3);
  two << 0, 0, 0, 3, 4, 0;
  CHECK(centred_singular_values(two).isApprox(Eigen::Vector3d(2.5 * std::sqrt(2.0), 0, 0)));
}

}  // namespace test_face_shape
