// operators/comparison/aw11.cpp — Alexa & Wardetzky 2011 polygon Laplacian.
#include "polydec/operators/comparison/aw11.h"

#include <Eigen/Dense>
#include <cmath>

namespace polydec {

Eigen::MatrixXd cyclic_difference(int n) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    d(i, i) = -1.0;
    d(i, (i + 1) % n) = 1.0;
  }
  return d;
}

namespace {

// Vector area of a polygon, (1/2) sum_i y_i x y_{i+1} on centred positions.
Eigen::Vector3d vector_area(const PolygonPositions& Y) {
  const int n = int(Y.rows());
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) a += 0.5 * Y.row(i).transpose().cross(Y.row((i + 1) % n).transpose());
  return a;
}

}  // namespace

Eigen::MatrixXd aw11_inner_product(const PolygonPositions& X, double lambda) {
  const int n = int(X.rows());
  const PolygonPositions Y = X.rowwise() - X.colwise().mean();  // d^T B does not depend on the origin
  const Eigen::Vector3d a = vector_area(Y);
  const double A = a.norm();
  if (!(A > 0)) throw std::invalid_argument("aw11: polygon of zero vector area");
  const Eigen::Vector3d nrm = a / A, t1 = nrm.unitOrthogonal(), t2 = nrm.cross(t1);
  Eigen::MatrixXd B(n, 3), E2(n, 2);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = Y.row(i).transpose(), q = Y.row((i + 1) % n).transpose();
    B.row(i) = 0.5 * (p + q).transpose();
    E2(i, 0) = (q - p).dot(t1);  // edges projected to the plane orthogonal to a
    E2(i, 1) = (q - p).dot(t2);
  }
  Eigen::MatrixXd Mf = B * B.transpose() / A;
  if (lambda > 0) {
    // Projector onto ker(E2^T) = I - E2 (E2^T E2)^-1 E2^T (E2 has rank 2 when A > 0).
    const Eigen::MatrixXd K =
        Eigen::MatrixXd::Identity(n, n) - E2 * (E2.transpose() * E2).ldlt().solve(E2.transpose());
    Mf += lambda * K;
  }
  return Mf;
}

Eigen::MatrixXd aw11_local_stiffness(const PolygonPositions& X, double lambda) {
  const Eigen::MatrixXd d = cyclic_difference(int(X.rows()));
  return -d.transpose() * aw11_inner_product(X, lambda) * d;
}

OperatorSet aw11_operators(const Mesh& mesh, double lambda, bool with_gradient) {
  const int nv = mesh.n_vertices();
  OperatorSet ops;
  ops.domain = mesh;
  ops.n_input_vertices = nv;
  ops.M_lumped = Eigen::VectorXd::Zero(nv);
  std::vector<Eigen::Triplet<double>> ts, tg;
  std::vector<double> block_weight;
  int row = 0;
  if (with_gradient) ops.G_blocks.push_back(0);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size());
    const PolygonPositions X = face_positions(mesh, f);
    const double A = vector_area(X.rowwise() - X.colwise().mean()).norm();
    if (!(A > 1e-14 * std::pow((X.rowwise() - X.colwise().mean()).rowwise().norm().maxCoeff(), 2)))
      throw InvalidMeshError("face", f, "aw11: face has zero vector area");
    const Eigen::MatrixXd Mf = aw11_inner_product(X, lambda);
    const Eigen::MatrixXd d = cyclic_difference(n);
    const Eigen::MatrixXd Sf = -d.transpose() * Mf * d;
    for (int a = 0; a < n; ++a) {
      ops.M_lumped[face[a]] += A / n;
      for (int b = 0; b < n; ++b) ts.emplace_back(face[a], face[b], Sf(a, b));
    }
    if (with_gradient) {
      // R with R^T R = M_f from the symmetric eigen-decomposition (M_f is only semi-definite
      // when lambda = 0).
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Mf);
      const Eigen::VectorXd ev = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
      const Eigen::MatrixXd Gf = ev.asDiagonal() * es.eigenvectors().transpose() * d / std::sqrt(A);
      for (int r = 0; r < n; ++r) {
        for (int b = 0; b < n; ++b) tg.emplace_back(row + r, face[b], Gf(r, b));
        block_weight.push_back(A);
      }
      row += n;
      ops.G_blocks.push_back(row);
    }
  }
  ops.S.resize(nv, nv);
  ops.S.setFromTriplets(ts.begin(), ts.end());
  if (with_gradient) {
    ops.G.resize(row, nv);
    ops.G.setFromTriplets(tg.begin(), tg.end());
    const Eigen::Map<const Eigen::VectorXd> W(block_weight.data(), row);
    ops.D = -(W.asDiagonal() * ops.G).transpose();
  }
  return ops;
}

}  // namespace polydec
