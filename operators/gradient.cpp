// operators/gradient.cpp — gradient and divergence on the refined fan triangles.
#include "operators/gradient.h"

namespace polydec {

void hat_gradients(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                   Eigen::Vector3d g[3]) {
  const Eigen::Vector3d N = (p1 - p0).cross(p2 - p0);
  const double n2 = N.squaredNorm();
  g[0] = N.cross(p2 - p1) / n2;
  g[1] = N.cross(p0 - p2) / n2;
  g[2] = N.cross(p1 - p0) / n2;
}

Eigen::VectorXd fan_areas(const Mesh& mesh, const Refinement& refinement) {
  Eigen::VectorXd a(mesh.n_halfedges());
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    if (refinement.fan[h] == FanTriangle::Degenerate) {
      a[h] = 0.0;
      continue;
    }
    const Eigen::Vector3d xf = refinement.virtual_points.row(mesh.halfedge_face(h)).transpose();
    a[h] = 0.5 * (mesh.position(mesh.halfedge_source(h)) - xf)
                     .cross(mesh.position(mesh.halfedge_target(h)) - xf)
                     .norm();
  }
  return a;
}

SparseMatrix gradient(const Mesh& mesh, const Refinement& refinement) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(size_t(mesh.n_halfedges()) * 3 * 8);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size()), h0 = mesh.face_offsets()[f];
    const Eigen::Vector3d xf = refinement.virtual_points.row(f).transpose();
    for (int k = 0; k < n; ++k) {
      const int h = h0 + k;
      if (refinement.fan[h] == FanTriangle::Degenerate) continue;
      const int i = face[k], j = face[(k + 1) % n];
      Eigen::Vector3d g[3];
      hat_gradients(mesh.position(i), mesh.position(j), xf, g);
      // Coarse vertex c contributes [c == i] g0 + [c == j] g1 + w_c g2.
      for (int m = 0; m < n; ++m) {
        const Eigen::Vector3d gm = refinement.weights[h0 + m] * g[2] +
                                   (m == k ? g[0] : Eigen::Vector3d::Zero()) +
                                   (m == (k + 1) % n ? g[1] : Eigen::Vector3d::Zero());
        for (int c = 0; c < 3; ++c) t.emplace_back(3 * h + c, face[m], gm[c]);
      }
    }
  }
  SparseMatrix G(3 * mesh.n_halfedges(), mesh.n_vertices());
  G.setFromTriplets(t.begin(), t.end());
  return G;
}

SparseMatrix divergence(const Mesh& mesh, const Refinement& refinement) {
  const Eigen::VectorXd a = fan_areas(mesh, refinement);
  Eigen::VectorXd w3(3 * a.size());
  for (int h = 0; h < a.size(); ++h) w3.segment<3>(3 * h).setConstant(a[h]);
  SparseMatrix D = -(w3.asDiagonal() * gradient(mesh, refinement)).transpose();
  return D;
}

}  // namespace polydec
