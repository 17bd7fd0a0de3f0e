// dec/volume_refinement.cpp — face and cell points of a polyhedral mesh and the classification
// of its sub-tetrahedra.
#include "polydec/dec/volume_refinement.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "polydec/dec/virtual_vertex.h"
#include "polydec/dec/volume_whitney.h"

namespace polydec {

namespace volume_refinement_detail {
namespace {

// The vertices of half-face hf in its outward order.
void halfface_vertices(const VolumeMesh& mesh, int hf, std::vector<int>& out) {
  const auto face = mesh.face(hf / 2);
  out.assign(face.begin(), face.end());
  if (hf & 1) std::reverse(out.begin(), out.end());
}

SubTet classify(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& f,
                const Eigen::Vector3d& c, double tolerance) {
  const double vol6 = 6.0 * tet_signed_volume(a, b, f, c);
  const double longest = std::max(
      {(b - a).norm(), (f - a).norm(), (c - a).norm(), (f - b).norm(), (c - b).norm(), (c - f).norm()});
  if (!(std::abs(vol6) > tolerance * longest * longest * longest)) return SubTet::Degenerate;
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

Eigen::Vector3d squared_volume_minimizer(const Eigen::MatrixX3d& A, const Eigen::MatrixX3d& B,
                                         const Eigen::MatrixX3d& C) {
  // vol(a, b, c, x) = n . (x - a) / 6 with n = (b - a) x (c - a): minimize sum (n_t . x - n_t . a_t)^2.
  const long T = A.rows();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (long t = 0; t < T; ++t) centre += (A.row(t) + B.row(t) + C.row(t)).transpose();
  centre /= double(3 * std::max<long>(T, 1));
  Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (long t = 0; t < T; ++t) {
    const Eigen::Vector3d a = A.row(t).transpose() - centre, b = B.row(t).transpose() - centre,
                          c = C.row(t).transpose() - centre;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    N += n * n.transpose();
    r += n * n.dot(a);
  }
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

Eigen::VectorXd least_norm_affine_weights(const Eigen::MatrixX3d& X, const Eigen::Vector3d& x) {
  const long m = X.rows();
  const Eigen::RowVector3d mean = X.colwise().mean();
  const Eigen::MatrixXd XcT = (X.rowwise() - mean).transpose();  // 3 x m
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(XcT);
  cod.setThreshold(1e-12);
  const Eigen::VectorXd v = cod.solve((x - mean.transpose()).eval());
  return Eigen::VectorXd::Constant(m, 1.0 / double(m)) + v;
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

  R.face_weights.resize(mesh.face_indices().size());
  R.face_points.resize(nF, 3);
  for (int f = 0; f < nF; ++f) {
    const auto face = mesh.face(f);
    PolygonPositions X(face.size(), 3);
    for (size_t k = 0; k < face.size(); ++k) X.row(k) = P.row(face[k]);
    const Eigen::VectorXd w = squared_area_weights(X);
    std::copy(w.data(), w.data() + w.size(), R.face_weights.begin() + mesh.face_offsets()[f]);
    R.face_points.row(f) = w.transpose() * X;
  }

  R.cell_points.resize(nC, 3);
  R.cell_weight_offsets.assign(1, 0);
  R.tet_offsets.assign(1, 0);
  std::vector<int> hv;
  for (int c = 0; c < nC; ++c) {
    const auto cell = mesh.cell(c);
    const auto verts = mesh.cell_vertices(c);
    const int m = int(verts.size());
    int n_tets = 0;
    for (int hf : cell) n_tets += mesh.face_size(hf / 2);
    Eigen::MatrixX3d A(n_tets, 3), B(n_tets, 3), C(n_tets, 3);
    int t = 0;
    for (int hf : cell) {
      halfface_vertices(mesh, hf, hv);
      const int n = int(hv.size());
      for (int i = 0; i < n; ++i, ++t) {
        A.row(t) = R.face_points.row(hf / 2);
        B.row(t) = P.row(hv[i]);
        C.row(t) = P.row(hv[(i + 1) % n]);
      }
    }
    const Eigen::Vector3d xc = squared_volume_minimizer(A, B, C);
    R.cell_points.row(c) = xc.transpose();

    Eigen::MatrixX3d X(m, 3);
    for (int k = 0; k < m; ++k) X.row(k) = P.row(verts[k]);
    Eigen::VectorXd w;
    if (options.cell_rule == CellPointRule::SquaredVolume) {
      w = least_norm_affine_weights(X, xc);
    } else {
      const int nf = int(cell.size());
      Eigen::MatrixX3d Q(nf + m, 3);
      for (int k = 0; k < nf; ++k) Q.row(k) = R.face_points.row(cell[k] / 2);
      Q.bottomRows(m) = X;
      const Eigen::VectorXd lambda = last_pinned_affine_weights(Q, xc);
      w = lambda.tail(m);
      for (int k = 0; k < nf; ++k) {
        const int f = cell[k] / 2;
        const auto face = mesh.face(f);
        const double* wf = R.face_weights.data() + mesh.face_offsets()[f];
        for (size_t i = 0; i < face.size(); ++i) {
          const int local = int(std::lower_bound(verts.begin(), verts.end(), face[i]) - verts.begin());
          w(local) += lambda(k) * wf[i];
        }
      }
    }
    R.cell_weights.insert(R.cell_weights.end(), w.data(), w.data() + m);
    R.cell_weight_offsets.push_back(int(R.cell_weights.size()));

    bool affected = false;
    for (int s = 0; s < n_tets; ++s) {
      const SubTet q = classify(B.row(s).transpose(), C.row(s).transpose(), A.row(s).transpose(), xc,
                                options.degenerate_tolerance);
      R.tets.push_back(q);
      if (q == SubTet::Degenerate) ++R.quality.n_degenerate;
      if (q == SubTet::Inverted) ++R.quality.n_inverted;
      affected = affected || q != SubTet::Valid;
    }
    if (affected) ++R.quality.n_cells_affected;
    R.tet_offsets.push_back(int(R.tets.size()));
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
