// apps/applications/curvature.cpp — mean curvature (eq. 29) and angle-weighted vertex normals.
#include "polydec/apps/applications/curvature.h"

#include <cmath>

#include "polydec/operators/solvers/cholesky.h"

namespace polydec {

Eigen::MatrixX3d vertex_normals(const Mesh& mesh) {
  Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(mesh.n_vertices(), 3);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size());
    for (int a = 0; a < n; ++a) {
      const Eigen::Vector3d x = mesh.position(face[a]);
      const Eigen::Vector3d e_next = mesh.position(face[(a + 1) % n]) - x;
      const Eigen::Vector3d e_prev = mesh.position(face[(a + n - 1) % n]) - x;
      const Eigen::Vector3d c = e_next.cross(e_prev);
      const double cn = c.norm();
      if (!(cn > 0)) continue;  // degenerate corner: no direction
      const double angle = std::atan2(cn, e_next.dot(e_prev));
      N.row(face[a]) += angle * (c / cn).transpose();
    }
  }
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    const double len = N.row(v).norm();
    if (len > 0) N.row(v) /= len;
  }
  return N;
}

SparseMatrix mass_with_unit_rows_for_unreferenced(const OperatorSet& ops) {
  SparseMatrix M = ops.M;
  for (int v = 0; v < int(M.rows()); ++v)
    if (!(ops.M_lumped[v] > 0)) M.coeffRef(v, v) = 1.0;
  return M;
}

double signed_volume(const Mesh& mesh) {
  // Sum over a triangle fan of each face of det(x0, xa, xa+1) / 6.
  double vol = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const Eigen::Vector3d x0 = mesh.position(face[0]);
    for (size_t a = 1; a + 1 < face.size(); ++a)
      vol += x0.dot(mesh.position(face[a]).cross(mesh.position(face[a + 1]))) / 6.0;
  }
  return vol;
}

Eigen::VectorXd mean_curvature(const OperatorSet& ops, const CurvatureOptions& options) {
  const Mesh& mesh = ops.domain;
  const int nv = mesh.n_vertices();
  if (!options.lumped_mass && ops.M.size() == 0)
    throw std::invalid_argument("mean curvature: Laplacian '" + ops.name + "' defines no unlumped mass");
  const Eigen::MatrixXd SX = ops.S * mesh.positions();
  Eigen::MatrixXd LX = Eigen::MatrixXd::Zero(nv, 3);
  if (options.lumped_mass) {
    for (int v = 0; v < nv; ++v)
      if (ops.M_lumped[v] > 0) LX.row(v) = SX.row(v) / ops.M_lumped[v];
  } else {
    LX = SparseCholesky(mass_with_unit_rows_for_unreferenced(ops), "mass matrix M").solve(SX);
  }
  Eigen::MatrixX3d N = vertex_normals(mesh);
  // A closed mesh whose faces are oriented inwards (negative enclosed volume) gets its normals
  // flipped, so that they point outwards whatever the file's orientation.
  if (mesh.n_boundary_edges() == 0 && signed_volume(mesh) < 0) N = -N;
  Eigen::VectorXd H = Eigen::VectorXd::Zero(nv);
  for (int v = 0; v < nv; ++v) {
    if (!(ops.M_lumped[v] > 0)) continue;
    const double len = LX.row(v).norm();
    H[v] = 0.5 * len * (LX.row(v).dot(N.row(v)) > 0 ? -1.0 : 1.0);
  }
  return H;
}

Eigen::VectorXd mean_curvature(const Mesh& mesh, const CurvatureOptions& options) {
  return mean_curvature(build_operators(mesh, parse_laplacian("ours"), false), options);
}

double curvature_rmse(const Eigen::VectorXd& H, double expected) {
  if (H.size() == 0) return 0.0;
  return std::sqrt((H.array() - expected).square().mean());
}

}  // namespace polydec
