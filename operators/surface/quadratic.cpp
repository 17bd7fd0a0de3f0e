// operators/surface/quadratic.cpp — face-by-face assembly of the quadratic S, M and HRZ-lumped M,
// and the refined P2 matrices of the explicit route.
#include "polydec/operators/surface/quadratic.h"

#include <array>
#include <vector>

namespace polydec {

namespace {

// The six local refined nodes of fan triangle k of an n-gon (local numbering: corners 0..n-1,
// edge midpoints n..2n-1, x_f 2n, spoke midpoints 2n+1..3n), in P2 order (corners x_k, x_k+1,
// x_f, then the midpoints of (x_k, x_k+1), (x_k+1, x_f), (x_f, x_k)).
std::array<int, 6> fan_nodes(int n, int k) {
  const int k1 = (k + 1) % n;
  return {k, k1, 2 * n, n + k, 2 * n + 1 + k1, 2 * n + 1 + k};
}

}  // namespace

QuadraticLaplacian assemble_quadratic_laplacian(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "assemble_quadratic_laplacian");
  const int nv = mesh.n_vertices(), nd = nv + mesh.n_edges();
  std::vector<Eigen::Triplet<double>> ts, tm;
  size_t entries = 0;  // (2n)^2 per face
  for (int f = 0; f < mesh.n_faces(); ++f) entries += 4 * mesh.face(f).size() * mesh.face(f).size();
  ts.reserve(entries);
  tm.reserve(entries);
  QuadraticLaplacian Q;
  Q.M_lumped = Eigen::VectorXd::Zero(nd);
  Q.quality = refinement.quality;
  std::vector<int> dof;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size()), h0 = mesh.face_offsets()[f];
    const PolygonPositions X = face_positions(mesh, f);
    const Eigen::Vector3d xf = refinement.virtual_points.row(f).transpose();
    const Eigen::MatrixXd W = quadratic_face_weights(X, xf);
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3 * n + 1, 2 * n);
    P.topRows(2 * n).setIdentity();
    P.bottomRows(n + 1) = W;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n + 1, 3 * n + 1), Mf = K;
    double area = 0;
    for (int k = 0; k < n; ++k) {
      if (refinement.fan[size_t(h0 + k)] == FanTriangle::Degenerate) continue;
      const Eigen::Vector3d a = X.row(k).transpose(), b = X.row((k + 1) % n).transpose();
      const Matrix6d Ke = p2_triangle_stiffness(a, b, xf), Me = p2_triangle_mass(a, b, xf);
      area += 0.5 * (b - a).cross(xf - a).norm();
      const std::array<int, 6> nodes = fan_nodes(n, k);
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
          K(nodes[i], nodes[j]) += Ke(i, j);
          Mf(nodes[i], nodes[j]) += Me(i, j);
        }
    }
    const Eigen::MatrixXd Sl = -(P.transpose() * K * P), Ml = P.transpose() * Mf * P;
    dof.assign(size_t(2 * n), 0);
    for (int k = 0; k < n; ++k) {
      dof[size_t(k)] = face[size_t(k)];
      dof[size_t(n + k)] = nv + mesh.halfedge_edge(h0 + k);
    }
    for (int j = 0; j < 2 * n; ++j)
      for (int i = 0; i < 2 * n; ++i) {
        ts.emplace_back(dof[size_t(i)], dof[size_t(j)], Sl(i, j));
        tm.emplace_back(dof[size_t(i)], dof[size_t(j)], Ml(i, j));
      }
    const double trace = Ml.trace();
    if (trace > 0)
      for (int i = 0; i < 2 * n; ++i) Q.M_lumped[dof[size_t(i)]] += Ml(i, i) * area / trace;
  }
  Q.S.resize(nd, nd);
  Q.S.setFromTriplets(ts.begin(), ts.end());
  Q.M.resize(nd, nd);
  Q.M.setFromTriplets(tm.begin(), tm.end());
  Q.dofs = quadratic_dof_positions(mesh);
  return Q;
}

QuadraticGradient quadratic_gradient(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "quadratic_gradient");
  const int nv = mesh.n_vertices(), nd = nv + mesh.n_edges(), nh = mesh.n_halfedges();
  std::vector<Eigen::Triplet<double>> tg, td;
  std::vector<int> dof;
  const Eigen::Vector3d centroid = Eigen::Vector3d::Constant(1.0 / 3.0);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size()), h0 = mesh.face_offsets()[f];
    const PolygonPositions X = face_positions(mesh, f);
    const Eigen::Vector3d xf = refinement.virtual_points.row(f).transpose();
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3 * n + 1, 2 * n);
    P.topRows(2 * n).setIdentity();
    P.bottomRows(n + 1) = quadratic_face_weights(X, xf);
    dof.assign(size_t(2 * n), 0);
    for (int k = 0; k < n; ++k) {
      dof[size_t(k)] = face[size_t(k)];
      dof[size_t(n + k)] = nv + mesh.halfedge_edge(h0 + k);
    }
    for (int k = 0; k < n; ++k) {
      const int h = h0 + k;
      if (refinement.fan[size_t(h)] == FanTriangle::Degenerate) continue;
      const Eigen::Vector3d a = X.row(k).transpose(), b = X.row((k + 1) % n).transpose();
      const double area = 0.5 * (b - a).cross(xf - a).norm();
      const Eigen::Matrix<double, 6, 3> B = p2_basis_gradients(centroid, a, b, xf);
      const std::array<int, 6> nodes = fan_nodes(n, k);
      Eigen::MatrixXd Gl = Eigen::MatrixXd::Zero(3, 2 * n);  // the fan triangle's gradient of each coarse dof
      for (int i = 0; i < 6; ++i) Gl += B.row(i).transpose() * P.row(nodes[size_t(i)]);
      for (int j = 0; j < 2 * n; ++j)
        for (int c = 0; c < 3; ++c) {
          if (Gl(c, j) == 0) continue;
          tg.emplace_back(3 * h + c, dof[size_t(j)], Gl(c, j));
          td.emplace_back(dof[size_t(j)], 3 * h + c, -area * Gl(c, j));
        }
    }
  }
  QuadraticGradient Q;
  Q.G.resize(3 * nh, nd);
  Q.G.setFromTriplets(tg.begin(), tg.end());
  Q.D.resize(nd, 3 * nh);
  Q.D.setFromTriplets(td.begin(), td.end());
  return Q;
}

QuadraticLaplacian quadratic_laplacian(const Mesh& mesh) {
  return assemble_quadratic_laplacian(mesh, refine(mesh));
}

QuadraticRefinedMatrices quadratic_refined_matrices(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "quadratic_refined_matrices");
  const int nv = mesh.n_vertices(), nc = nv + mesh.n_edges(), nf = mesh.n_faces(),
            nr = nc + nf + mesh.n_halfedges();
  std::vector<Eigen::Triplet<double>> ts, tm;
  for (int f = 0; f < nf; ++f) {
    const int h0 = mesh.face_offsets()[f], n = mesh.face_offsets()[f + 1] - h0;
    const Eigen::Vector3d xf = refinement.virtual_points.row(f).transpose();
    for (int k = 0; k < n; ++k) {
      const int h = h0 + k, h1 = h0 + (k + 1) % n;
      if (refinement.fan[size_t(h)] == FanTriangle::Degenerate) continue;
      const Eigen::Vector3d a = mesh.positions().row(mesh.halfedge_source(h)).transpose();
      const Eigen::Vector3d b = mesh.positions().row(mesh.halfedge_source(h1)).transpose();
      const Matrix6d Ke = p2_triangle_stiffness(a, b, xf), Me = p2_triangle_mass(a, b, xf);
      const int nodes[6] = {mesh.halfedge_source(h),
                            mesh.halfedge_source(h1),
                            nc + f,
                            nv + mesh.halfedge_edge(h),
                            nc + nf + h1,
                            nc + nf + h};
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
          ts.emplace_back(nodes[i], nodes[j], -Ke(i, j));
          tm.emplace_back(nodes[i], nodes[j], Me(i, j));
        }
    }
  }
  QuadraticRefinedMatrices R;
  R.S.resize(nr, nr);
  R.S.setFromTriplets(ts.begin(), ts.end());
  R.M.resize(nr, nr);
  R.M.setFromTriplets(tm.begin(), tm.end());
  return R;
}

}  // namespace polydec
