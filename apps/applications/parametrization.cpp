// apps/applications/parametrization.cpp — spectral conformal parametrization via the boundary Schur complement.
#include "polydec/apps/applications/parametrization.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/operators/solvers/cholesky.h"

namespace polydec {

ConformalParametrization spectral_conformal_parametrization(const OperatorSet& ops) {
  const Mesh& mesh = ops.domain;
  const int nv = mesh.n_vertices();
  // Boundary / interior numbering; vertices in no face take no part.
  std::vector<int> bidx(nv, -1), iidx(nv, -1), bverts, iverts;
  for (int v = 0; v < nv; ++v) {
    if (mesh.vertex_faces(v).empty()) continue;
    if (mesh.is_boundary_vertex(v)) {
      bidx[v] = int(bverts.size());
      bverts.push_back(v);
    } else {
      iidx[v] = int(iverts.size());
      iverts.push_back(v);
    }
  }
  const int nb = int(bverts.size()), ni = int(iverts.size());
  if (nb == 0) throw std::invalid_argument("spectral conformal parametrization: the mesh has no boundary");

  // -S split into interior/boundary blocks.
  std::vector<Eigen::Triplet<double>> tII, tIB;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nb, nb);  // becomes the Schur complement of -S onto the boundary
  for (int j = 0; j < ops.S.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(ops.S, j); it; ++it) {
      const int r = int(it.row());
      const double a = -it.value();
      if (iidx[r] >= 0 && iidx[j] >= 0) tII.emplace_back(iidx[r], iidx[j], a);
      if (iidx[r] >= 0 && bidx[j] >= 0) tIB.emplace_back(iidx[r], bidx[j], a);
      if (bidx[r] >= 0 && bidx[j] >= 0) K(bidx[r], bidx[j]) += a;
    }
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(ni, nb);  // U_I = -(-S_II)^-1 (-S_IB) U_B = X U_B (per component)
  if (ni > 0) {
    SparseMatrix SII(ni, ni), SIB(ni, nb);
    SII.setFromTriplets(tII.begin(), tII.end());
    SIB.setFromTriplets(tIB.begin(), tIB.end());
    // Each component with interior vertices must touch the boundary, else -S_II is singular.
    const SparseCholesky chol(SII, "-S on the interior vertices (conformal parametrization)");
    X = -chol.solve(Eigen::MatrixXd(SIB));
    K += Eigen::MatrixXd(SIB.transpose()) * X;  // K = -S_BB - S_BI S_II^-1 S_IB, with signs of -S
  }
  // Schur complement of L_C = diag(-S, -S) - A on the boundary: [K 0; 0 K] - A_BB.
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(2 * nb, 2 * nb);
  C.topLeftCorner(nb, nb) = K;
  C.bottomRightCorner(nb, nb) = K;
  for (const auto& loop : mesh.boundary_loops())
    for (size_t a = 0; a < loop.size(); ++a) {
      const int i = bidx[loop[a]], j = bidx[loop[(a + 1) % loop.size()]];
      // U^T A U = sum (u_i v_j - u_j v_i): symmetric entries of 1/2.
      C(i, nb + j) -= 0.5;
      C(nb + j, i) -= 0.5;
      C(j, nb + i) += 0.5;
      C(nb + i, j) += 0.5;
    }
  // The translations (constant u or v on the boundary of one connected component) are exact
  // null vectors of C; Mullen et al. constrain U to be B-orthogonal to them. Solve in their
  // orthogonal complement (B is the identity on the boundary), so that a flat mesh, whose
  // similarity maps are null vectors too, cannot return a translation.
  std::vector<int> comp(nv, -1);
  int n_comp = 0;
  for (int s = 0; s < nv; ++s) {
    if (comp[s] >= 0 || mesh.vertex_faces(s).empty()) continue;
    std::vector<int> stack{s};
    comp[s] = n_comp;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int f : mesh.vertex_faces(v))
        for (int u : mesh.face(f))
          if (comp[u] < 0) {
            comp[u] = n_comp;
            stack.push_back(u);
          }
    }
    ++n_comp;
  }
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(2 * nb, 2 * n_comp);
  for (int k = 0; k < nb; ++k) {
    T(k, 2 * comp[bverts[k]]) = 1.0;
    T(nb + k, 2 * comp[bverts[k]] + 1) = 1.0;
  }
  for (int c = 0; c < 2 * n_comp; ++c) {
    const double len = T.col(c).norm();
    if (!(len > 0))
      throw std::invalid_argument(
          "spectral conformal parametrization: a connected component has no boundary");
    T.col(c) /= len;
  }
  if (2 * n_comp >= 2 * nb)
    throw std::invalid_argument("spectral conformal parametrization: too few boundary vertices");
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(T);
  const Eigen::MatrixXd Qfull = qr.householderQ();
  const Eigen::MatrixXd Q = Qfull.rightCols(2 * nb - 2 * n_comp);
  const Eigen::MatrixXd Cq = Q.transpose() * C * Q;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (Cq + Cq.transpose()));
  if (eig.info() != Eigen::Success)
    throw SolverError("spectral conformal parametrization: eigensolver failed");
  const Eigen::VectorXd UB = Q * eig.eigenvectors().col(0);

  ConformalParametrization p;
  p.eigenvalue = eig.eigenvalues()[0];
  p.uv = Eigen::MatrixX2d::Zero(nv, 2);
  for (int k = 0; k < nb; ++k) p.uv.row(bverts[k]) << UB[k], UB[nb + k];
  if (ni > 0) {
    const Eigen::MatrixXd UI = X * Eigen::MatrixXd(p.uv(bverts, Eigen::all));
    for (int k = 0; k < ni; ++k) p.uv.row(iverts[k]) = UI.row(k);
  }
  // Into [0,1]^2 with the aspect ratio kept.
  std::vector<int> used(bverts);
  used.insert(used.end(), iverts.begin(), iverts.end());
  const Eigen::RowVector2d lo = p.uv(used, Eigen::all).colwise().minCoeff();
  const Eigen::RowVector2d hi = p.uv(used, Eigen::all).colwise().maxCoeff();
  const double extent = (hi - lo).maxCoeff();
  if (!(extent > 0))
    throw SolverError("spectral conformal parametrization: the parametrization collapsed to a point");
  for (int v : used) p.uv.row(v) = (p.uv.row(v) - lo) / extent;
  return p;
}

ConformalParametrization spectral_conformal_parametrization(const Mesh& mesh) {
  return spectral_conformal_parametrization(build_operators(mesh, parse_laplacian("ours"), false));
}

namespace {

// Calls visit(vertex, weight, alpha - beta) for every face corner (see conformal_distortion);
// `target` holds the deformed positions (a uv map embedded with z = 0).
template <class Visit>
void for_each_corner_angle_difference(const Mesh& mesh, const Eigen::MatrixX3d& target, Visit&& visit) {
  if (target.rows() != mesh.n_vertices())
    throw std::invalid_argument("conformal distortion: the deformed positions need one row per vertex");
  auto angle = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); };
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size());
    Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();
    for (int a = 0; a < n; ++a) vector_area += mesh.position(face[a]).cross(mesh.position(face[(a + 1) % n]));
    const double w = 0.5 * vector_area.norm() / n;
    for (int a = 0; a < n; ++a) {
      const int i = face[a], j = face[(a + 1) % n], k = face[(a + n - 1) % n];
      const double alpha = angle(mesh.position(j) - mesh.position(i), mesh.position(k) - mesh.position(i));
      const Eigen::Vector3d p = target.row(i).transpose();
      const double beta = angle(target.row(j).transpose() - p, target.row(k).transpose() - p);
      visit(i, w, alpha - beta);
    }
  }
}

Eigen::MatrixX3d embed(const Eigen::MatrixX2d& uv) {
  Eigen::MatrixX3d X = Eigen::MatrixX3d::Zero(uv.rows(), 3);
  X.leftCols(2) = uv;
  return X;
}

}  // namespace

double conformal_distortion(const Mesh& mesh, const Eigen::MatrixX3d& deformed) {
  double sum = 0, wsum = 0;
  for_each_corner_angle_difference(mesh, deformed, [&](int, double w, double d) {
    sum += w * d * d;
    wsum += w;
  });
  return wsum > 0 ? std::sqrt(sum / wsum) : 0.0;
}

double conformal_distortion(const Mesh& mesh, const Eigen::MatrixX2d& uv) {
  if (uv.rows() != mesh.n_vertices()) throw std::invalid_argument("conformal distortion: uv needs one row per vertex");
  return conformal_distortion(mesh, embed(uv));
}

Eigen::VectorXd vertex_conformal_distortion(const Mesh& mesh, const Eigen::MatrixX2d& uv) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(mesh.n_vertices()), wsum = sum;
  if (uv.rows() != mesh.n_vertices()) throw std::invalid_argument("conformal distortion: uv needs one row per vertex");
  for_each_corner_angle_difference(mesh, embed(uv), [&](int v, double w, double d) {
    sum[v] += w * d * d;
    wsum[v] += w;
  });
  for (int v = 0; v < mesh.n_vertices(); ++v) sum[v] = wsum[v] > 0 ? std::sqrt(sum[v] / wsum[v]) : 0.0;
  return sum;
}

int count_flipped_fan_triangles(const Mesh& mesh, const Refinement& r, const Eigen::MatrixX2d& uv) {
  check_refinement(mesh, r, "count_flipped_fan_triangles");
  int flipped = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size()), h0 = mesh.face_offsets()[f];
    Eigen::Vector2d uf = Eigen::Vector2d::Zero();
    for (int a = 0; a < n; ++a) uf += r.weights[h0 + a] * uv.row(face[a]).transpose();
    for (int a = 0; a < n; ++a) {
      if (r.fan[h0 + a] == FanTriangle::Degenerate) continue;
      const Eigen::Vector2d p = uv.row(face[a]).transpose() - uf,
                            q = uv.row(face[(a + 1) % n]).transpose() - uf;
      if (!(p.x() * q.y() - p.y() * q.x() > 0)) ++flipped;
    }
  }
  return flipped;
}

void write_obj_with_uv(const std::string& path, const Mesh& mesh, const Eigen::MatrixX2d& uv) {
  std::ofstream out(path);
  if (!out) throw FileError(path, 0, -1, "cannot open file for writing");
  for (int v = 0; v < mesh.n_vertices(); ++v)
    out << fmt::format("v {:.17g} {:.17g} {:.17g}\n", mesh.positions()(v, 0), mesh.positions()(v, 1),
                       mesh.positions()(v, 2));
  for (int v = 0; v < mesh.n_vertices(); ++v) out << fmt::format("vt {:.17g} {:.17g}\n", uv(v, 0), uv(v, 1));
  for (int f = 0; f < mesh.n_faces(); ++f) {
    out << 'f';
    for (int v : mesh.face(f)) out << ' ' << v + 1 << '/' << v + 1;
    out << '\n';
  }
  if (!out) throw FileError(path, 0, -1, "write failed");
}

}  // namespace polydec
