// operators/comparison/triangulation.cpp — O(n^3) dynamic programming over polygon diagonals.
#include "polydec/operators/comparison/triangulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "polydec/dec/surface/refinement.h"

namespace polydec {

namespace {

double squared_area(const PolygonPositions& X, int a, int b, int c) {
  return 0.25 * (X.row(b) - X.row(a)).cross(X.row(c) - X.row(a)).squaredNorm();
}

// Smallest interior angle of triangle (a, b, c) in radians; 0 for a degenerate triangle.
double min_angle(const PolygonPositions& X, int a, int b, int c) {
  const int v[3] = {a, b, c};
  double m = M_PI;
  for (int k = 0; k < 3; ++k) {
    const Eigen::RowVector3d u = X.row(v[(k + 1) % 3]) - X.row(v[k]), w = X.row(v[(k + 2) % 3]) - X.row(v[k]);
    m = std::min(m, std::atan2(u.cross(w).norm(), u.dot(w)));
  }
  return m;
}

}  // namespace

PolygonTriangulation triangulate_polygon(const PolygonPositions& X, TriangulationRule rule) {
  const int n = int(X.rows());
  if (n < 3) throw std::invalid_argument("triangulate_polygon: fewer than 3 corners");
  // best(i, j) = optimal value of the sub-polygon i, i+1, .., j; apex(i, j) = its apex k.
  // For MinSquaredArea values are sums (minimized), for MaxMinAngle minima (maximized); both are
  // stored as "cost to minimize" (the angle negated).
  const bool area = rule == TriangulationRule::MinSquaredArea;
  Eigen::MatrixXd best = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXi apex = Eigen::MatrixXi::Constant(n, n, -1);
  for (int len = 2; len < n; ++len)
    for (int i = 0; i + len < n; ++i) {
      const int j = i + len;
      double b = std::numeric_limits<double>::infinity();
      for (int k = i + 1; k < j; ++k) {
        double c;
        if (area) {
          c = best(i, k) + best(k, j) + squared_area(X, i, k, j);
        } else {
          c = -min_angle(X, i, k, j);
          if (k - i >= 2) c = std::max(c, best(i, k));
          if (j - k >= 2) c = std::max(c, best(k, j));
        }
        if (apex(i, j) < 0 || c < b - 1e-12 * std::abs(b)) {  // near-ties: smallest apex, not round-off
          b = c;
          apex(i, j) = k;
        }
      }
      best(i, j) = b;
    }
  PolygonTriangulation T;
  T.reserve(n - 2);
  std::vector<std::pair<int, int>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const int k = apex(i, j);
    T.emplace_back(i, k, j);
    stack.emplace_back(i, k);
    stack.emplace_back(k, j);
  }
  std::sort(T.begin(), T.end(), [](const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return T;
}

double triangulation_cost(const PolygonPositions& X, const PolygonTriangulation& T, TriangulationRule rule) {
  double c = rule == TriangulationRule::MinSquaredArea ? 0.0 : M_PI;
  for (const auto& t : T) {
    if (rule == TriangulationRule::MinSquaredArea)
      c += squared_area(X, t[0], t[1], t[2]);
    else
      c = std::min(c, min_angle(X, t[0], t[1], t[2]));
  }
  return c;
}

std::vector<Eigen::Vector3i> triangulate(const Mesh& mesh, TriangulationRule rule) {
  std::vector<Eigen::Vector3i> tris;
  tris.reserve(mesh.n_halfedges() - 2 * mesh.n_faces());
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    if (face.size() == 3) {
      tris.emplace_back(face[0], face[1], face[2]);
      continue;
    }
    for (const auto& t : triangulate_polygon(face_positions(mesh, f), rule))
      tris.emplace_back(face[t[0]], face[t[1]], face[t[2]]);
  }
  return tris;
}

}  // namespace polydec
