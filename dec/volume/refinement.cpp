// dec/volume/refinement.cpp — face and cell points of a polyhedral mesh and the classification
// of its sub-tetrahedra.
#include "polydec/dec/volume/refinement.h"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <array>
#include <cmath>
#include <span>
#include <stdexcept>

#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/detail/scale.h"
#include "polydec/dec/detail/threads.h"
#include "polydec/dec/surface/virtual_vertex.h"

namespace polydec {

namespace volume_refinement_detail {
namespace {

// The vertices of half-face hf in its outward order.
void halfface_vertices(const VolumeMesh& mesh, int hf, std::vector<int>& out) {
  const auto face = mesh.face(hf / 2);
  out.assign(face.begin(), face.end());
  if (hf & 1) std::reverse(out.begin(), out.end());
}

// Quality of a sub-tetrahedron (x_i, x_{i+1}, x_f, x_c) (face triangle in outward order, cell
// point x_c) from vol6 = 6 signed volume = ((x_i - x_f) x (x_{i+1} - x_f)) . (x_c - x_f) and its
// longest squared edge: degenerate when |vol6| <= tolerance * longest edge^3, compared squared
// (tol2 = tolerance^2, no square roots); inverted when x_c lies on the outer side of the face
// triangle: its normal points away from the cell, so a cell point inside gives vol6 < 0.
inline SubTet classify(double vol6, double longest2, double tol2) {
  if (!(vol6 * vol6 > tol2 * longest2 * longest2 * longest2)) return SubTet::Degenerate;
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

// A symmetric 3x3 matrix by its upper triangle (a00, a01, a02, a11, a12, a22).
using Sym3 = std::array<double, 6>;

Eigen::Matrix3d to_matrix(const Sym3& a) {
  Eigen::Matrix3d A;
  A << a[0], a[1], a[2], a[1], a[3], a[4], a[2], a[4], a[5];
  return A;
}

// Solves A x = b (A positive semi-definite) when lambda_min > tau lambda_max; false (x not
// written) otherwise. det A > tau trace(A)^3 implies the criterion without the eigenvalues (the
// usual case); failing that, the closed-form eigenvalues decide. When det A > 1e-6 trace(A)^3
// (condition number below 1e6) by the adjugate, x = adj(A) b / det A (one division, no chain of
// square roots), otherwise by Cholesky.
bool well_conditioned_solve(const Sym3& a, const double* b, double tau, double* x) {
  const double tr = a[0] + a[3] + a[5];
  const double c00 = a[3] * a[5] - a[4] * a[4], c01 = a[4] * a[2] - a[1] * a[5], c02 = a[1] * a[4] - a[3] * a[2];
  const double det = a[0] * c00 + a[1] * c01 + a[2] * c02;
  if (det > 1e-6 * tr * tr * tr && det > tau * tr * tr * tr) {
    const double c11 = a[0] * a[5] - a[2] * a[2], c12 = a[1] * a[2] - a[0] * a[4], c22 = a[0] * a[3] - a[1] * a[1];
    const double inv = 1 / det;
    x[0] = (c00 * b[0] + c01 * b[1] + c02 * b[2]) * inv;
    x[1] = (c01 * b[0] + c11 * b[1] + c12 * b[2]) * inv;
    x[2] = (c02 * b[0] + c12 * b[1] + c22 * b[2]) * inv;
    return true;
  }
  if (!(det > tau * tr * tr * tr)) {
    const Eigen::Matrix3d A = to_matrix(a);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(A, Eigen::EigenvaluesOnly);
    if (!(eig.eigenvalues()(0) > tau * eig.eigenvalues().cwiseAbs().maxCoeff())) return false;
    Eigen::Map<Eigen::Vector3d> solution(x);
    solution = A.llt().solve(Eigen::Map<const Eigen::Vector3d>(b));
    return true;
  }
  const double l00 = std::sqrt(a[0]), l10 = a[1] / l00, l20 = a[2] / l00;
  const double l11 = std::sqrt(a[3] - l10 * l10), l21 = (a[4] - l20 * l10) / l11;
  const double l22 = std::sqrt(a[5] - l20 * l20 - l21 * l21);
  const double y0 = b[0] / l00, y1 = (b[1] - l10 * y0) / l11, y2 = (b[2] - l20 * y0 - l21 * y1) / l22;
  x[2] = y2 / l22;
  x[1] = (y1 - l21 * x[2]) / l11;
  x[0] = (y0 - l10 * x[1] - l20 * x[2]) / l00;
  return true;
}

// The minimizer (offset from the centre) of sum_t (n_t . x - n_t . a_t)^2 from its normal
// equations N x = r (N = sum n_t n_t^T, r = sum n_t (n_t . a_t), coordinates centred).
Eigen::Vector3d solve_squared_volume(const Sym3& n, const Eigen::Vector3d& r) {
  // Well conditioned (the usual case, lambda_min > 1e-6 lambda_max): a Cholesky solve; otherwise
  // the eigen-decomposition's pseudo-inverse.
  Eigen::Vector3d x;
  if (well_conditioned_solve(n, r.data(), 1e-6, x.data())) return x;
  const Eigen::Matrix3d N = to_matrix(n);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(N);
  const Eigen::Vector3d lambda = eig.eigenvalues();
  const double top = lambda.cwiseAbs().maxCoeff();
  x.setZero();
  if (top > 0)
    for (int k = 0; k < 3; ++k)
      if (lambda(k) > 1e-12 * top)
        x += eig.eigenvectors().col(k) * (eig.eigenvectors().col(k).dot(r) / lambda(k));
  return x;
}

// Adds n n^T to the symmetric N.
inline void add_outer(Sym3& N, double n0, double n1, double n2) {
  N[0] += n0 * n0, N[1] += n0 * n1, N[2] += n0 * n2, N[3] += n1 * n1, N[4] += n1 * n2, N[5] += n2 * n2;
}

// The normal equations N x = r of min_x sum_t (n_t . x - n_t . a_t)^2, the sum of squared volumes
// vol(a_t, b_t, c_t, x) = n_t . (x - a_t) / 6 with n_t = (b_t - a_t) x (c_t - a_t).
struct SquaredVolumeSystem {
  Sym3 N{};
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  // Adds a triangle's normal n_t and its n_t . a_t.
  void add(double n0, double n1, double n2, double na) {
    add_outer(N, n0, n1, n2);
    r[0] += n0 * na, r[1] += n1 * na, r[2] += n2 * na;
  }
};

// Least-norm affine weights of the centred points Xc (m x 3, columns summing to zero) reproducing
// the offset y from their mean, written to w (m entries): w = 1/m + Xc^+ y.
void centred_affine_weights(const Eigen::MatrixX3d& Xc, const Eigen::Vector3d& y, double* w) {
  const long m = Xc.rows();
  // Full column rank (every 3D cell): Xc^+ = Xc (Xc^T Xc)^-1, through the 3x3 Gram matrix when it
  // is well conditioned (lambda_min > 1e-10 lambda_max: singular values within 1e-5 of each
  // other's scale, so the Gram's round-off stays near 1e-6 of the COD's threshold; det G > 1e-10
  // trace(G)^3 implies it without the eigenvalues); otherwise the decomposition below.
  Sym3 g{};
  const double *x0 = Xc.col(0).data(), *x1 = Xc.col(1).data(), *x2 = Xc.col(2).data();
  for (long k = 0; k < m; ++k) {
    g[0] += x0[k] * x0[k], g[1] += x0[k] * x1[k], g[2] += x0[k] * x2[k];
    g[3] += x1[k] * x1[k], g[4] += x1[k] * x2[k], g[5] += x2[k] * x2[k];
  }
  double z[3];
  if (well_conditioned_solve(g, y.data(), 1e-10, z)) {
    for (long k = 0; k < m; ++k) w[k] = 1.0 / double(m) + x0[k] * z[0] + x1[k] * z[1] + x2[k] * z[2];
    return;
  }
  const Eigen::MatrixXd XcT = Xc.transpose();  // 3 x m
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(XcT);
  cod.setThreshold(1e-12);
  const Eigen::VectorXd v = cod.solve(y);
  for (long k = 0; k < m; ++k) w[k] = 1.0 / double(m) + v[k];
}

}  // namespace
}  // namespace volume_refinement_detail

Eigen::Vector3d squared_volume_minimizer(const Eigen::MatrixX3d& A, const Eigen::MatrixX3d& B,
                                         const Eigen::MatrixX3d& C) {
  using namespace volume_refinement_detail;
  const long T = A.rows();
  const Eigen::RowVector3d centre = (A.colwise().sum() + B.colwise().sum() + C.colwise().sum()) / double(3 * std::max<long>(T, 1));
  SquaredVolumeSystem system;
  for (long t = 0; t < T; ++t) {
    const Eigen::RowVector3d a = A.row(t) - centre;
    const Eigen::RowVector3d n = (B.row(t) - A.row(t)).cross(C.row(t) - A.row(t));
    system.add(n[0], n[1], n[2], n.dot(a));
  }
  return centre.transpose() + solve_squared_volume(system.N, system.r);
}

Eigen::VectorXd least_norm_affine_weights(const Eigen::MatrixX3d& X, const Eigen::Vector3d& x) {
  Eigen::VectorXd w(X.rows());
  const Eigen::RowVector3d mean = X.colwise().mean();
  const Eigen::MatrixX3d Xc = X.rowwise() - mean;
  volume_refinement_detail::centred_affine_weights(Xc, (x - mean.transpose()).eval(), w.data());
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
  // Faces and cells are independent: T threads take chunks of them (results independent of T).
  const int T = std::min(resolve_threads(options.threads), std::max(1, nC / 2048));
  constexpr long kChunk = 2048;  // faces or cells a free thread takes at once (take_chunks)

  // The large arrays are advised to take huge pages before they are first written (first-touch
  // page faults dominate large meshes; dec/detail/huge_pages.h).
  assign_on_huge_pages(R.face_weights, mesh.face_indices().size());
  R.face_points.resize(nF, 3);
  advise_huge_pages(R.face_points.data(), sizeof(double) * 3 * size_t(nF));
  // Each face's moment N_f = sum_i n_i n_i^T of its fan triangles' normals
  // n_i = (x_i - x_f) x (x_{i+1} - x_f): the part of the cells' squared-volume normal equations
  // that the face contributes (below), the same for both of its cells (n_i changes sign with the
  // orientation), so computed once here.
  const auto moments = uninitialized_on_huge_pages<Sym3>(size_t(nF));  // every face's is written below
  const double planarity =
      options.planarity_tolerance > 0 ? options.planarity_tolerance : mesh.precision().planarity_tolerance;
  const double noise = mesh.coordinate_noise();
  // A face or cell far outside the ordinary sizes (dec/detail/scale.h) is computed in coordinates
  // scaled by 2^-e (e its exponent, 0 otherwise: then every factor below is 1 and the results are
  // those of the unscaled formulas bit for bit); a face's moment is kept in its own units, times
  // 2^-4e, with e in face_exponent.
  std::vector<short> face_exponent(size_t(nF), 0);
  std::atomic<long> next_face{0};
  run_on_threads(T, [&](int) {
    std::vector<double> corners, work, scaled;
    take_chunks(next_face, nF, kChunk, [&](int f) {
      const auto face = mesh.face(f);
      const int n = int(face.size());
      corners.resize(3 * size_t(n));
      work.resize(3 * size_t(n));
      for (int k = 0; k < n; ++k)
        for (int d = 0; d < 3; ++d) corners[3 * k + d] = P(face[k], d);
      PlanarityCut cut = planarity_cut(planarity, noise, corners.data(), n);
      // x_f = c + sum_k w_k (x_k - c) with c the corners' mean: far from the origin no digits are
      // lost, and a face in a coordinate plane keeps that coordinate exactly.
      double c[3] = {0, 0, 0}, x[3], extent = 0;
      for (int k = 0; k < n; ++k)
        for (int d = 0; d < 3; ++d) c[d] += corners[3 * k + d];
      for (int d = 0; d < 3; ++d) x[d] = c[d] /= n;
      for (int k = 0; k < n; ++k)
        for (int d = 0; d < 3; ++d) extent = std::fmax(extent, std::fabs(corners[3 * k + d] - c[d]));
      const int e = detail::normalizing_exponent(extent);
      const double inv = std::ldexp(1.0, -e);
      double* w = R.face_weights.data() + mesh.face_offsets()[f];
      if (e == 0) {
        squared_area_weights(corners.data(), n, w, work.data(), cut);
      } else {
        // The weights are affine: the same for the centred corners scaled by 2^-e (and the noise with them).
        scaled.resize(3 * size_t(n));
        for (int k = 0; k < n; ++k)
          for (int d = 0; d < 3; ++d) scaled[3 * k + d] = (corners[3 * k + d] - c[d]) * inv;
        if (cut.relative <= 0) cut.noise *= inv;
        squared_area_weights(scaled.data(), n, w, work.data(), cut);
      }
      for (int k = 0; k < n; ++k)
        for (int d = 0; d < 3; ++d) x[d] += w[k] * (corners[3 * k + d] - c[d]);
      for (int d = 0; d < 3; ++d) R.face_points(f, d) = x[d];
      Sym3 Nf{};
      const double* last = corners.data() + 3 * (n - 1);
      double a0 = (last[0] - x[0]) * inv, a1 = (last[1] - x[1]) * inv, a2 = (last[2] - x[2]) * inv;
      for (int k = 0; k < n; ++k) {
        const double b0 = (corners[3 * k] - x[0]) * inv, b1 = (corners[3 * k + 1] - x[1]) * inv,
                     b2 = (corners[3 * k + 2] - x[2]) * inv;
        add_outer(Nf, a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0);
        a0 = b0, a1 = b1, a2 = b2;
      }
      moments[size_t(f)] = Nf;
      face_exponent[size_t(f)] = short(e);
    });
  });

  R.cell_points.resize(nC, 3);
  advise_huge_pages(R.cell_points.data(), sizeof(double) * 3 * size_t(nC));
  assign_on_huge_pages(R.cell_weight_offsets, size_t(nC) + 1);
  assign_on_huge_pages(R.tet_offsets, size_t(nC) + 1);
  for (int c = 0; c < nC; ++c) {
    int n_tets = 0;
    for (int hf : mesh.cell(c)) n_tets += mesh.face_size(hf / 2);
    R.tet_offsets[c + 1] = R.tet_offsets[c] + n_tets;
    R.cell_weight_offsets[c + 1] = R.cell_weight_offsets[c] + int(mesh.cell_vertices(c).size());
  }
  assign_on_huge_pages(R.cell_weights, size_t(R.cell_weight_offsets[nC]));
  assign_on_huge_pages(R.tets, size_t(R.tet_offsets[nC]));
  std::vector<SubTetQuality> quality(T);
  // One cell, in coordinates relative to the mean o of its vertices. The squared-volume normal
  // equations are N x = r with N = sum_f N_f and r = sum_f N_f (x_f - o) (6 vol of a sub-tetrahedron
  // is n_i . (x - x_f)). The classification computes each sub-tetrahedron's 6 vol = n_i . (x_c - x_f);
  // its longest squared edge (classify()) only when 6 vol is below the tolerance for a bound of
  // every edge of the cell's refinement: (2 R)^2, R the largest distance of a corner, face point
  // or the cell point from o (taken as 4.5 R^2 to absorb the round-off).
  const double *P0 = P.col(0).data(), *P1 = P.col(1).data(), *P2 = P.col(2).data();
  const double *F0 = R.face_points.col(0).data(), *F1 = R.face_points.col(1).data(),
               *F2 = R.face_points.col(2).data();
  std::atomic<long> next_cell{0};
  run_on_threads(T, [&](int thread) {
    Eigen::MatrixX3d X, Xc;  // reused: no allocation per cell of the same size
    SubTetQuality& Q = quality[thread];
    const double tol2 = options.degenerate_tolerance * options.degenerate_tolerance;
    take_chunks(next_cell, nC, kChunk, [&](int c) {
      const auto cell = mesh.cell(c);
      const auto verts = mesh.cell_vertices(c);
      const int m = int(verts.size());
      double o[3] = {0, 0, 0};
      for (int v : verts) o[0] += P0[v], o[1] += P1[v], o[2] += P2[v];
      for (double& x : o) x /= double(m);
      Xc.resize(m, 3);
      double extent = 0;
      for (int k = 0; k < m; ++k) {
        const double y0 = P0[verts[k]] - o[0], y1 = P1[verts[k]] - o[1], y2 = P2[verts[k]] - o[2];
        Xc(k, 0) = y0, Xc(k, 1) = y1, Xc(k, 2) = y2;
        extent = std::fmax(extent, std::fmax(std::fabs(y0), std::fmax(std::fabs(y1), std::fabs(y2))));
      }
      // The cell in units of 2^e (e = 0 for ordinary sizes): relative coordinates times inv,
      // a face's moment (kept in units of 2^e_f) times 2^(4 (e_f - e)).
      const int e = detail::normalizing_exponent(extent);
      const double inv = std::ldexp(1.0, -e);
      double R2 = 0;
      for (int k = 0; k < m; ++k) {
        const double y0 = Xc(k, 0) *= inv, y1 = Xc(k, 1) *= inv, y2 = Xc(k, 2) *= inv;
        R2 = std::max(R2, y0 * y0 + y1 * y1 + y2 * y2);
      }
      Sym3 N{};
      double r[3] = {0, 0, 0};
      for (int hf : cell) {
        const int f = hf / 2;
        const Sym3& A = moments[size_t(f)];
        const double to_cell = std::ldexp(1.0, 4 * (face_exponent[size_t(f)] - e));
        const double q0 = (F0[f] - o[0]) * inv, q1 = (F1[f] - o[1]) * inv, q2 = (F2[f] - o[2]) * inv;
        double a[6];
        for (int k = 0; k < 6; ++k) N[k] += a[k] = A[k] * to_cell;
        r[0] += a[0] * q0 + a[1] * q1 + a[2] * q2;
        r[1] += a[1] * q0 + a[3] * q1 + a[4] * q2;
        r[2] += a[2] * q0 + a[4] * q1 + a[5] * q2;
        R2 = std::max(R2, q0 * q0 + q1 * q1 + q2 * q2);
      }
      const Eigen::Vector3d xc = solve_squared_volume(N, Eigen::Vector3d(r[0], r[1], r[2]));
      const double unit = std::ldexp(1.0, e);
      for (int d = 0; d < 3; ++d) R.cell_points(c, d) = o[d] + xc[d] * unit;

      double* w = R.cell_weights.data() + R.cell_weight_offsets[c];
      if (options.cell_rule == CellPointRule::SquaredVolume) {
        centred_affine_weights(Xc, xc, w);
      } else {
        // Unscaled cells in the mesh's coordinates (as polyLaplace), scaled ones relative to o
        // (affine weights do not change).
        const Eigen::RowVector3d origin = e == 0 ? Eigen::RowVector3d(o[0], o[1], o[2]) : Eigen::RowVector3d::Zero();
        X = Xc.rowwise() + origin;
        const int nf = int(cell.size());
        Eigen::MatrixX3d Qp(nf + m, 3);
        for (int k = 0; k < nf; ++k) {
          const int f = cell[k] / 2;
          if (e == 0) Qp.row(k) = R.face_points.row(f);
          else Qp.row(k) << (F0[f] - o[0]) * inv, (F1[f] - o[1]) * inv, (F2[f] - o[2]) * inv;
        }
        Qp.bottomRows(m) = X;
        const Eigen::VectorXd lambda = last_pinned_affine_weights(Qp, origin.transpose() + xc);
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
      SubTet* flag = R.tets.data() + R.tet_offsets[c];
      const double x0 = xc[0], x1 = xc[1], x2 = xc[2];
      R2 = std::max(R2, x0 * x0 + x1 * x1 + x2 * x2);
      const double bound = 4.5 * R2, clear = tol2 * bound * bound * bound;
      for (int hf : cell) {
        const int f = hf / 2;
        const auto face = mesh.face(f);
        const int n = int(face.size());
        const double q0 = (F0[f] - o[0]) * inv, q1 = (F1[f] - o[1]) * inv, q2 = (F2[f] - o[2]) * inv;
        const double h0 = x0 - q0, h1 = x1 - q1, h2 = x2 - q2;
        // Corner i in outward order, relative to o (half-face 2f + 1 runs against the face).
        auto corner = [&](int i, double* y) {
          const int v = hf & 1 ? face[n - 1 - i] : face[i];
          y[0] = (P0[v] - o[0]) * inv, y[1] = (P1[v] - o[1]) * inv, y[2] = (P2[v] - o[2]) * inv;
        };
        double a[3], b[3];
        corner(0, a);
        double ua0 = a[0] - q0, ua1 = a[1] - q1, ua2 = a[2] - q2;
        for (int i = 0; i < n; ++i, ++flag) {
          corner(i + 1 == n ? 0 : i + 1, b);
          const double ub0 = b[0] - q0, ub1 = b[1] - q1, ub2 = b[2] - q2;
          const double m0 = ua1 * ub2 - ua2 * ub1, m1 = ua2 * ub0 - ua0 * ub2, m2 = ua0 * ub1 - ua1 * ub0;
          const double vol6 = m0 * h0 + m1 * h1 + m2 * h2;
          if (vol6 < 0 && vol6 * vol6 > clear) {  // the usual case: valid, nothing to count
            *flag = SubTet::Valid;
          } else {
            if (vol6 * vol6 > clear) {
              *flag = SubTet::Inverted;
            } else {
              auto d2 = [](double e0, double e1, double e2) { return e0 * e0 + e1 * e1 + e2 * e2; };
              const double longest2 = std::max({d2(b[0] - a[0], b[1] - a[1], b[2] - a[2]), d2(ua0, ua1, ua2),
                                                d2(ub0, ub1, ub2), d2(x0 - a[0], x1 - a[1], x2 - a[2]),
                                                d2(x0 - b[0], x1 - b[1], x2 - b[2]), d2(h0, h1, h2)});
              *flag = classify(vol6, longest2, tol2);
            }
            if (*flag == SubTet::Degenerate) ++Q.n_degenerate;
            if (*flag == SubTet::Inverted) ++Q.n_inverted;
            affected = affected || *flag != SubTet::Valid;
          }
          a[0] = b[0], a[1] = b[1], a[2] = b[2];
          ua0 = ub0, ua1 = ub1, ua2 = ub2;
        }
      }
      if (affected) ++Q.n_cells_affected;
    });
  });
  for (const SubTetQuality& q : quality) {
    R.quality.n_degenerate += q.n_degenerate;
    R.quality.n_inverted += q.n_inverted;
    R.quality.n_cells_affected += q.n_cells_affected;
  }
  return R;
}

std::vector<RefinedTet> refined_tets(const VolumeMesh& mesh, const VolumeRefinement& refinement) {
  check_refinement(mesh, refinement, "refined_tets");
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
  const int nV = mesh.n_vertices(), nF = mesh.n_faces(), nC = mesh.n_cells();
  // Called per sub-tetrahedron corner in the operators' loops: the message only on the failure path.
  if (r < 0 || r >= nV + nF + nC || refinement.face_points.rows() != nF || refinement.cell_points.rows() != nC)
    check_refined_vertex(mesh, refinement, r, "refined_position");
  if (r < nV) return mesh.position(r);
  if (r < nV + nF) return refinement.face_points.row(r - nV).transpose();
  return refinement.cell_points.row(r - nV - nF).transpose();
}

}  // namespace polydec
