// operators/comparison/degoes20.cpp — de Goes, Butts & Desbrun 2020 polygon operators.
#include "polydec/operators/comparison/degoes20.h"

#include "polydec/operators/comparison/aw11.h"

#include <cmath>

namespace polydec {

namespace {

struct FaceFrame {
  PolygonPositions Y;  // centred corners
  Eigen::Vector3d n;   // unit normal (vector area direction)
  double A = 0;        // vector area magnitude
};

FaceFrame frame(const PolygonPositions& X) {
  FaceFrame F;
  F.Y = X.rowwise() - X.colwise().mean();
  const int k = int(X.rows());
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (int i = 0; i < k; ++i) a += 0.5 * F.Y.row(i).transpose().cross(F.Y.row((i + 1) % k).transpose());
  F.A = a.norm();
  if (!(F.A > 0)) throw std::invalid_argument("degoes20: polygon of zero vector area");
  F.n = a / F.A;
  return F;
}

Eigen::MatrixXd cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d K;
  K << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return K;
}

// Sharp U_f (3 x n): (1/A) n x (b_i - c), with midpoints b_i in centred coordinates.
Eigen::MatrixXd sharp(const FaceFrame& F) {
  const int k = int(F.Y.rows());
  Eigen::MatrixXd Bc(3, k);
  for (int i = 0; i < k; ++i) Bc.col(i) = 0.5 * (F.Y.row(i) + F.Y.row((i + 1) % k)).transpose();
  return cross_matrix(F.n) * Bc / F.A;
}

}  // namespace

Eigen::MatrixXd degoes20_local_gradient(const PolygonPositions& X) {
  const FaceFrame F = frame(X);
  return sharp(F) * cyclic_difference(int(X.rows()));
}

Eigen::MatrixXd degoes20_local_stiffness(const PolygonPositions& X, double lambda) {
  const int k = int(X.rows());
  const FaceFrame F = frame(X);
  const Eigen::MatrixXd U = sharp(F), d = cyclic_difference(k);
  Eigen::MatrixXd E(k, 3);
  for (int i = 0; i < k; ++i) E.row(i) = F.Y.row((i + 1) % k) - F.Y.row(i);
  const Eigen::MatrixXd V = E * (Eigen::Matrix3d::Identity() - F.n * F.n.transpose());
  const Eigen::MatrixXd P = Eigen::MatrixXd::Identity(k, k) - V * U;
  const Eigen::MatrixXd Mf = F.A * U.transpose() * U + lambda * P.transpose() * P;
  return -d.transpose() * Mf * d;
}

OperatorSet degoes20_operators(const Mesh& mesh, double lambda, bool with_gradient) {
  const int nv = mesh.n_vertices(), nf = mesh.n_faces();
  OperatorSet ops;
  ops.domain = mesh;
  ops.n_input_vertices = nv;
  ops.M_lumped = Eigen::VectorXd::Zero(nv);
  std::vector<Eigen::Triplet<double>> ts, tg;
  Eigen::VectorXd W(3 * nf);
  for (int f = 0; f < nf; ++f) {
    const auto face = mesh.face(f);
    const int k = int(face.size());
    const PolygonPositions X = face_positions(mesh, f);
    const PolygonPositions Y = X.rowwise() - X.colwise().mean();
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    for (int i = 0; i < k; ++i) a += 0.5 * Y.row(i).transpose().cross(Y.row((i + 1) % k).transpose());
    const double A = a.norm();
    if (!(A > 1e-14 * Y.rowwise().squaredNorm().maxCoeff()))
      throw InvalidMeshError("face", f, "degoes20: face has zero vector area");
    const Eigen::MatrixXd Sf = degoes20_local_stiffness(X, lambda);
    for (int i = 0; i < k; ++i) {
      ops.M_lumped[face[i]] += A / k;
      for (int j = 0; j < k; ++j) ts.emplace_back(face[i], face[j], Sf(i, j));
    }
    if (with_gradient) {
      const Eigen::MatrixXd Gf = degoes20_local_gradient(X);
      for (int c = 0; c < 3; ++c)
        for (int j = 0; j < k; ++j) tg.emplace_back(3 * f + c, face[j], Gf(c, j));
      W.segment<3>(3 * f).setConstant(A);
    }
  }
  ops.S.resize(nv, nv);
  ops.S.setFromTriplets(ts.begin(), ts.end());
  if (with_gradient) {
    ops.G.resize(3 * nf, nv);
    ops.G.setFromTriplets(tg.begin(), tg.end());
    ops.D = -(W.asDiagonal() * ops.G).transpose();
  }
  return ops;
}

}  // namespace polydec
