// bench/plain_volume_reference.cpp — the plain polyhedral Laplacian (see the header): written
// the way a first implementation would be, with no attention to speed beyond computing each face
// point once.
#include "bench/plain_volume_reference.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "polydec/dec/mesh/volume_mesh.h"

namespace plain_volume_reference {

namespace {

using Vec3 = Eigen::Vector3d;

// Least-norm affine weights of x over the rows of X: minimum-norm solution of [X^T; 1^T] w = [x; 1],
// in coordinates relative to the mean of X (uncentred, the decomposition's rank decision compares
// a planar face's round-off with the coordinates' magnitude instead of the face's size, and on
// small faces far from the origin takes them for non-planar: weights off by percents).
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

// Minimizer of sum_i area(x_i, x_{i+1}, x)^2: sum_i |e_i x (x - x_i)|^2 is quadratic in x.
Vec3 face_point(const Eigen::MatrixXd& X) {
  const int n = int(X.rows());
  const Vec3 mean = X.colwise().mean().transpose();
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Vec3 b = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    const Vec3 xi = X.row(i).transpose() - mean, xj = X.row((i + 1) % n).transpose() - mean;
    const Vec3 e = xj - xi;
    const Eigen::Matrix3d Ai = e.squaredNorm() * Eigen::Matrix3d::Identity() - e * e.transpose();  // |e x y|^2 = y^T Ai y
    A += Ai;
    b += Ai * xi;
  }
  return mean + A.completeOrthogonalDecomposition().solve(b);
}

}  // namespace

Mesh from_volume_mesh(const polydec::VolumeMesh& mesh) {
  Mesh out;
  for (int v = 0; v < mesh.n_vertices(); ++v) out.V.push_back(mesh.position(v));
  for (int f = 0; f < mesh.n_faces(); ++f) out.F.emplace_back(mesh.face(f).begin(), mesh.face(f).end());
  for (int c = 0; c < mesh.n_cells(); ++c) out.C.emplace_back(mesh.cell(c).begin(), mesh.cell(c).end());
  return out;
}

void build(const Mesh& mesh, Eigen::SparseMatrix<double>& S, Eigen::SparseMatrix<double>& Mout) {
  // Face points and weights, once per face.
  std::vector<Eigen::VectorXd> fw(mesh.F.size());
  std::vector<Vec3> fp(mesh.F.size());
  for (size_t f = 0; f < mesh.F.size(); ++f) {
    const auto& face = mesh.F[f];
    Eigen::MatrixXd X(face.size(), 3);
    for (size_t i = 0; i < face.size(); ++i) X.row(i) = mesh.V[face[i]].transpose();
    fp[f] = face_point(X);
    fw[f] = affine_weights(X, fp[f]);
  }
  std::vector<Eigen::Triplet<double>> ts, tm;
  for (const auto& cell : mesh.C) {
    // The cell's vertices, ascending.
    std::vector<int> verts;
    for (int hf : cell) verts.insert(verts.end(), mesh.F[hf / 2].begin(), mesh.F[hf / 2].end());
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    const int m = int(verts.size()), nf = int(cell.size()), r = m + nf + 1;
    auto local = [&](int v) { return int(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin()); };

    // Cell point: minimizer of sum vol(x_f, x_i, x_{i+1}, x)^2 = sum (n . (x - x_f))^2 / 36.
    Vec3 mean = Vec3::Zero();
    for (int v : verts) mean += mesh.V[v];
    mean /= m;
    Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
    Vec3 rhs = Vec3::Zero();
    for (int hf : cell) {
      const auto& face = mesh.F[hf / 2];
      const int n = int(face.size());
      for (int i = 0; i < n; ++i) {
        const Vec3 a = fp[hf / 2] - mean, b = mesh.V[face[i]] - mean, c = mesh.V[face[(i + 1) % n]] - mean;
        const Vec3 nrm = (b - a).cross(c - a);
        N += nrm * nrm.transpose();
        rhs += nrm * nrm.dot(a);
      }
    }
    const Vec3 xc = mean + N.completeOrthogonalDecomposition().solve(rhs);
    Eigen::MatrixXd X(m, 3);
    for (int k = 0; k < m; ++k) X.row(k) = mesh.V[verts[k]].transpose();
    const Eigen::VectorXd wc = affine_weights(X, xc);

    // Local prolongation: cell vertices, face points (half-face order), cell point.
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(r, m);
    P.topRows(m).setIdentity();
    for (int k = 0; k < nf; ++k) {
      const auto& face = mesh.F[cell[k] / 2];
      for (size_t i = 0; i < face.size(); ++i) P(m + k, local(face[i])) = fw[cell[k] / 2](i);
    }
    P.row(m + nf) = wc.transpose();

    // Fine local matrices over the sub-tetrahedra (x_a, x_b, x_f, x_c).
    Eigen::MatrixXd Sf = Eigen::MatrixXd::Zero(r, r), Mf = Sf;
    for (int k = 0; k < nf; ++k) {
      const int hf = cell[k];
      std::vector<int> face = mesh.F[hf / 2];
      if (hf & 1) std::reverse(face.begin(), face.end());
      const int n = int(face.size());
      for (int i = 0; i < n; ++i) {
        const int id[4] = {local(face[i]), local(face[(i + 1) % n]), m + k, m + nf};
        const Vec3 p[4] = {mesh.V[face[i]], mesh.V[face[(i + 1) % n]], fp[hf / 2], xc};
        Eigen::Matrix4d T;
        for (int a = 0; a < 4; ++a) {
          T(a, 0) = 1.0;
          T.block<1, 3>(a, 1) = p[a].transpose();
        }
        const double vol = std::abs(T.determinant()) / 6.0;
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b) Mf(id[a], id[b]) += vol / 20.0 * (a == b ? 2.0 : 1.0);
        double longest = 0;
        for (int a = 0; a < 4; ++a)
          for (int b = a + 1; b < 4; ++b) longest = std::max(longest, (p[a] - p[b]).norm());
        if (6.0 * vol <= 1e-8 * longest * longest * longest) continue;
        // Barycentric coordinate l_a(x) = Tinv(0, a) + Tinv(1..3, a) . x.
        const Eigen::Matrix4d Tinv = T.inverse();
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b)
            Sf(id[a], id[b]) -= vol * Tinv.block<3, 1>(1, a).dot(Tinv.block<3, 1>(1, b));
      }
    }
    const Eigen::MatrixXd Sl = P.transpose() * Sf * P, Ml = P.transpose() * Mf * P;
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b) {
        ts.emplace_back(verts[a], verts[b], Sl(a, b));
        tm.emplace_back(verts[a], verts[b], Ml(a, b));
      }
  }
  const int nv = int(mesh.V.size());
  S.resize(nv, nv);
  Mout.resize(nv, nv);
  S.setFromTriplets(ts.begin(), ts.end());
  Mout.setFromTriplets(tm.begin(), tm.end());
}

}  // namespace plain_volume_reference
