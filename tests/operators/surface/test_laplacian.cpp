// tests/operators/surface/test_laplacian.cpp — the polygon Laplacian's defining properties (paper
// section 4.3): symmetry, constants in the null space, negative semi-definiteness, linear
// precision, reduction to the cotangent Laplacian on triangles, fast assembly = explicit
// P^T S^f P, S = D G, lumped mass = fan area, invariance under rigid motion, relabeling, scale.
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/operators/surface/gradient.h"
#include "polydec/operators/surface/laplacian.h"
#include "tests/support/plain_cotan.h"
#include "tests/support/support.h"

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <random>

using namespace polydec;

namespace test_laplacian {
using polydec::test::relative_difference;

namespace {

struct Case {
  std::string name;
  Mesh mesh;
};

// Generated meshes plus the paper's meshes that are present.
std::vector<Case> test_meshes() {
  std::vector<Case> c = {{"quad grid", quad_grid(5, 4)},
                         {"hex grid", hex_grid(6, 5)},
                         {"noisy hex sphere", add_noise(hex_sphere(1), 0.2, 7)},
                         {"noisy torus", add_noise(torus(10, 6), 0.15, 3)},
                         {"uv sphere", uv_sphere(6, 9)}};
  for (const char* name : {"L-plane.obj", "tetris.obj", "tetris_2.obj", "quad-sphere.off", "noisy-sphere.off"}) {
    const std::string p = polydec::test::shared_path(name);
    if (!p.empty()) c.push_back({name, read_mesh(p)});
  }
  return c;
}

// For a planar mesh, a unit vector in its plane (else the zero vector).
Eigen::Vector3d in_plane_direction(const Mesh& m) {
  const Eigen::MatrixXd Y = m.positions().rowwise() - m.positions().colwise().mean();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Y, Eigen::ComputeThinV);
  if (svd.singularValues()[2] > 1e-12 * svd.singularValues()[0]) return Eigen::Vector3d::Zero();
  return (0.8 * svd.matrixV().col(0) - 0.6 * svd.matrixV().col(1)).normalized();
}

}  // namespace

TEST_CASE("S is symmetric, annihilates constants and is negative semi-definite", "[laplacian]") {
  for (const auto& [name, mesh] : test_meshes()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const Laplacian L = assemble_laplacian(mesh, r);
    const double scale = L.S.diagonal().cwiseAbs().maxCoeff();
    CHECK(relative_difference(L.S, SparseMatrix(L.S.transpose())) < 1e-15);
    CHECK((L.S * Eigen::VectorXd::Ones(mesh.n_vertices())).cwiseAbs().maxCoeff() < 1e-12 * scale);
    CHECK(relative_difference(L.M, SparseMatrix(L.M.transpose())) < 1e-15);
    if (mesh.n_vertices() <= 700) {
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(L.S)};
      CHECK(es.eigenvalues().maxCoeff() < 1e-10 * scale);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> em{Eigen::MatrixXd(L.M)};
      CHECK(em.eigenvalues().minCoeff() > 0);
    }
  }
}

TEST_CASE("linear precision on planar meshes whose fans are all positively oriented", "[laplacian]") {
  for (const auto& [name, mesh] : test_meshes()) {
    const Eigen::Vector3d a = in_plane_direction(mesh);
    if (a.isZero()) continue;
    INFO(name);
    const Refinement r = refine(mesh);
    const SparseMatrix S = stiffness(mesh, r);
    const Eigen::VectorXd u = mesh.positions() * a;
    const Eigen::VectorXd Su = S * u;
    double worst = 0;
    for (int v = 0; v < mesh.n_vertices(); ++v)
      if (!mesh.is_boundary_vertex(v)) worst = std::max(worst, std::abs(Su[v]));
    const double scale = S.diagonal().cwiseAbs().maxCoeff() * u.cwiseAbs().maxCoeff();
    if (r.quality.ok()) {
      CHECK(worst < 1e-12 * scale);
    } else {
      // The fan folds over or degenerates: the paper's operator loses linear precision there.
      // Documented in docs/operators.md with the measured size.
      WARN(name << ": " << r.quality.n_inverted << " inverted, " << r.quality.n_degenerate
                << " degenerate fan triangles; linear-precision defect " << worst / scale);
      CHECK(worst > 1e-6 * scale);
    }
  }
}

TEST_CASE("on triangle meshes S is the cotangent Laplacian and M the Galerkin mass", "[laplacian]") {
  std::vector<Mesh> meshes = {triangle_grid(4, 5), add_noise(dual(hex_sphere(1)), 0.1)};
  const std::string p = polydec::test::shared_path("unit-sphere-low.off");
  if (!p.empty()) meshes.push_back(read_mesh(p));
  for (const Mesh& mesh : meshes) {
    REQUIRE(mesh.max_face_size() == 3);
    const Laplacian L = assemble_laplacian(mesh, refine(mesh));
    const auto plain = polydec::test::plain_cotan(mesh);
    CHECK(relative_difference(L.S, plain.S) < 1e-12);
    CHECK(relative_difference(L.M, plain.M) < 1e-12);
  }
}

TEST_CASE("fast assembly equals the explicit route P^T S^f P on the refined mesh", "[laplacian]") {
  for (const auto& [name, mesh] : test_meshes()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const Laplacian L = assemble_laplacian(mesh, r);
    const Mesh fine = refined_mesh(mesh, r);
    std::vector<bool> skip(r.fan.size());
    for (size_t h = 0; h < r.fan.size(); ++h) skip[h] = r.fan[h] == FanTriangle::Degenerate;
    const auto plain = polydec::test::plain_cotan(fine, skip);
    const SparseMatrix P = prolongation(mesh, r);
    const SparseMatrix S_explicit = SparseMatrix(P.transpose()) * plain.S * P;
    const SparseMatrix M_explicit = SparseMatrix(P.transpose()) * plain.M * P;
    CHECK(relative_difference(L.S, S_explicit) < 1e-12);
    CHECK(relative_difference(L.M, M_explicit) < 1e-12);
    // Lumped mass: row sums; total = area of the fan triangulation.
    CHECK((L.M_lumped - L.M * Eigen::VectorXd::Ones(mesh.n_vertices())).cwiseAbs().maxCoeff() <
          1e-14 * L.M_lumped.maxCoeff());
    const Eigen::VectorXd a = fan_areas(mesh, r);
    double fan_area = 0;
    for (size_t h = 0; h < r.fan.size(); ++h) fan_area += a[long(h)];
    CHECK(L.M_lumped.sum() == Approx(fan_area).epsilon(1e-12));
  }
}

TEST_CASE("the lumped mass alone equals the row sums of the assembled M", "[laplacian]") {
  std::vector<Case> cases = test_meshes();
  cases.push_back({"triangle grid", triangle_grid(5, 4)});
  cases.push_back({"noisy cube sphere", add_noise(cube_sphere(6), 0.2, 4)});
  cases.push_back({"chevron grid (non-convex hexagons)", chevron_grid(5, 4)});
  cases.push_back({"noisy genus 2", add_noise(genus2(1), 0.2, 9)});
  {
    const Mesh grid = quad_grid(3, 2);  // plus one vertex in no face
    PolygonSoup soup;
    soup.positions.resize(grid.n_vertices() + 1, 3);
    soup.positions << grid.positions(), Eigen::RowVector3d(0.5, 0.5, 1.0);
    for (int f = 0; f < grid.n_faces(); ++f) soup.add_face(grid.face(f));
    cases.push_back({"quad grid with an unreferenced vertex", Mesh(std::move(soup))});
  }
  for (const auto& [name, mesh] : cases) {
    INFO(name);
    const int nv = mesh.n_vertices();
    const Refinement r = refine(mesh);
    const Laplacian full = assemble_laplacian(mesh, r);
    // With M: its column sums, stored values in row order.
    bool column_sums = true;
    for (int j = 0; j < nv; ++j) {
      double s = 0.0;
      for (SparseMatrix::InnerIterator it(full.M, j); it; ++it) s += it.value();
      column_sums = column_sums && full.M_lumped[j] == s;
    }
    CHECK(column_sums);
    // Without M: per face, the same for every route that asks for no M.
    const Laplacian alone = assemble_laplacian(mesh, r, {false, false, true});
    CHECK(alone.S.nonZeros() == 0);
    CHECK(alone.M.nonZeros() == 0);
    const Eigen::VectorXd rows = full.M * Eigen::VectorXd::Ones(nv);
    CHECK((alone.M_lumped - rows).cwiseAbs().maxCoeff() <= 1e-14 * rows.cwiseAbs().maxCoeff());
    for (int v = 0; v < nv; ++v)
      if (mesh.vertex_faces(v).empty()) CHECK(alone.M_lumped[v] == 0.0);
    const Laplacian with_S = assemble_laplacian(mesh, r, {true, false, true});
    CHECK(with_S.M_lumped == alone.M_lumped);
    CHECK(with_S.M.nonZeros() == 0);
    CHECK(relative_difference(with_S.S, full.S) == 0.0);
    CHECK(lumped_mass(mesh, r) == alone.M_lumped);
    const FacePattern fp = face_pattern(mesh);
    Laplacian again;
    reassemble_laplacian(mesh, r, fp, {false, false, true}, again);
    CHECK(again.M_lumped == alone.M_lumped);
  }
}

TEST_CASE("S = D G and D = -G^T W", "[laplacian]") {
  for (const auto& [name, mesh] : test_meshes()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const SparseMatrix S = stiffness(mesh, r), G = gradient(mesh, r), D = divergence(mesh, r);
    CHECK(G.rows() == 3 * mesh.n_halfedges());
    CHECK(relative_difference(S, SparseMatrix(D * G)) < 1e-12);
    // The gradient of a constant vanishes; the gradient of a linear function on a planar mesh is that constant vector.
    const Eigen::VectorXd g1 = G * Eigen::VectorXd::Ones(mesh.n_vertices());
    CHECK(g1.cwiseAbs().maxCoeff() < 1e-9 * Eigen::Map<const Eigen::VectorXd>(G.valuePtr(), G.nonZeros()).cwiseAbs().maxCoeff());
    const Eigen::Vector3d a = in_plane_direction(mesh);
    if (!a.isZero()) {
      const Eigen::VectorXd ga = G * (mesh.positions() * a);
      for (int h = 0; h < mesh.n_halfedges(); ++h)
        if (r.fan[h] != FanTriangle::Degenerate) CHECK((ga.segment<3>(3 * h) - a).norm() < 1e-9);
    }
  }
}

TEST_CASE("invariance under rigid motion, relabeling and scaling", "[laplacian]") {
  for (const auto& [name, mesh] : test_meshes()) {
    INFO(name);
    const Laplacian L = assemble_laplacian(mesh, refine(mesh));
    // Rigid motion.
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const Eigen::MatrixX3d X = (mesh.positions() * R.transpose()).rowwise() + Eigen::RowVector3d(0.3, -2, 5);
    const Mesh moved = mesh.with_positions(X);
    const Laplacian Lm = assemble_laplacian(moved, refine(moved));
    CHECK(relative_difference(L.S, Lm.S) < 1e-11);
    CHECK(relative_difference(L.M, Lm.M) < 1e-11);
    // Scaling: S unchanged, M times s^2.
    for (double s : {1e-6, 1e6}) {
      const Mesh scaled = mesh.with_positions(s * mesh.positions());
      const Laplacian Ls = assemble_laplacian(scaled, refine(scaled));
      CHECK(relative_difference(L.S, Ls.S) < 1e-11);
      CHECK(relative_difference(L.M, SparseMatrix(Ls.M / (s * s))) < 1e-11);
    }
    // Relabeling vertices by a random permutation: S' = Pi S Pi^T.
    std::vector<int> perm(mesh.n_vertices());
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), std::mt19937(5));
    PolygonSoup soup;
    soup.precision = mesh.precision();  // the same data: what its digits resolve decides planarity
    soup.positions.resize(mesh.n_vertices(), 3);
    for (int v = 0; v < mesh.n_vertices(); ++v) soup.positions.row(perm[v]) = mesh.positions().row(v);
    for (int f = 0; f < mesh.n_faces(); ++f) {
      std::vector<int> face;
      for (int v : mesh.face(f)) face.push_back(perm[v]);
      soup.add_face(face);
    }
    const Mesh relabeled(std::move(soup));
    const Laplacian Lr = assemble_laplacian(relabeled, refine(relabeled));
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic> Pi(mesh.n_vertices());
    for (int v = 0; v < mesh.n_vertices(); ++v) Pi.indices()[v] = perm[v];
    const SparseMatrix Sp = Pi * L.S * Pi.transpose();
    CHECK(relative_difference(Sp, Lr.S) < 1e-13);
  }
}

}  // namespace test_laplacian
