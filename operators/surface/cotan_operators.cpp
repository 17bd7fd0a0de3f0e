// operators/surface/cotan_operators.cpp — cotangent stiffness, Galerkin mass and triangle gradients.
#include "polydec/operators/surface/cotan_operators.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "polydec/dec/surface/whitney.h"

namespace polydec {

double triangle_area_from_lengths(double a, double b, double c) {
  double s[3] = {a, b, c};
  std::sort(s, s + 3, std::greater<>());  // s[0] >= s[1] >= s[2]
  const double p =
      (s[0] + (s[1] + s[2])) * (s[2] - (s[0] - s[1])) * (s[2] + (s[0] - s[1])) * (s[0] + (s[1] - s[2]));
  return p > 0 ? 0.25 * std::sqrt(p) : 0.0;
}

namespace cotan_operators_detail {
namespace {

// Assembles S, M, lumped M from per-triangle lengths; `gradients(t, g)` fills the three
// corner gradients of triangle t (only called for non-degenerate triangles).
template <class GradientFn>
TriangleOperators assemble(int nv, const std::vector<Eigen::Vector3i>& tris,
                           const std::vector<Eigen::Vector3d>& len, bool with_gradient, double tol,
                           GradientFn gradients) {
  const int nt = int(tris.size());
  std::vector<Eigen::Triplet<double>> ts, tm, tg;
  ts.reserve(9 * size_t(nt));
  tm.reserve(9 * size_t(nt));
  if (with_gradient) tg.reserve(9 * size_t(nt));
  TriangleOperators ops;
  Eigen::VectorXd area(nt);
  for (int t = 0; t < nt; ++t) {
    const Eigen::Vector3i& c = tris[t];
    const Eigen::Vector3d& l = len[t];  // l[k]: edge (k, k+1), opposite corner k+2
    const double A = triangle_area_from_lengths(l[0], l[1], l[2]);
    area[t] = A;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) tm.emplace_back(c[a], c[b], A / 12.0 * (a == b ? 2.0 : 1.0));
    const double longest2 = l.squaredNorm() > 0 ? l.cwiseAbs2().maxCoeff() : 0.0;
    if (!(2 * A > tol * longest2)) {
      ++ops.n_degenerate;
      area[t] = 0.0;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      // Edge k joins corners k and k+1; the angle opposite it is at corner k+2:
      // cot = (l_{k+1}^2 + l_{k+2}^2 - l_k^2) / (4 A); S gets half of it.
      const double l0 = l[k], l1 = l[(k + 1) % 3], l2 = l[(k + 2) % 3];
      const double w = (l1 * l1 + l2 * l2 - l0 * l0) / (8.0 * A);
      const int i = c[k], j = c[(k + 1) % 3];
      ts.emplace_back(i, j, w);
      ts.emplace_back(j, i, w);
      ts.emplace_back(i, i, -w);
      ts.emplace_back(j, j, -w);
    }
    if (with_gradient) {
      Eigen::Vector3d g[3];
      gradients(t, g);
      for (int a = 0; a < 3; ++a)
        for (int d = 0; d < 3; ++d) tg.emplace_back(3 * t + d, c[a], g[a][d]);
    }
  }
  ops.S.resize(nv, nv);
  ops.S.setFromTriplets(ts.begin(), ts.end());
  ops.M.resize(nv, nv);
  ops.M.setFromTriplets(tm.begin(), tm.end());
  ops.M_lumped = Eigen::VectorXd::Zero(nv);
  for (int j = 0; j < ops.M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(ops.M, j); it; ++it) ops.M_lumped[it.row()] += it.value();
  if (with_gradient) {
    ops.G.resize(3 * nt, nv);
    ops.G.setFromTriplets(tg.begin(), tg.end());
    Eigen::VectorXd w3(3 * nt);
    for (int t = 0; t < nt; ++t) w3.segment<3>(3 * t).setConstant(area[t]);
    ops.D = -(w3.asDiagonal() * ops.G).transpose();
  }
  return ops;
}

}  // namespace
}  // namespace cotan_operators_detail

using namespace cotan_operators_detail;

TriangleOperators cotan_operators(const Mesh& mesh, bool with_gradient, double tol) {
  std::vector<Eigen::Vector3i> tris(mesh.n_faces());
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    if (face.size() != 3)
      throw std::invalid_argument("cotan_operators: face " + std::to_string(f) + " is not a triangle");
    tris[f] = Eigen::Vector3i(face[0], face[1], face[2]);
  }
  return cotan_operators(mesh.positions(), tris, with_gradient, tol);
}

TriangleOperators cotan_operators(const Eigen::MatrixX3d& X, const std::vector<Eigen::Vector3i>& tris,
                                  bool with_gradient, double tol) {
  const int nv = int(X.rows());
  std::vector<Eigen::Vector3d> len(tris.size());
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      if (tris[t][k] < 0 || tris[t][k] >= nv)
        throw std::out_of_range("cotan_operators: triangle " + std::to_string(t) +
                                " has a vertex index out of range");
      len[t][k] = (X.row(tris[t][(k + 1) % 3]) - X.row(tris[t][k])).norm();
    }
  return assemble(nv, tris, len, with_gradient, tol, [&](int t, Eigen::Vector3d g[3]) {
    const Eigen::Matrix3d G =
        hat_gradients(X.row(tris[t][0]).transpose(), X.row(tris[t][1]).transpose(), X.row(tris[t][2]).transpose());
    for (int a = 0; a < 3; ++a) g[a] = G.col(a);
  });
}

TriangleOperators cotan_operators(const LengthTriangles& T, bool with_gradient, double tol) {
  if (T.triangles.size() != T.lengths.size())
    throw std::invalid_argument("cotan_operators: one length triple per triangle expected");
  return assemble(T.n_vertices, T.triangles, T.lengths, with_gradient, tol, [&](int t, Eigen::Vector3d g[3]) {
    // Layout: corner 0 at the origin, corner 1 at (l0, 0), corner 2 above the x axis.
    const Eigen::Vector3d& l = T.lengths[t];
    const double x2 = (l[0] * l[0] + l[2] * l[2] - l[1] * l[1]) / (2 * l[0]);
    const double y2 = 2 * triangle_area_from_lengths(l[0], l[1], l[2]) / l[0];
    const Eigen::Matrix3d G = hat_gradients(Eigen::Vector3d::Zero(), Eigen::Vector3d(l[0], 0, 0), Eigen::Vector3d(x2, y2, 0));
    for (int a = 0; a < 3; ++a) g[a] = G.col(a);
  });
}

}  // namespace polydec
