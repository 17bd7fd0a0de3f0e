// dec/surface/quadratic.cpp — P2 element matrices, the least-norm quadratic weights per face, and the
// quadratic prolongation with its node positions.
#include "polydec/dec/surface/quadratic.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <vector>

namespace polydec {

Eigen::Matrix<double, 6, 1> p2_basis(const Eigen::Vector3d& l) {
  Eigen::Matrix<double, 6, 1> b;
  b << l[0] * (2 * l[0] - 1), l[1] * (2 * l[1] - 1), l[2] * (2 * l[2] - 1), 4 * l[0] * l[1], 4 * l[1] * l[2],
      4 * l[2] * l[0];
  return b;
}

Eigen::Matrix<double, 6, 3> p2_basis_gradients(const Eigen::Vector3d& l, const Eigen::Vector3d& p0,
                                               const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
  const Eigen::Vector3d p[3] = {p0, p1, p2};
  const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
  const double n2 = n.squaredNorm();
  Eigen::Matrix<double, 6, 3> G = Eigen::Matrix<double, 6, 3>::Zero();
  if (!(n2 > 0)) return G;
  // grad l_i = n x e_i / |n|^2, e_i the edge opposite corner i, counter-clockwise.
  Eigen::Matrix3d g;
  for (int i = 0; i < 3; ++i) g.row(i) = n.cross(p[(i + 2) % 3] - p[(i + 1) % 3]) / n2;
  for (int i = 0; i < 3; ++i) G.row(i) = (4 * l[i] - 1) * g.row(i);
  for (int k = 0; k < 3; ++k) {
    const int i = k, j = (k + 1) % 3;
    G.row(3 + k) = 4 * (l[i] * g.row(j) + l[j] * g.row(i));
  }
  return G;
}

Matrix6d p2_triangle_stiffness(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                               const Eigen::Vector3d& p2) {
  const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
  Matrix6d K = Matrix6d::Zero();
  // The integrand is quadratic: the rule of the three edge midpoints (weights area/3) is exact.
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d l = Eigen::Vector3d::Zero();
    l[k] = l[(k + 1) % 3] = 0.5;
    const Eigen::Matrix<double, 6, 3> G = p2_basis_gradients(l, p0, p1, p2);
    K.noalias() += (area / 3) * G * G.transpose();
  }
  return K;
}

Matrix6d p2_triangle_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
  const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
  Matrix6d M;
  // Corner-corner 6 / -1; corner-midpoint 0 on its own edges, -4 on the opposite edge (midpoint 3
  // is opposite corner 2, 4 opposite 0, 5 opposite 1); midpoint-midpoint 32 / 16.
  M << 6, -1, -1, 0, -4, 0,  //
      -1, 6, -1, 0, 0, -4,   //
      -1, -1, 6, -4, 0, 0,   //
      0, 0, -4, 32, 16, 16,  //
      -4, 0, 0, 16, 32, 16,  //
      0, -4, 0, 16, 16, 32;
  return (area / 180) * M;
}

Eigen::MatrixXd quadratic_face_weights(const PolygonPositions& X, const Eigen::Vector3d& xf) {
  const int n = int(X.rows());
  const Eigen::RowVector3d c = X.colwise().mean();
  const Eigen::MatrixX3d Y = X.rowwise() - c;
  // The best-fit plane: the two leading right singular vectors of the centred corners; lengths in
  // units of the corners' rms radius, so the Vandermonde matrix is O(1) whatever the scale.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Y, Eigen::ComputeFullV);
  const double s = std::sqrt(Y.squaredNorm() / n);
  // A polygon collapsed to a point: only constants can be reproduced; uniform weights.
  if (!(s > 0)) return Eigen::MatrixXd::Constant(n + 1, 2 * n, 0.5 / n);
  const Eigen::Vector3d e1 = svd.matrixV().col(0) / s, e2 = svd.matrixV().col(1) / s;
  auto monomials = [&](const Eigen::RowVector3d& x) {
    const double u = (x - c).dot(e1.transpose()), v = (x - c).dot(e2.transpose());
    Eigen::Matrix<double, 6, 1> m;
    m << 1, u, v, u * u, u * v, v * v;
    return m;
  };
  Eigen::MatrixXd A(6, 2 * n), B(6, n + 1);
  for (int k = 0; k < n; ++k) {
    A.col(k) = monomials(X.row(k));
    A.col(n + k) = monomials(0.5 * (X.row(k) + X.row((k + 1) % n)));
  }
  B.col(0) = monomials(xf.transpose());
  for (int k = 0; k < n; ++k) B.col(1 + k) = monomials(0.5 * (X.row(k) + xf.transpose()));
  // Minimum-norm solution of A C = B (rank-revealing; a polygon whose edges span only two lines
  // has rank 5 and gets the least-squares weights).
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
  cod.setThreshold(1e-10);
  return cod.solve(B).transpose();
}

Eigen::MatrixX3d quadratic_dof_positions(const Mesh& mesh) {
  const int nv = mesh.n_vertices(), ne = mesh.n_edges();
  Eigen::MatrixX3d D(nv + ne, 3);
  D.topRows(nv) = mesh.positions();
  for (int e = 0; e < ne; ++e)
    D.row(nv + e) =
        0.5 * (mesh.positions().row(mesh.edges()(e, 0)) + mesh.positions().row(mesh.edges()(e, 1)));
  return D;
}

Eigen::MatrixX3d quadratic_refined_positions(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "quadratic_refined_positions");
  const int nc = mesh.n_vertices() + mesh.n_edges(), nf = mesh.n_faces();
  Eigen::MatrixX3d D(nc + nf + mesh.n_halfedges(), 3);
  D.topRows(nc) = quadratic_dof_positions(mesh);
  D.middleRows(nc, nf) = refinement.virtual_points;
  for (int h = 0; h < mesh.n_halfedges(); ++h)
    D.row(nc + nf + h) = 0.5 * (mesh.positions().row(mesh.halfedge_source(h)) +
                                refinement.virtual_points.row(mesh.halfedge_face(h)));
  return D;
}

Eigen::SparseMatrix<double> quadratic_prolongation(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "quadratic_prolongation");
  const int nv = mesh.n_vertices(), nc = nv + mesh.n_edges(), nf = mesh.n_faces();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(size_t(nc) + size_t(mesh.n_halfedges()) * 14);
  for (int i = 0; i < nc; ++i) t.emplace_back(i, i, 1.0);
  std::vector<int> cols;
  for (int f = 0; f < nf; ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size()), h0 = mesh.face_offsets()[f];
    const Eigen::MatrixXd W =
        quadratic_face_weights(face_positions(mesh, f), refinement.virtual_points.row(f));
    cols.assign(size_t(2 * n), 0);
    for (int k = 0; k < n; ++k) {
      cols[size_t(k)] = face[size_t(k)];
      cols[size_t(n + k)] = nv + mesh.halfedge_edge(h0 + k);
    }
    for (int j = 0; j < 2 * n; ++j) {
      t.emplace_back(nc + f, cols[size_t(j)], W(0, j));
      for (int k = 0; k < n; ++k) t.emplace_back(nc + nf + h0 + k, cols[size_t(j)], W(1 + k, j));
    }
  }
  Eigen::SparseMatrix<double> P(nc + nf + mesh.n_halfedges(), nc);
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

}  // namespace polydec
