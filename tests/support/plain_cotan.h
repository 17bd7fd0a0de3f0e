// tests/support/plain_cotan.h — a deliberately plain cotangent Laplacian and Galerkin mass of a triangle
// mesh (eq. 2-3), written independently of operators/ to serve as a test oracle.
#pragma once

#include "polydec/dec/mesh/mesh.h"

#include <Eigen/Sparse>

namespace polydec::test {

struct PlainCotan {
  Eigen::SparseMatrix<double> S, M;
};

inline PlainCotan plain_cotan(const Mesh& tri, const std::vector<bool>& skip = {}) {
  std::vector<Eigen::Triplet<double>> ts, tm;
  for (int f = 0; f < tri.n_faces(); ++f) {
    const auto c = tri.face(f);
    const Eigen::Vector3d p[3] = {tri.position(c[0]), tri.position(c[1]), tri.position(c[2])};
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) tm.emplace_back(c[a], c[b], area / 12.0 * (a == b ? 2.0 : 1.0));
    if (!skip.empty() && skip[f]) continue;
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, d = (a + 2) % 3;
      const Eigen::Vector3d u = p[b] - p[a], v = p[d] - p[a];
      const double w = 0.5 * u.dot(v) / u.cross(v).norm();  // half cotangent of the angle at a
      ts.emplace_back(c[b], c[d], w);
      ts.emplace_back(c[d], c[b], w);
      ts.emplace_back(c[b], c[b], -w);
      ts.emplace_back(c[d], c[d], -w);
    }
  }
  PlainCotan r;
  r.S.resize(tri.n_vertices(), tri.n_vertices());
  r.M.resize(tri.n_vertices(), tri.n_vertices());
  r.S.setFromTriplets(ts.begin(), ts.end());
  r.M.setFromTriplets(tm.begin(), tm.end());
  return r;
}

}  // namespace polydec::test
