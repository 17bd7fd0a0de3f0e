// bench/plain_surface_reference.cpp — the plain polygon Laplacian (see the header): written the way
// a first implementation would be, a dense (n+1) x (n+1) fan system per face and no attention to speed.
#include "bench/plain_surface_reference.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "polydec/dec/mesh/mesh.h"

namespace plain_surface_reference {

namespace {

using Vec3 = Eigen::Vector3d;

// Minimizer of sum_i area(x_i, x_{i+1}, x)^2 over x (eq. 10): with e_i = x_{i+1} - x_i,
// 4 area^2 = |e_i x (x - x_i)|^2 = (x - x_i)^T (|e_i|^2 I - e_i e_i^T) (x - x_i), so the minimizer
// solves sum_i A_i x = sum_i A_i x_i. Relative to the mean of the corners.
Vec3 virtual_point(const Eigen::MatrixXd& X) {
  const int n = int(X.rows());
  const Vec3 mean = X.colwise().mean().transpose();
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Vec3 b = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    const Vec3 xi = X.row(i).transpose() - mean, xj = X.row((i + 1) % n).transpose() - mean;
    const Vec3 e = xj - xi;
    const Eigen::Matrix3d Ai = e.squaredNorm() * Eigen::Matrix3d::Identity() - e * e.transpose();
    A += Ai;
    b += Ai * xi;
  }
  return mean + A.completeOrthogonalDecomposition().solve(b);
}

// Least-norm affine weights of x over the rows of X: the minimum-norm w with X^T w = x and
// sum w = 1, in coordinates relative to the mean of X.
Eigen::VectorXd affine_weights(const Eigen::MatrixXd& X, const Vec3& x) {
  const int n = int(X.rows());
  const Eigen::RowVector3d mean = X.colwise().mean();
  Eigen::MatrixXd K(4, n);
  K.topRows(3) = (X.rowwise() - mean).transpose();
  K.row(3).setOnes();
  Eigen::VectorXd r(4);
  r.head(3) = x - mean.transpose();
  r(3) = 1.0;
  return K.completeOrthogonalDecomposition().solve(r);
}

}  // namespace

Mesh from_mesh(const polydec::Mesh& mesh) {
  Mesh out;
  for (int v = 0; v < mesh.n_vertices(); ++v) out.V.push_back(mesh.position(v));
  for (int f = 0; f < mesh.n_faces(); ++f) out.F.emplace_back(mesh.face(f).begin(), mesh.face(f).end());
  return out;
}

void build(const Mesh& mesh, Eigen::SparseMatrix<double>& S, Eigen::SparseMatrix<double>& M) {
  std::vector<Eigen::Triplet<double>> ts, tm;
  for (const auto& face : mesh.F) {
    const int n = int(face.size());
    Eigen::MatrixXd X(n, 3);
    for (int i = 0; i < n; ++i) X.row(i) = mesh.V[face[i]].transpose();
    const Vec3 xf = virtual_point(X);
    const Eigen::VectorXd w = affine_weights(X, xf);

    // Fine local matrices over (x_0, ..., x_{n-1}, x_f): the fan triangles (x_i, x_{i+1}, x_f).
    Eigen::MatrixXd Sf = Eigen::MatrixXd::Zero(n + 1, n + 1), Mf = Sf;
    for (int i = 0; i < n; ++i) {
      const int id[3] = {i, (i + 1) % n, n};
      const Vec3 p[3] = {mesh.V[face[i]], mesh.V[face[(i + 1) % n]], xf};
      const double twice_area = (p[1] - p[0]).cross(p[2] - p[0]).norm();
      // Linear mass: area / 12 * (1 + delta_ab).
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) Mf(id[a], id[b]) += twice_area / 24.0 * (a == b ? 2.0 : 1.0);
      double longest = 0;
      for (int a = 0; a < 3; ++a) longest = std::max(longest, (p[(a + 1) % 3] - p[a]).norm());
      if (twice_area <= 1e-8 * longest * longest) continue;
      // Cotangent stiffness: the angle at corner a weighs the opposite edge (b, c) by cot / 2.
      for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        const Vec3 u = p[b] - p[a], v = p[c] - p[a];
        const double half_cot = 0.5 * u.dot(v) / u.cross(v).norm();
        Sf(id[b], id[c]) += half_cot;
        Sf(id[c], id[b]) += half_cot;
        Sf(id[b], id[b]) -= half_cot;
        Sf(id[c], id[c]) -= half_cot;
      }
    }

    // The face's prolongation P = [I; w^T] (eq. 11): corner values and the virtual vertex's.
    Eigen::MatrixXd P(n + 1, n);
    P.topRows(n).setIdentity();
    P.row(n) = w.transpose();
    const Eigen::MatrixXd Sl = P.transpose() * Sf * P, Ml = P.transpose() * Mf * P;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        ts.emplace_back(face[a], face[b], Sl(a, b));
        tm.emplace_back(face[a], face[b], Ml(a, b));
      }
  }
  const int nv = int(mesh.V.size());
  S.resize(nv, nv);
  M.resize(nv, nv);
  S.setFromTriplets(ts.begin(), ts.end());
  M.setFromTriplets(tm.begin(), tm.end());
}

}  // namespace plain_surface_reference
