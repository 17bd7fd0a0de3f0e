// tests/operators/surface/test_quadratic.cpp — the quadratic polygon Laplacian: symmetry, constants in
// the null space, negative semi-definiteness, the mass sums to the area, the face-by-face assembly
// equals the explicit P^T S^f P, standard P2 finite elements on triangle meshes (an independent
// assembly, no refinement), the patch test on planar polygon meshes (convex and not), and the
// HRZ lumping.
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <catch2/catch.hpp>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/operators/surface/quadratic.h"
#include "tests/support/feec_meshes.h"
#include "tests/support/p2_reference.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_quadratic_operators {
using polydec::test::relative_difference;

namespace {

std::vector<std::pair<std::string, Mesh>> surfaces() {
  return {{"quad grid", quad_grid(4, 3)}, {"mixed planar grid", test::planar_grid(5, 4, 0.3, true)},
          {"hex sphere", hex_sphere(1)},  {"noisy torus", add_noise(torus(8, 5), 0.15, 3)},
          {"uv sphere", uv_sphere(5, 7)}, {"chevrons", chevron_grid(3, 3)}};
}

// Standard P2 finite elements on a triangle mesh, straight from the mesh's triangles with the
// test's own element matrices: dofs vertices then edges, as the library numbers them.
std::pair<SparseMatrix, SparseMatrix> standard_p2(const Mesh& mesh) {
  const int nv = mesh.n_vertices(), nd = nv + mesh.n_edges();
  std::vector<Eigen::Triplet<double>> ts, tm;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const int h0 = mesh.face_offsets()[f];
    int dof[6];
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) {
      dof[k] = mesh.halfedge_source(h0 + k);
      dof[3 + k] = nv + mesh.halfedge_edge(h0 + k);  // edge (k, k+1)
      p[k] = mesh.positions().row(dof[k]).transpose();
    }
    const test::P2Reference e = test::p2_reference(p[0], p[1], p[2]);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        ts.emplace_back(dof[i], dof[j], -e.K(i, j));
        tm.emplace_back(dof[i], dof[j], e.M(i, j));
      }
  }
  SparseMatrix S(nd, nd), M(nd, nd);
  S.setFromTriplets(ts.begin(), ts.end());
  M.setFromTriplets(tm.begin(), tm.end());
  return {S, M};
}

// Dofs on the mesh boundary: boundary vertices and the midpoints of boundary edges.
std::vector<bool> boundary_dofs(const Mesh& mesh) {
  std::vector<bool> b(size_t(mesh.n_vertices() + mesh.n_edges()), false);
  for (int v = 0; v < mesh.n_vertices(); ++v) b[size_t(v)] = mesh.is_boundary_vertex(v);
  for (int e = 0; e < mesh.n_edges(); ++e) b[size_t(mesh.n_vertices() + e)] = mesh.is_boundary_edge(e);
  return b;
}

}  // namespace

TEST_CASE("quadratic S is symmetric, annihilates constants, is negative semi-definite and M sums to the area",
          "[quadratic]") {
  for (const auto& [name, mesh] : surfaces()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const QuadraticLaplacian Q = assemble_quadratic_laplacian(mesh, r);
    const int nd = mesh.n_vertices() + mesh.n_edges();
    REQUIRE(Q.S.rows() == nd);
    const double scale = Q.S.diagonal().cwiseAbs().maxCoeff();
    CHECK(relative_difference(Q.S, SparseMatrix(Q.S.transpose())) < 1e-14);
    CHECK(relative_difference(Q.M, SparseMatrix(Q.M.transpose())) < 1e-14);
    CHECK((Q.S * Eigen::VectorXd::Ones(nd)).cwiseAbs().maxCoeff() < 1e-12 * scale);
    // The fan area: the linear operator's lumped mass sums to it.
    const double area = lumped_mass(mesh, r).sum();
    CHECK(std::abs(Q.M.sum() - area) <= 1e-12 * area);
    CHECK(std::abs(Q.M_lumped.sum() - area) <= 1e-12 * area);
    CHECK(Q.M_lumped.minCoeff() > 0);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eS(Eigen::MatrixXd(Q.S)), eM(Eigen::MatrixXd(Q.M));
    CHECK(eS.eigenvalues().maxCoeff() <= 1e-12 * scale);
    // One zero eigenvalue per connected component, and M positive definite (P full column rank).
    CHECK(eS.eigenvalues()[nd - 2] < -1e-8 * scale);
    CHECK(eM.eigenvalues().minCoeff() > 1e-8 * eM.eigenvalues().maxCoeff());
    CHECK((Q.dofs - quadratic_dof_positions(mesh)).norm() == 0.0);
  }
}

TEST_CASE("quadratic S and M equal the explicit P^T S^f P and P^T M^f P", "[quadratic]") {
  for (const auto& [name, mesh] : surfaces()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const QuadraticLaplacian Q = assemble_quadratic_laplacian(mesh, r);
    const SparseMatrix P = quadratic_prolongation(mesh, r);
    const QuadraticRefinedMatrices F = quadratic_refined_matrices(mesh, r);
    CHECK(relative_difference(Q.S, SparseMatrix(P.transpose() * F.S * P)) < 1e-13);
    CHECK(relative_difference(Q.M, SparseMatrix(P.transpose() * F.M * P)) < 1e-13);
  }
}

TEST_CASE("on triangle meshes the quadratic operator is standard P2 finite elements", "[quadratic]") {
  const std::vector<std::pair<std::string, Mesh>> meshes = {
      {"triangle grid", triangle_grid(4, 3)},
      {"jittered triangles", add_noise(triangle_grid(5, 5), 0.2, 9)},
      {"icosphere", test::icosphere(2)}};
  for (const auto& [name, mesh] : meshes) {
    INFO(name);
    const QuadraticLaplacian Q = quadratic_laplacian(mesh);
    const auto [S, M] = standard_p2(mesh);
    CHECK(relative_difference(Q.S, S) < 1e-12);
    CHECK(relative_difference(Q.M, M) < 1e-12);
    // HRZ on a triangle: area/19 per corner, 16 area/57 per edge midpoint.
    Eigen::VectorXd hrz = Eigen::VectorXd::Zero(Q.M_lumped.size());
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const int h0 = mesh.face_offsets()[f];
      const PolygonPositions X = face_positions(mesh, f);
      const double a = 0.5 * (X.row(1) - X.row(0)).cross(X.row(2) - X.row(0)).norm();
      for (int k = 0; k < 3; ++k) {
        hrz[mesh.halfedge_source(h0 + k)] += a / 19;
        hrz[mesh.n_vertices() + mesh.halfedge_edge(h0 + k)] += 16 * a / 57;
      }
    }
    CHECK((Q.M_lumped - hrz).cwiseAbs().maxCoeff() <= 1e-13 * hrz.maxCoeff());
  }
}

TEST_CASE("patch test: S u = Laplace(u) M 1 at interior dofs for quadratic u on planar polygon meshes",
          "[quadratic]") {
  std::vector<std::pair<std::string, Mesh>> meshes = {
      {"quads", test::planar_grid(5, 4, 0.3, false)},
      {"hexagons", hex_grid(5, 5)},
      {"mixed 3- to 6-gons", test::planar_grid(6, 6, 0.25, true)},
      {"non-convex chevrons", chevron_grid(5, 4)},
      {"quads at 1e-6", test::planar_grid(4, 4, 0.3, false)
                            .with_positions(test::planar_grid(4, 4, 0.3, false).positions() * 1e-6)}};
  for (const char* file : {"L-plane.obj", "tetris.obj", "tetris_2.obj"}) {
    const std::string p = test::shared_path(file);
    if (!p.empty()) meshes.push_back({file, read_mesh(p)});
  }
  for (const auto& [name, mesh] : meshes) {
    INFO(name);
    const Refinement r = refine(mesh);
    if (!r.quality.ok()) {
      WARN(name << ": skipped, its fan has degenerate or inverted triangles (exactness needs a valid fan)");
      continue;
    }
    const QuadraticLaplacian Q = assemble_quadratic_laplacian(mesh, r);
    const std::vector<bool> boundary = boundary_dofs(mesh);
    // Coordinates x, y in the mesh's plane (the L-PLANE file lies in a plane y = const), in units
    // of the mesh's size s.
    const Eigen::RowVector3d o = mesh.positions().colwise().mean();
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(mesh.positions().rowwise() - o),
                                                Eigen::ComputeThinV);
    REQUIRE(svd.singularValues()[2] <= 1e-12 * svd.singularValues()[0]);
    const double s = (mesh.positions().colwise().maxCoeff() - mesh.positions().colwise().minCoeff()).norm();
    const Eigen::Vector3d e1 = svd.matrixV().col(0) / s, e2 = svd.matrixV().col(1) / s;
    for (const auto& c : {std::array<double, 3>{1, 0, 0}, {0, 1, 0}, {0.3, -0.7, 2}}) {
      // u = a x^2 + b x y + c y^2 + a linear part.
      Eigen::VectorXd u(Q.dofs.rows());
      for (int i = 0; i < u.size(); ++i) {
        const double x = (Q.dofs.row(i) - o).dot(e1.transpose()), y = (Q.dofs.row(i) - o).dot(e2.transpose());
        u[i] = c[0] * x * x + c[1] * x * y + c[2] * y * y + 0.5 * x - y + 3;
      }
      const double laplace = 2 * (c[0] + c[2]) / (s * s);
      const Eigen::VectorXd Su = Q.S * u, rhs = laplace * (Q.M * Eigen::VectorXd::Ones(u.size()));
      const double scale = Su.cwiseAbs().maxCoeff() + rhs.cwiseAbs().maxCoeff();
      int n_interior = 0;
      double worst = 0;
      for (int i = 0; i < u.size(); ++i)
        if (!boundary[size_t(i)]) {
          ++n_interior;
          worst = std::max(worst, std::abs(Su[i] - rhs[i]));
        }
      REQUIRE(n_interior > 0);
      CHECK(worst <= 1e-10 * scale);
    }
  }
}

TEST_CASE("the linear operator fails the quadratic patch test on hexagons (the test can fail)",
          "[quadratic]") {
  // The same check with the paper's linear S and M: exact for linear u only.
  const Mesh mesh = hex_grid(5, 5);
  const Refinement r = refine(mesh);
  const Laplacian L = assemble_laplacian(mesh, r);
  Eigen::VectorXd u(mesh.n_vertices());
  for (int v = 0; v < u.size(); ++v) u[v] = mesh.positions()(v, 0) * mesh.positions()(v, 0);
  const Eigen::VectorXd Su = L.S * u, rhs = 2 * (L.M * Eigen::VectorXd::Ones(u.size()));
  double worst = 0;
  for (int v = 0; v < u.size(); ++v)
    if (!mesh.is_boundary_vertex(v)) worst = std::max(worst, std::abs(Su[v] - rhs[v]));
  CHECK(worst > 1e-3 * rhs.cwiseAbs().maxCoeff());
}

}  // namespace test_quadratic_operators
