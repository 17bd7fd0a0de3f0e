// tests/operators/volume/test_laplacian.cpp — the polyhedral stiffness and mass:
// symmetry, null space, semi-definiteness, linear precision, equality with an independently
// assembled linear FEM on tetrahedral meshes (both cell-point rules), invariance under
// translation and scaling, total mass, the cell-point kernels, degenerate sub-tetrahedra, and the
// polyLaplace weight rule against an independent reference of that construction.
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <cmath>

#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/surface/virtual_vertex.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/refinement.h"
#include "polydec/operators/volume/laplacian.h"
#include "tests/support/volume_meshes.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_laplacian {
using polydec::test::relative_difference;

namespace {

// Independent linear FEM on one tetrahedron: barycentric coordinates from the inverse of [1 p].
void reference_tet(const Eigen::Vector3d p[4], Eigen::Matrix4d& S, Eigen::Matrix4d& M) {
  Eigen::Matrix4d A;
  for (int a = 0; a < 4; ++a) A.row(a) << 1.0, p[a].transpose();
  const Eigen::Matrix4d B = A.inverse();  // column a: coefficients of lambda_a
  const double vol = std::abs(A.determinant()) / 6.0;
  const Eigen::Matrix<double, 3, 4> G = B.bottomRows(3);
  S = -vol * G.transpose() * G;
  M = vol / 20.0 * (Eigen::Matrix4d::Ones() + Eigen::Matrix4d::Identity());
}

// The standard linear FEM of a tetrahedral mesh, assembled from the cells' vertex lists.
void reference_tet_mesh(const VolumeMesh& mesh, SparseMatrix& S, SparseMatrix& M) {
  std::vector<Eigen::Triplet<double>> ts, tm;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const auto v = mesh.cell_vertices(c);
    REQUIRE(v.size() == 4);
    Eigen::Vector3d p[4];
    for (int a = 0; a < 4; ++a) p[a] = mesh.position(v[a]);
    Eigen::Matrix4d Sl, Ml;
    reference_tet(p, Sl, Ml);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        ts.emplace_back(v[a], v[b], Sl(a, b)), tm.emplace_back(v[a], v[b], Ml(a, b));
  }
  S.resize(mesh.n_vertices(), mesh.n_vertices());
  M.resize(mesh.n_vertices(), mesh.n_vertices());
  S.setFromTriplets(ts.begin(), ts.end());
  M.setFromTriplets(tm.begin(), tm.end());
}

// Independent reference of polyLaplace's construction: face points by the surface rule, the cell
// point minimizing the sum of squared sub-tetrahedron volumes from the quadratic's values
// (polarization, full-pivoting LU), cell weights over [face points, vertices ascending] with the
// first k-1 from the SVD pseudo-inverse and the last 1 minus their sum; S and M as P^T A P with the
// explicit refined tetrahedral mesh.
void reference_polylaplace(const VolumeMesh& mesh, SparseMatrix& S, SparseMatrix& M) {
  const int nV = mesh.n_vertices(), nF = mesh.n_faces(), nC = mesh.n_cells();
  std::vector<Eigen::Vector3d> pos(nV + nF + nC);
  std::vector<Eigen::Triplet<double>> tp;
  for (int v = 0; v < nV; ++v) pos[v] = mesh.position(v), tp.emplace_back(v, v, 1.0);
  std::vector<Eigen::VectorXd> fw(nF);
  for (int f = 0; f < nF; ++f) {
    const auto face = mesh.face(f);
    PolygonPositions X(face.size(), 3);
    for (size_t k = 0; k < face.size(); ++k) X.row(k) = mesh.position(face[k]).transpose();
    fw[f] = squared_area_weights(X);
    pos[nV + f] = X.transpose() * fw[f];
    for (size_t k = 0; k < face.size(); ++k) tp.emplace_back(nV + f, face[k], fw[f](k));
  }
  std::vector<std::array<int, 4>> tets;
  for (int c = 0; c < nC; ++c) {
    std::vector<std::array<Eigen::Vector3d, 3>> tris;
    for (int hf : mesh.cell(c)) {
      const auto face = mesh.face(hf / 2);
      const int n = int(face.size());
      for (int i = 0; i < n; ++i) {
        tris.push_back({pos[nV + hf / 2], pos[face[i]], pos[face[(i + 1) % n]]});
        tets.push_back({face[i], face[(i + 1) % n], nV + hf / 2, nV + nF + c});
      }
    }
    auto q = [&](const Eigen::Vector3d& x) {
      double s = 0;
      for (const auto& t : tris) {
        Eigen::Matrix3d D;
        D << (t[1] - t[0]).transpose(), (t[2] - t[0]).transpose(), (x - t[0]).transpose();
        s += D.determinant() * D.determinant();
      }
      return s;
    };
    const double q0 = q(Eigen::Vector3d::Zero());
    Eigen::Matrix3d H;
    Eigen::Vector3d g;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d ei = Eigen::Vector3d::Unit(i);
      g(i) = (q(ei) - q(-ei)) / 2;
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d ej = Eigen::Vector3d::Unit(j);
        H(i, j) = (q(ei + ej) - q(ei) - q(ej) + q0) / 2;
      }
    }
    const Eigen::Vector3d xc = H.fullPivLu().solve(-g / 2);
    pos[nV + nF + c] = xc;
    const auto verts = mesh.cell_vertices(c);
    std::vector<Eigen::Vector3d> pts;
    for (int hf : mesh.cell(c)) pts.push_back(pos[nV + hf / 2]);
    for (int v : verts) pts.push_back(pos[v]);
    const int k = int(pts.size());
    Eigen::MatrixXd D(3, k - 1);
    for (int j = 0; j + 1 < k; ++j) D.col(j) = pts[j] - pts[k - 1];
    const Eigen::VectorXd lam =
        D.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(Eigen::VectorXd(xc - pts[k - 1]));
    Eigen::VectorXd lambda(k);
    lambda.head(k - 1) = lam;
    lambda(k - 1) = 1 - lam.sum();
    int j = 0;
    for (int hf : mesh.cell(c)) {
      const auto face = mesh.face(hf / 2);
      for (size_t i = 0; i < face.size(); ++i)
        tp.emplace_back(nV + nF + c, face[i], lambda(j) * fw[hf / 2](i));
      ++j;
    }
    for (int v : verts) tp.emplace_back(nV + nF + c, v, lambda(j++));
  }
  SparseMatrix P(nV + nF + nC, nV);
  P.setFromTriplets(tp.begin(), tp.end());
  std::vector<Eigen::Triplet<double>> ts, tm;
  for (const auto& t : tets) {
    Eigen::Vector3d p[4];
    for (int a = 0; a < 4; ++a) p[a] = pos[t[a]];
    Eigen::Matrix4d Sl, Ml;
    reference_tet(p, Sl, Ml);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        ts.emplace_back(t[a], t[b], Sl(a, b)), tm.emplace_back(t[a], t[b], Ml(a, b));
  }
  SparseMatrix St(P.rows(), P.rows()), Mt(P.rows(), P.rows());
  St.setFromTriplets(ts.begin(), ts.end());
  Mt.setFromTriplets(tm.begin(), tm.end());
  S = P.transpose() * St * P;
  M = P.transpose() * Mt * P;
}

// Symmetry, S 1 = 0, negative semi-definite (dense spectrum), M positive, masses sum to the volume.
// (The volume check needs planar faces: VolumeMesh::volume() triangulates faces its own way.)
void check_basic(const VolumeMesh& mesh, const VolumeLaplacian& L, bool planar = true) {
  const Eigen::MatrixXd S = Eigen::MatrixXd(L.S);
  const double scale = S.cwiseAbs().maxCoeff();
  CHECK((S - S.transpose()).cwiseAbs().maxCoeff() <= 1e-13 * scale);
  CHECK((S * Eigen::VectorXd::Ones(S.cols())).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S);
  CHECK(eig.eigenvalues().maxCoeff() <= 1e-12 * scale);
  // Exactly one zero eigenvalue on a connected mesh.
  CHECK(eig.eigenvalues()(S.rows() - 2) < -1e-8 * scale);
  CHECK(relative_difference(L.M, SparseMatrix(L.M.transpose())) <= 1e-14);
  if (planar) CHECK(std::abs(L.M_lumped.sum() - mesh.volume()) <= 1e-12 * mesh.volume());
  CHECK(L.M_lumped.minCoeff() > 0);
}

// S x = 0 at interior vertices for the coordinate functions.
double linear_precision_defect(const VolumeMesh& mesh, const SparseMatrix& S) {
  const Eigen::MatrixXd SX = S * mesh.positions();
  double worst = 0;
  const double scale = Eigen::MatrixXd(S).cwiseAbs().maxCoeff() * mesh.bounding_box_diagonal();
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (!mesh.is_boundary_vertex(v)) worst = std::max(worst, SX.row(v).cwiseAbs().maxCoeff() / scale);
  return worst;
}

}  // namespace

TEST_CASE("cell point kernels: squared-volume minimizer and affine weights", "[volume][volume-operators]") {
  // A unit cube's minimizer is its centre by symmetry; an affine image moves it along.
  const VolumeMesh cube = test::hex_grid_mesh(1, 1, 1);
  const VolumeRefinement R = refine_volume(cube);
  CHECK((R.cell_points.row(0) - Eigen::RowVector3d(0.5, 0.5, 0.5)).norm() < 1e-14);
  for (int k = 0; k < 8; ++k) CHECK(std::abs(R.cell_weights[k] - 0.125) < 1e-14);
  Eigen::Matrix3d A;
  A << 1.3, 0.2, -0.1, 0.1, 0.8, 0.3, -0.2, 0.25, 1.1;
  const Eigen::Vector3d t(5, -3, 2);
  const Eigen::MatrixX3d Y = (cube.positions() * A.transpose()).rowwise() + t.transpose();
  const VolumeMesh sheared = cube.with_positions(Y);
  const VolumeRefinement Rs = refine_volume(sheared);
  CHECK((Rs.cell_points.row(0).transpose() - (A * Eigen::Vector3d(0.5, 0.5, 0.5) + t)).norm() < 1e-12);
  // Weights reproduce the point and sum to one, for both rules.
  for (CellPointRule rule : {CellPointRule::SquaredVolume, CellPointRule::PolyLaplace}) {
    VolumeRefinementOptions o;
    o.cell_rule = rule;
    const VolumeRefinement Rr = refine_volume(sheared, o);
    const auto w = Rr.weights_of_cell(0);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    double sum = 0;
    const auto verts = sheared.cell_vertices(0);
    for (size_t k = 0; k < verts.size(); ++k) x += w[k] * sheared.position(verts[k]), sum += w[k];
    CHECK(std::abs(sum - 1) < 1e-13);
    CHECK((x - Rr.cell_points.row(0).transpose()).norm() < 1e-12);
  }
  // Least-norm weights: invariant under a similarity transform of points and target.
  Eigen::MatrixX3d X(6, 3);
  X << 0, 0, 0, 1, 0.1, 0, 0.2, 1, 0.3, 0, 0.1, 1, 1, 1, 1, 0.4, 0.5, 0.6;
  const Eigen::Vector3d x(0.3, 0.4, 0.35);
  const Eigen::VectorXd w1 = least_norm_affine_weights(X, x);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const double s = 1e-5;
  const Eigen::Vector3d shift =
      s * Eigen::Vector3d(3e2, 2e2, -5e2);  // far from the points, relative to their size
  const Eigen::MatrixX3d Xs = ((s * X * Q.transpose()).rowwise() + shift.transpose());
  const Eigen::VectorXd w2 = least_norm_affine_weights(Xs, s * Q * x + shift);
  CHECK((w1 - w2).cwiseAbs().maxCoeff() < 1e-11);
  CHECK((X.transpose() * w1 - x).norm() < 1e-14);
  // The least-norm weights have the smaller norm of the two rules' weights over the same points.
  const Eigen::VectorXd w3 = last_pinned_affine_weights(X, x);
  CHECK((X.transpose() * w3 - x).norm() < 1e-14);
  CHECK(w1.norm() <= w3.norm() + 1e-15);
}

TEST_CASE("single tetrahedron and tetrahedral grids: the standard linear FEM, both rules",
          "[volume][volume-operators]") {
  Eigen::MatrixX3d X = test::grid_positions(3, 3, 3);
  test::jitter_interior(X, 3, 3, 3, 0.15, 7);
  const VolumeMesh mesh = test::tet_grid_mesh(3, 3, 3, &X);
  SparseMatrix Sr, Mr;
  reference_tet_mesh(mesh, Sr, Mr);
  for (CellPointRule rule : {CellPointRule::SquaredVolume, CellPointRule::PolyLaplace}) {
    VolumeRefinementOptions o;
    o.cell_rule = rule;
    const VolumeRefinement R = refine_volume(mesh, o);
    CHECK(R.quality.ok());
    const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
    CHECK(relative_difference(L.S, Sr) < 1e-12);
    CHECK(relative_difference(L.M, Mr) < 1e-12);
    check_basic(mesh, L);
    CHECK(linear_precision_defect(mesh, L.S) < 1e-12);
  }
}

TEST_CASE("hexahedral grids and a pyramid: properties and linear precision", "[volume][volume-operators]") {
  // Planar faces: an affine image of a 3x3x3 grid, and a grid with one layer moved (still planar).
  Eigen::Matrix3d A;
  A << 1.0, 0.3, 0.1, 0.0, 0.7, -0.2, 0.1, 0.0, 1.4;
  Eigen::MatrixX3d X = test::grid_positions(3, 3, 3) * A.transpose();
  const VolumeMesh affine = test::hex_grid_mesh(3, 3, 3, &X);
  Eigen::MatrixX3d Y = test::grid_positions(3, 3, 3);
  for (int v = 0; v < Y.rows(); ++v) {
    Y(v, 0) = std::pow(Y(v, 0), 1.5);  // non-uniform spacing along each axis: faces stay planar
    Y(v, 2) = Y(v, 2) * Y(v, 2) + 0.2 * Y(v, 2);
  }
  const VolumeMesh graded = test::hex_grid_mesh(3, 3, 3, &Y);
  // Generated meshes with planar faces: clipped truncated octahedra and pyramids (dec/mesh/volume_generators.h).
  const VolumeMesh truncated = truncated_octahedra_volume(2);
  const VolumeMesh pyramids = pyramid_grid_volume(2, 2, 2);
  for (const VolumeMesh* m : {&affine, &graded, &truncated, &pyramids}) {
    const VolumeRefinement R = refine_volume(*m);
    CHECK(R.quality.ok());
    const VolumeLaplacian L = assemble_volume_laplacian(*m, R);
    check_basic(*m, L);
    CHECK(linear_precision_defect(*m, L.S) < 1e-12);
  }
  // Jittered interior vertices (non-planar faces): still symmetric, S 1 = 0, semi-definite.
  Eigen::MatrixX3d Z = test::grid_positions(3, 3, 3);
  test::jitter_interior(Z, 3, 3, 3, 0.25, 3);
  const VolumeMesh jittered = test::hex_grid_mesh(3, 3, 3, &Z);
  check_basic(jittered, assemble_volume_laplacian(jittered, refine_volume(jittered)), false);
  const VolumeMesh pyramid = test::single_pyramid();
  check_basic(pyramid, assemble_volume_laplacian(pyramid, refine_volume(pyramid)));
}

TEST_CASE("volume operators: translation and scale invariance", "[volume][volume-operators]") {
  Eigen::MatrixX3d Z = test::grid_positions(2, 2, 2);
  test::jitter_interior(Z, 2, 2, 2, 0.25, 11);
  const VolumeMesh mesh = test::hex_grid_mesh(2, 2, 2, &Z);
  const VolumeLaplacian L = assemble_volume_laplacian(mesh, refine_volume(mesh));
  for (double s : {1e-6, 1e6}) {
    const Eigen::MatrixX3d Y = (s * Z).rowwise() + Eigen::RowVector3d(3e2, -7e1, 1e3) * s;
    const VolumeMesh moved = mesh.with_positions(Y);
    const VolumeLaplacian Ls = assemble_volume_laplacian(moved, refine_volume(moved));
    CHECK(relative_difference(Ls.S, SparseMatrix(s * L.S)) < 1e-9);
    CHECK(relative_difference(Ls.M, SparseMatrix(s * s * s * L.M)) < 1e-9);
  }
}

TEST_CASE("volume refinement: degenerate sub-tetrahedra are reported and add no stiffness",
          "[volume][volume-operators]") {
  // A hexahedron squashed to a relative height of 1e-12: every sub-tetrahedron is flat.
  Eigen::MatrixX3d X = test::grid_positions(1, 1, 1);
  X.col(2) *= 1e-12;
  const VolumeMesh flat = test::hex_grid_mesh(1, 1, 1, &X);
  const VolumeRefinement R = refine_volume(flat);
  CHECK(R.quality.n_degenerate == 24);
  CHECK(R.quality.n_cells_affected == 1);
  const VolumeLaplacian L = assemble_volume_laplacian(flat, R);
  CHECK(L.S.norm() == 0.0);
  CHECK(L.M.coeffs().allFinite());
  // A regular cube has none.
  CHECK(refine_volume(test::hex_grid_mesh(1, 1, 1)).quality.ok());
}

TEST_CASE("volume assembly skips exactly the flagged sub-tetrahedra: equal to the explicit refined mesh",
          "[volume][volume-operators]") {
  // A loose degeneracy tolerance flags the flatter sub-tetrahedra of a jittered grid, on half-faces
  // of both parities; the cell kernel must skip the same tetrahedra as refined_tets() lists (the
  // order of VolumeRefinement::tets): S and M against P^T S^tet P from those tetrahedra alone.
  const VolumeMesh mesh = hex_grid_volume(3, 3, 2, VolumeJitter{0.3, 5});
  VolumeRefinementOptions options;
  options.degenerate_tolerance = 0.25;
  const VolumeRefinement R = refine_volume(mesh, options);
  const std::vector<RefinedTet> tets = refined_tets(mesh, R);
  REQUIRE(R.quality.n_degenerate > 0);
  REQUIRE(R.quality.n_degenerate < int(tets.size()) / 2);
  // Flagged tetrahedra on odd half-faces whose mirrored position in the half-face is not flagged:
  // reading the flags in the face's order instead of the half-face's would skip other tetrahedra.
  int odd_flagged = 0;
  for (int c = 0, t = 0; c < mesh.n_cells(); ++c)
    for (int hf : mesh.cell(c)) {
      const int n = mesh.face_size(hf / 2);
      for (int i = 0; i < n; ++i)
        if ((hf & 1) && R.tets[t + i] == SubTet::Degenerate && R.tets[t + n - 2 - i + (i + 2 > n ? n : 0)] != SubTet::Degenerate)
          ++odd_flagged;
      t += n;
    }
  CHECK(odd_flagged > 0);

  const int nR = mesh.n_vertices() + mesh.n_faces() + mesh.n_cells();
  std::vector<Eigen::Triplet<double>> ts, tm;
  for (const RefinedTet& t : tets) {
    Eigen::Vector3d p[4];
    for (int a = 0; a < 4; ++a) p[a] = refined_position(mesh, R, t.v[a]);
    Eigen::Matrix4d Sl, Ml;
    reference_tet(p, Sl, Ml);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        if (t.quality != SubTet::Degenerate) ts.emplace_back(t.v[a], t.v[b], Sl(a, b));
        tm.emplace_back(t.v[a], t.v[b], Ml(a, b));
      }
  }
  SparseMatrix St(nR, nR), Mt(nR, nR);
  St.setFromTriplets(ts.begin(), ts.end());
  Mt.setFromTriplets(tm.begin(), tm.end());
  const SparseMatrix P = volume_prolongation(mesh, R);
  const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
  CHECK(relative_difference(L.S, SparseMatrix(P.transpose() * St * P)) <= 1e-12);
  CHECK(relative_difference(L.M, SparseMatrix(P.transpose() * Mt * P)) <= 1e-12);
}

TEST_CASE("polyLaplace weight rule equals an independent reference of that construction",
          "[volume][volume-operators]") {
  Eigen::MatrixX3d Z = test::grid_positions(2, 2, 2);
  test::jitter_interior(Z, 2, 2, 2, 0.25, 5);
  const VolumeMesh meshes[] = {test::hex_grid_mesh(2, 2, 2, &Z), test::single_pyramid(),
                               test::hex_solid_torus(6)};
  VolumeRefinementOptions o;
  o.cell_rule = CellPointRule::PolyLaplace;
  for (const VolumeMesh& mesh : meshes) {
    SparseMatrix Sr, Mr;
    reference_polylaplace(mesh, Sr, Mr);
    const VolumeLaplacian L = assemble_volume_laplacian(mesh, refine_volume(mesh, o));
    CHECK(relative_difference(L.S, Sr) < 1e-10);
    CHECK(relative_difference(L.M, Mr) < 1e-10);
    // The default rule puts the cell point at the same place but weighs it differently.
    const VolumeRefinement Rd = refine_volume(mesh);
    CHECK((Rd.cell_points - refine_volume(mesh, o).cell_points).norm() <
          1e-12 * mesh.bounding_box_diagonal());
  }
}

TEST_CASE("polyLaplace weight rule on the shared cube meshes equals the independent reference",
          "[volume][volume-operators]") {
  VolumeRefinementOptions o;
  o.cell_rule = CellPointRule::PolyLaplace;
  for (const char* name :
       {"volume/cube_hexahedron_1.ovm", "volume/cube_pyramids_1.ovm", "volume/cube_truncated_1.ovm",
        "volume/cube_pyramids_2.ovm", "volume/cube_truncated_2.ovm"}) {
    const std::string path = test::shared_path(name);
    if (path.empty()) {
      WARN("skipped: " << name << " missing");
      continue;
    }
    INFO(name);
    const VolumeMesh mesh = read_volume_mesh(path);
    SparseMatrix Sr, Mr;
    reference_polylaplace(mesh, Sr, Mr);
    const VolumeLaplacian L = assemble_volume_laplacian(mesh, refine_volume(mesh, o));
    CHECK(relative_difference(L.S, Sr) < 1e-10);
    CHECK(relative_difference(L.M, Mr) < 1e-10);
  }
}

}  // namespace test_volume_laplacian
