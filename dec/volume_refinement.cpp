// dec/volume_refinement.cpp — face and cell points of a polyhedral mesh and the classification
// of its sub-tetrahedra.
#include "polydec/dec/volume_refinement.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "polydec/dec/threads.h"
#include "polydec/dec/virtual_vertex.h"

namespace polydec {

namespace volume_refinement_detail {
namespace {

// The vertices of half-face hf in its outward order.
void halfface_vertices(const VolumeMesh& mesh, int hf, std::vector<int>& out) {
  const auto face = mesh.face(hf / 2);
  out.assign(face.begin(), face.end());
  if (hf & 1) std::reverse(out.begin(), out.end());
}

// Quality of the sub-tetrahedron (a, b, f, c) (face triangle (a, b, f) in outward order, cell point
// c): degenerate when 6 |vol| <= tolerance * longest edge^3, compared squared (tol2 = tolerance^2,
// no square roots); inverted when c lies on the outer side of the face triangle.
inline SubTet classify(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& f,
                       const Eigen::Vector3d& c, double tol2) {
  const double vol6 = (b - a).dot((f - a).cross(c - a));  // 6 tet_signed_volume(a, b, f, c)
  const double longest2 = std::max({(b - a).squaredNorm(), (f - a).squaredNorm(), (c - a).squaredNorm(),
                                    (f - b).squaredNorm(), (c - b).squaredNorm(), (c - f).squaredNorm()});
  if (!(vol6 * vol6 > tol2 * longest2 * longest2 * longest2)) return SubTet::Degenerate;
  // Outward face triangle (a, b, f): its normal n = (b - a) x (f - a) points away from the cell,
  // so a cell point inside gives n . (c - a) < 0, i.e. vol6 < 0.
  return vol6 < 0 ? SubTet::Valid : SubTet::Inverted;
}

}  // namespace
}  // namespace volume_refinement_detail

CellPointRule parse_cell_point_rule(const std::string& name) {
  if (name == "squared-volume") return CellPointRule::SquaredVolume;
  if (name == "polylaplace") return CellPointRule::PolyLaplace;
  throw std::invalid_argument("unknown cell point rule '" + name + "' (squared-volume, polylaplace)");
}

std::string to_string(CellPointRule rule) {
  return rule == CellPointRule::PolyLaplace ? "polylaplace" : "squared-volume";
}

namespace volume_refinement_detail {
namespace {

// The squared-volume minimizer (squared_volume_minimizer()) of the triangles that
// for_each_triangle(visit) passes to visit(a, b, c), in the same order on each call.
template <class ForEachTriangle>
Eigen::Vector3d squared_volume_point(ForEachTriangle&& for_each_triangle) {
  // vol(a, b, c, x) = n . (x - a) / 6 with n = (b - a) x (c - a): minimize sum (n_t . x - n_t . a_t)^2.
  long T = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for_each_triangle([&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    centre += a + b + c;
    ++T;
  });
  centre /= double(3 * std::max<long>(T, 1));
  Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for_each_triangle([&](const Eigen::Vector3d& at, const Eigen::Vector3d& bt, const Eigen::Vector3d& ct) {
    const Eigen::Vector3d a = at - centre, b = bt - centre, c = ct - centre;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    N += n * n.transpose();
    r += n * n.dot(a);
  });
  // Well conditioned (the usual case): a Cholesky solve. det N > 1e-6 trace(N)^3 implies
  // lambda_min >= det / trace^2 > 1e-6 lambda_max without the eigenvalues; otherwise the
  // closed-form eigenvalues decide.
  const double tr = N.trace();
  if (N.determinant() > 1e-6 * tr * tr * tr) return centre + N.llt().solve(r);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> direct;
  direct.computeDirect(N, Eigen::EigenvaluesOnly);
  if (direct.eigenvalues()(0) > 1e-6 * direct.eigenvalues().cwiseAbs().maxCoeff())
    return centre + N.llt().solve(r);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(N);
  const Eigen::Vector3d lambda = eig.eigenvalues();
  const double top = lambda.cwiseAbs().maxCoeff();
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  if (top > 0)
    for (int k = 0; k < 3; ++k)
      if (lambda(k) > 1e-12 * top)
        x += eig.eigenvectors().col(k) * (eig.eigenvectors().col(k).dot(r) / lambda(k));
  return centre + x;
}

// Least-norm affine weights of the points X (m x 3) reproducing x, written to w (m entries);
// Xc is scratch (least_norm_affine_weights()).
void affine_weights_into(const Eigen::MatrixX3d& X, const Eigen::Vector3d& x, double* w, Eigen::MatrixX3d& Xc) {
  const long m = X.rows();
  const Eigen::RowVector3d mean = X.colwise().mean();
  Xc = X.rowwise() - mean;
  // Full column rank (every 3D cell): Xc^+ = Xc (Xc^T Xc)^-1, through the 3x3 Gram matrix when it
  // is well conditioned (lambda_min > 1e-10 lambda_max: singular values within 1e-5 of each
  // other's scale, so the Gram's round-off stays near 1e-6 of the COD's threshold; det G > 1e-10
  // trace(G)^3 implies it without the eigenvalues); otherwise the decomposition below.
  Eigen::Matrix3d G;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) G(i, j) = G(j, i) = Xc.col(i).dot(Xc.col(j));
  const double tr = G.trace();
  bool gram = G.determinant() > 1e-10 * tr * tr * tr;
  if (!gram) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(G, Eigen::EigenvaluesOnly);
    gram = eig.eigenvalues()(0) > 1e-10 * eig.eigenvalues()(2);
  }
  if (gram) {
    const Eigen::Vector3d y = G.llt().solve((x - mean.transpose()).eval());
    for (long k = 0; k < m; ++k) w[k] = 1.0 / double(m) + Xc.row(k).dot(y);
    return;
  }
  const Eigen::MatrixXd XcT = Xc.transpose();  // 3 x m
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(XcT);
  cod.setThreshold(1e-12);
  const Eigen::VectorXd v = cod.solve((x - mean.transpose()).eval());
  for (long k = 0; k < m; ++k) w[k] = 1.0 / double(m) + v[k];
}

// Calls visit(x_f, x_i, x_{i+1}) for the sub-tetrahedra of cell c in VolumeRefinement::tets
// order: over the cell's half-faces and, within one, over its edges (i, i + 1) in outward order.
template <class Visit>
void for_each_cell_triangle(const VolumeMesh& mesh, const Eigen::MatrixX3d& face_points, int c, Visit&& visit) {
  const auto& P = mesh.positions();
  for (int hf : mesh.cell(c)) {
    const auto face = mesh.face(hf / 2);
    const int n = int(face.size());
    const Eigen::Vector3d xf = face_points.row(hf / 2).transpose();
    for (int i = 0; i < n; ++i) {
      // Half-face 2f + 1 runs against the face: its i-th vertex is face[n - 1 - i].
      const int j = i + 1 == n ? 0 : i + 1;
      const int u = hf & 1 ? face[n - 1 - i] : face[i], v = hf & 1 ? face[n - 1 - j] : face[j];
      visit(xf, Eigen::Vector3d(P(u, 0), P(u, 1), P(u, 2)), Eigen::Vector3d(P(v, 0), P(v, 1), P(v, 2)));
    }
  }
}

}  // namespace
}  // namespace volume_refinement_detail

Eigen::Vector3d squared_volume_minimizer(const Eigen::MatrixX3d& A, const Eigen::MatrixX3d& B,
                                         const Eigen::MatrixX3d& C) {
  return volume_refinement_detail::squared_volume_point([&](auto&& visit) {
    for (long t = 0; t < A.rows(); ++t)
      visit(A.row(t).transpose(), B.row(t).transpose(), C.row(t).transpose());
  });
}

Eigen::VectorXd least_norm_affine_weights(const Eigen::MatrixX3d& X, const Eigen::Vector3d& x) {
  Eigen::VectorXd w(X.rows());
  Eigen::MatrixX3d Xc;
  volume_refinement_detail::affine_weights_into(X, x, w.data(), Xc);
  return w;
}

Eigen::VectorXd last_pinned_affine_weights(const Eigen::MatrixX3d& Q, const Eigen::Vector3d& x) {
  const long k = Q.rows();
  const Eigen::Vector3d last = Q.row(k - 1).transpose();
  Eigen::MatrixXd D(3, k - 1);
  for (long j = 0; j + 1 < k; ++j) D.col(j) = Q.row(j).transpose() - last;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(D);
  cod.setThreshold(1e-12);
  const Eigen::VectorXd w = cod.solve((x - last).eval());
  Eigen::VectorXd out(k);
  out.head(k - 1) = w;
  out(k - 1) = 1.0 - w.sum();
  return out;
}

VolumeRefinement refine_volume(const VolumeMesh& mesh, const VolumeRefinementOptions& options) {
  using namespace volume_refinement_detail;
  VolumeRefinement R;
  R.options = options;
  const int nF = mesh.n_faces(), nC = mesh.n_cells();
  const auto& P = mesh.positions();
  // Faces and cells are independent: T threads take contiguous ranges (results independent of T).
  const int T = std::min(resolve_threads(options.threads), std::max(1, nC / 2048));

  R.face_weights.resize(mesh.face_indices().size());
  R.face_points.resize(nF, 3);
  const double planarity =
      options.planarity_tolerance > 0 ? options.planarity_tolerance : mesh.precision().planarity_tolerance;
  const double noise = mesh.coordinate_noise();
  run_on_threads(T, [&](int t) {
    std::vector<double> corners, work;
    for (int f = int(long(nF) * t / T); f < int(long(nF) * (t + 1) / T); ++f) {
      const auto face = mesh.face(f);
      const int n = int(face.size());
      corners.resize(3 * size_t(n));
      work.resize(3 * size_t(n));
      for (int k = 0; k < n; ++k)
        for (int d = 0; d < 3; ++d) corners[3 * k + d] = P(face[k], d);
      double* w = R.face_weights.data() + mesh.face_offsets()[f];
      squared_area_weights(corners.data(), n, w, work.data(),
                           planarity_cut(planarity, noise, corners.data(), n));
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int k = 0; k < n; ++k) x += w[k] * Eigen::Vector3d(corners[3 * k], corners[3 * k + 1], corners[3 * k + 2]);
      R.face_points.row(f) = x.transpose();
    }
  });

  R.cell_points.resize(nC, 3);
  R.cell_weight_offsets.assign(size_t(nC) + 1, 0);
  R.tet_offsets.assign(size_t(nC) + 1, 0);
  for (int c = 0; c < nC; ++c) {
    int n_tets = 0;
    for (int hf : mesh.cell(c)) n_tets += mesh.face_size(hf / 2);
    R.tet_offsets[c + 1] = R.tet_offsets[c] + n_tets;
    R.cell_weight_offsets[c + 1] = R.cell_weight_offsets[c] + int(mesh.cell_vertices(c).size());
  }
  R.cell_weights.resize(size_t(R.cell_weight_offsets[nC]));
  R.tets.resize(size_t(R.tet_offsets[nC]));
  std::vector<SubTetQuality> quality(T);
  run_on_threads(T, [&](int thread) {
    Eigen::MatrixX3d X, Xc;  // reused: no allocation per cell of the same size
    SubTetQuality& Q = quality[thread];
    const double tol2 = options.degenerate_tolerance * options.degenerate_tolerance;
    for (int c = int(long(nC) * thread / T); c < int(long(nC) * (thread + 1) / T); ++c) {
      const auto cell = mesh.cell(c);
      const auto verts = mesh.cell_vertices(c);
      const int m = int(verts.size());
      const Eigen::Vector3d xc = squared_volume_point(
          [&](auto&& visit) { for_each_cell_triangle(mesh, R.face_points, c, visit); });
      R.cell_points.row(c) = xc.transpose();

      X.resize(m, 3);
      for (int k = 0; k < m; ++k) X.row(k) = P.row(verts[k]);
      double* w = R.cell_weights.data() + R.cell_weight_offsets[c];
      if (options.cell_rule == CellPointRule::SquaredVolume) {
        affine_weights_into(X, xc, w, Xc);
      } else {
        const int nf = int(cell.size());
        Eigen::MatrixX3d Qp(nf + m, 3);
        for (int k = 0; k < nf; ++k) Qp.row(k) = R.face_points.row(cell[k] / 2);
        Qp.bottomRows(m) = X;
        const Eigen::VectorXd lambda = last_pinned_affine_weights(Qp, xc);
        for (int k = 0; k < m; ++k) w[k] = lambda(nf + k);
        for (int k = 0; k < nf; ++k) {
          const int f = cell[k] / 2;
          const auto face = mesh.face(f);
          const double* wf = R.face_weights.data() + mesh.face_offsets()[f];
          for (size_t i = 0; i < face.size(); ++i) {
            const int local = int(std::lower_bound(verts.begin(), verts.end(), face[i]) - verts.begin());
            w[local] += lambda(k) * wf[i];
          }
        }
      }

      bool affected = false;
      SubTet* q = R.tets.data() + R.tet_offsets[c];
      for_each_cell_triangle(mesh, R.face_points, c,
                             [&](const Eigen::Vector3d& f, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
                               *q = classify(a, b, f, xc, tol2);
                               if (*q == SubTet::Degenerate) ++Q.n_degenerate;
                               if (*q == SubTet::Inverted) ++Q.n_inverted;
                               affected = affected || *q != SubTet::Valid;
                               ++q;
                             });
      if (affected) ++Q.n_cells_affected;
    }
  });
  for (const SubTetQuality& q : quality) {
    R.quality.n_degenerate += q.n_degenerate;
    R.quality.n_inverted += q.n_inverted;
    R.quality.n_cells_affected += q.n_cells_affected;
  }
  return R;
}

std::vector<RefinedTet> refined_tets(const VolumeMesh& mesh, const VolumeRefinement& refinement) {
  using namespace volume_refinement_detail;
  std::vector<RefinedTet> out;
  out.reserve(refinement.tets.size());
  const int nV = mesh.n_vertices(), nF = mesh.n_faces();
  std::vector<int> hv;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    int t = refinement.tet_offsets[c];
    for (int hf : mesh.cell(c)) {
      halfface_vertices(mesh, hf, hv);
      const int n = int(hv.size());
      for (int i = 0; i < n; ++i, ++t)
        out.push_back({{hv[i], hv[(i + 1) % n], nV + hf / 2, nV + nF + c}, refinement.tets[t]});
    }
  }
  return out;
}

Eigen::Vector3d refined_position(const VolumeMesh& mesh, const VolumeRefinement& refinement, int r) {
  const int nV = mesh.n_vertices(), nF = mesh.n_faces();
  if (r < nV) return mesh.position(r);
  if (r < nV + nF) return refinement.face_points.row(r - nV).transpose();
  return refinement.cell_points.row(r - nV - nF).transpose();
}

}  // namespace polydec
