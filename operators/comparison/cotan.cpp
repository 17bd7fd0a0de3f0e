// operators/comparison/cotan.cpp — edge lengths of triangles, mixed Voronoi areas, mean edge length.
#include "polydec/operators/comparison/cotan.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace polydec {

LengthTriangles length_triangles(const Eigen::MatrixX3d& X, const std::vector<Eigen::Vector3i>& triangles) {
  LengthTriangles T;
  T.n_vertices = int(X.rows());
  T.triangles = triangles;
  T.lengths.reserve(triangles.size());
  for (const Eigen::Vector3i& t : triangles) {
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= X.rows()) throw std::out_of_range("length_triangles: vertex index out of range");
    T.lengths.emplace_back((X.row(t[1]) - X.row(t[0])).norm(), (X.row(t[2]) - X.row(t[1])).norm(),
                           (X.row(t[0]) - X.row(t[2])).norm());
  }
  return T;
}

Eigen::VectorXd voronoi_areas(const LengthTriangles& T) {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(T.n_vertices);
  for (size_t t = 0; t < T.triangles.size(); ++t) {
    const Eigen::Vector3i& c = T.triangles[t];
    const Eigen::Vector3d& l = T.lengths[t];  // l[k]: edge (k, k+1), opposite corner k+2
    const double A = triangle_area_from_lengths(l[0], l[1], l[2]);
    if (!(A > 0)) continue;
    const Eigen::Vector3d l2 = l.cwiseAbs2();
    // cos-sign of the angle at corner k (opposite edge k+1): l_k^2 + l_{k+2}^2 - l_{k+1}^2.
    int obtuse = -1;
    for (int k = 0; k < 3; ++k)
      if (l2[k] + l2[(k + 2) % 3] - l2[(k + 1) % 3] < 0) obtuse = k;
    if (obtuse >= 0) {
      for (int k = 0; k < 3; ++k) a[c[k]] += k == obtuse ? A / 2 : A / 4;
      continue;
    }
    // cot of the angle opposite edge e: (l_{e+1}^2 + l_{e+2}^2 - l_e^2) / (4 A); corner k touches
    // edges k and k+2, each contributing |e|^2 cot(opposite) / 8.
    auto cot_opp = [&](int e) { return (l2[(e + 1) % 3] + l2[(e + 2) % 3] - l2[e]) / (4 * A); };
    for (int k = 0; k < 3; ++k) a[c[k]] += (l2[k] * cot_opp(k) + l2[(k + 2) % 3] * cot_opp((k + 2) % 3)) / 8;
  }
  return a;
}

double mean_edge_length(const Eigen::MatrixX3d& X, const std::vector<Eigen::Vector3i>& tris) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * tris.size());
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k)
      edges.emplace_back(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  double sum = 0;
  for (const auto& [i, j] : edges) sum += (X.row(i) - X.row(j)).norm();
  return edges.empty() ? 0.0 : sum / double(edges.size());
}

}  // namespace polydec
