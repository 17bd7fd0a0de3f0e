// tests/operators/comparison/test_diamond.cpp — the Diamond Laplacian [BBA21] on surfaces and volumes:
// symmetry, null space, negative semi-definiteness, S = D G, mass totals, linear precision at
// interior vertices, rigid-motion and scale behaviour, the exact relation to the cotangent
// gradients on planar triangle meshes, and the 3D Franke Poisson convergence.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <random>

#include "polydec/apps/applications/volume/poisson.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/operators/comparison/diamond.h"
#include "polydec/operators/comparison/volume_diamond.h"
#include "polydec/operators/registry/volume_laplacians.h"
#include "tests/support/plain_cotan.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_diamond {
using test::relative_difference;

namespace {

double max_abs(const SparseMatrix& A) { return A.nonZeros() ? A.coeffs().cwiseAbs().maxCoeff() : 0.0; }

double surface_area(const Mesh& mesh) {
  double a = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < face.size(); ++k)
      v += mesh.position(face[k]).cross(mesh.position(face[(k + 1) % face.size()]));
    a += v.norm() / 2;
  }
  return a;
}

// Appends the shared meshes ../shared/data/PREFIX + NAME read by `read` (skipped with a warning where
// missing).
template <class AnyMesh, class Reader>
void add_shared(std::vector<std::pair<std::string, AnyMesh>>& meshes, const std::string& prefix,
                const std::vector<std::string>& names, Reader read) {
  for (const std::string& name : names) {
    const std::string path = test::shared_path(prefix + name);
    if (path.empty())
      WARN("skipped: ../shared/data/" << prefix << name << " not found");
    else
      meshes.emplace_back(name, read(path));
  }
}

// Unit vector-area normal of face f.
Eigen::Vector3d face_normal(const Mesh& mesh, int f) {
  const auto face = mesh.face(f);
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < face.size(); ++k)
    v += mesh.position(face[k]).cross(mesh.position(face[(k + 1) % face.size()]));
  return v.normalized();
}

// The generic checks of an operator set: symmetric, S 1 = 0, x^T S x <= 0, S = D G, shapes.
void check_properties(const OperatorSet& ops, int n) {
  REQUIRE(ops.S.rows() == n);
  REQUIRE(ops.S.cols() == n);
  const double s = max_abs(ops.S);
  REQUIRE(s > 0);
  CHECK(relative_difference(ops.S, SparseMatrix(ops.S.transpose())) < 1e-13);
  CHECK((ops.S * Eigen::VectorXd::Ones(n)).cwiseAbs().maxCoeff() <= 1e-12 * s);
  std::mt19937 rng(5);
  std::normal_distribution<double> N;
  for (int trial = 0; trial < 8; ++trial) {
    Eigen::VectorXd x(n);
    for (int i = 0; i < n; ++i) x[i] = N(rng);
    CHECK(x.dot(ops.S * x) <= 1e-12 * s * x.squaredNorm());
  }
  REQUIRE(ops.G.cols() == n);
  REQUIRE(ops.D.rows() == n);
  CHECK(relative_difference(SparseMatrix(ops.D * ops.G), ops.S) < 1e-12);
  REQUIRE(ops.M_lumped.size() == n);
  CHECK(ops.M_lumped.minCoeff() >= 0);
  CHECK((ops.M * Eigen::VectorXd::Ones(n) - ops.M_lumped).cwiseAbs().maxCoeff() <=
        1e-12 * ops.M_lumped.maxCoeff());
}

// max over interior vertices and coordinates c of |(S x_c)_v| / (|S|_max * |x_c|_max).
template <class AnyMesh>
double interior_linear_defect(const AnyMesh& mesh, const SparseMatrix& S) {
  double worst = 0;
  const double s = max_abs(S);
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd u = mesh.positions().col(c);
    const double umax = u.cwiseAbs().maxCoeff();
    if (umax == 0) continue;
    const Eigen::VectorXd r = S * u;
    for (int v = 0; v < mesh.n_vertices(); ++v)
      if (!mesh.is_boundary_vertex(v)) worst = std::max(worst, std::abs(r[v]) / (s * umax));
  }
  return worst;
}

// Interior vertices moved in the plane z = 0 by up to `amplitude` times the mean edge length.
Mesh planar_jitter(const Mesh& mesh, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  Eigen::MatrixX3d X = mesh.positions();
  const double h = mesh.mean_edge_length();
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (!mesh.is_boundary_vertex(v)) {
      X(v, 0) += amplitude * h * U(rng);
      X(v, 1) += amplitude * h * U(rng);
    }
  return mesh.with_positions(X);
}

}  // namespace

TEST_CASE("diamond (surface): symmetric, S 1 = 0, negative semi-definite, S = D G, mass = area",
          "[diamond]") {
  std::vector<std::pair<std::string, Mesh>> meshes{{"hex grid", hex_grid(6, 5)},
                                                   {"noisy uv sphere", add_noise(uv_sphere(6, 8), 0.2, 3)},
                                                   {"cube sphere", cube_sphere(3)},
                                                   {"torus", torus(8, 6)}};
  add_shared(meshes, "", {"L-plane.obj", "tetris_2.obj", "noisy-sphere.off"},
             [](const std::string& p) { return read_mesh(p); });
  for (const auto& [name, mesh] : meshes) {
    INFO(name);
    const OperatorSet ops = build_operators(mesh, parse_laplacian("diamond"));
    CHECK(ops.name == "diamond");
    CHECK(ops.n_degenerate_triangles == 0);
    check_properties(ops, mesh.n_vertices());
    CHECK(ops.G.rows() == 3 * mesh.n_edges());
    // The lumped masses sum to the diamonds' total area (the area for planar polygons, checked below;
    // less on curved meshes, where a diamond is flattened across its edge).
    CHECK(ops.M_lumped.sum() == Approx(surface_diamonds(mesh, refine(mesh)).weight.sum()).epsilon(1e-12));
    CHECK(ops.M_lumped.sum() <= surface_area(mesh) * (1 + 1e-12));
  }
  // Planar polygons: the diamond areas sum to the area exactly.
  const Mesh hex = hex_grid(6, 5);
  CHECK(diamond_operators(hex).M_lumped.sum() == Approx(surface_area(hex)).epsilon(1e-12));
}

TEST_CASE("diamond (surface): linear precision at interior vertices of planar polygon meshes", "[diamond]") {
  std::vector<std::pair<std::string, Mesh>> meshes{
      {"hex grid", hex_grid(7, 6)},
      {"jittered hex grid", planar_jitter(hex_grid(7, 6), 0.15, 2)},
      {"jittered quad grid", planar_jitter(quad_grid(6, 7), 0.2, 3)},
      {"jittered triangle grid", planar_jitter(triangle_grid(6, 6), 0.15, 4)}};
  add_shared(meshes, "", {"quad-plane.obj", "L-plane.obj", "tetris.obj", "tetris_2.obj"},
             [](const std::string& p) { return read_mesh(p); });
  for (const auto& [name, mesh] : meshes) {
    INFO(name);
    const OperatorSet ops = diamond_operators(mesh);
    REQUIRE(ops.n_folded_triangles == 0);  // a folded diamond breaks the Green-formula cancellation
    CHECK(interior_linear_defect(mesh, ops.S) < 1e-11);
    // The gradient of a linear function is exact on every diamond (virtual points interpolate linearly).
    const Eigen::Vector3d normal = face_normal(mesh, 0);
    Eigen::Vector3d grad(0.7, -1.3, 0.4);
    grad -= grad.dot(normal) * normal;  // in the mesh's plane
    const Eigen::VectorXd u = mesh.positions() * grad;
    const Eigen::VectorXd Gu = ops.G * u;
    for (int e = 0; e < mesh.n_edges(); ++e)
      CHECK((Gu.segment<3>(3 * e) - grad).norm() < 1e-10 * grad.norm());
  }
}

TEST_CASE("diamond (surface): rigid motions leave S, M unchanged, scaling leaves S unchanged", "[diamond]") {
  const Mesh mesh = add_noise(cube_sphere(3), 0.15, 7);
  const OperatorSet ops = diamond_operators(mesh);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::MatrixX3d moved = (mesh.positions() * R.transpose()).rowwise() + Eigen::RowVector3d(3, -7, 11);
  const OperatorSet rot = diamond_operators(mesh.with_positions(moved));
  CHECK(relative_difference(rot.S, ops.S) < 1e-11);
  CHECK(relative_difference(rot.M, ops.M) < 1e-11);
  // The gradient turns with the mesh.
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(mesh.n_vertices(), -1, 2);
  const Eigen::VectorXd g = ops.G * u, g_rot = rot.G * u;
  double worst = 0;
  for (int e = 0; e < mesh.n_edges(); ++e)
    worst = std::max(worst, (R * g.segment<3>(3 * e) - g_rot.segment<3>(3 * e)).norm());
  CHECK(worst < 1e-10 * g.cwiseAbs().maxCoeff());
  for (double scale : {1e-6, 1e6}) {
    const OperatorSet sc = diamond_operators(mesh.with_positions(scale * mesh.positions()));
    CHECK(relative_difference(sc.S, ops.S) < 1e-10);                                  // dimensionless in 2D
    CHECK(relative_difference(SparseMatrix(sc.M / (scale * scale)), ops.M) < 1e-10);  // area
  }
}

TEST_CASE("diamond on planar triangle meshes: the area-weighted mean of the two cotangent gradients",
          "[diamond]") {
  // Derived here (the relation the paper's authors state was not available to check): on a triangle
  // the squared-area virtual point is the centroid, where the linear interpolant's value is the
  // mean of the corners, so on a planar triangle mesh the Green formula over the diamond of edge e
  // integrates the piecewise linear u exactly: G_e u = (A_f grad u_f + A_g grad u_g) / (A_f + A_g)
  // (boundary edges: grad u_f). Each diamond holds a third of each of its triangles, so by Jensen's
  // inequality -u^T S u <= -u^T S_cot u: S - S_cot is positive semi-definite, and S != S_cot.
  const Mesh mesh = planar_jitter(triangle_grid(5, 6), 0.15, 11);
  const OperatorSet ops = diamond_operators(mesh);
  const Refinement r = refine(mesh);
  for (double w : r.weights) CHECK(w == Approx(1.0 / 3).epsilon(1e-12));
  const int nF = mesh.n_faces();
  std::vector<double> area(nF);
  std::vector<Eigen::Matrix3d> grads(nF);  // column k: gradient of corner k's hat function
  for (int f = 0; f < nF; ++f) {
    const auto t = mesh.face(f);
    const Eigen::Vector3d p[3] = {mesh.position(t[0]), mesh.position(t[1]), mesh.position(t[2])};
    const Eigen::Vector3d n2 = (p[1] - p[0]).cross(p[2] - p[0]);
    area[f] = n2.norm() / 2;
    for (int k = 0; k < 3; ++k)
      grads[f].col(k) = n2.normalized().cross(p[(k + 2) % 3] - p[(k + 1) % 3]) / n2.norm();
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  Eigen::VectorXd u(mesh.n_vertices());
  for (int v = 0; v < mesh.n_vertices(); ++v) u[v] = U(rng);
  auto tri_grad = [&](int f) {
    const auto t = mesh.face(f);
    return Eigen::Vector3d(grads[f] * Eigen::Vector3d(u[t[0]], u[t[1]], u[t[2]]));
  };
  const Eigen::VectorXd Gu = ops.G * u;
  double worst = 0, gmax = 0;
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    const int o = mesh.halfedge_opposite(h), f = mesh.halfedge_face(h);
    if (o >= 0 && o < h) continue;
    const Eigen::Vector3d expected =
        o < 0 ? tri_grad(f)
              : Eigen::Vector3d(
                    (area[f] * tri_grad(f) + area[mesh.halfedge_face(o)] * tri_grad(mesh.halfedge_face(o))) /
                    (area[f] + area[mesh.halfedge_face(o)]));
    worst = std::max(worst, (Gu.segment<3>(3 * mesh.halfedge_edge(h)) - expected).norm());
    gmax = std::max(gmax, expected.norm());
  }
  CHECK(worst < 1e-10 * gmax);
  const SparseMatrix S_cot = test::plain_cotan(mesh).S;
  const Eigen::VectorXd ev =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(ops.S - S_cot)).eigenvalues();
  CHECK(ev.minCoeff() >= -1e-12 * max_abs(S_cot));
  CHECK(ev.maxCoeff() > 1e-2 * max_abs(S_cot));  // not the cotangent Laplacian
  CHECK(relative_difference(ops.S, S_cot) > 1e-2);
}

TEST_CASE("diamond (surface) on degenerate polygons: finite, counted, S 1 = 0", "[diamond][robust]") {
  // A collinear triangle hanging off the bottom boundary edge (a, b) of a quad grid: its two boundary
  // edges' diamonds are flat (degenerate); thin quads (a row collapsed to 1e-9 of the spacing) too.
  const Mesh grid = quad_grid(3, 3);
  PolygonSoup s;
  s.positions = grid.positions();
  s.face_offsets = grid.face_offsets();
  s.face_indices = grid.face_indices();
  int a = -1, b = -1;
  for (int v = 0; v < grid.n_vertices(); ++v) {
    if (grid.position(v).norm() < 1e-12) a = v;
    if ((grid.position(v) - Eigen::Vector3d(1.0 / 3, 0, 0)).norm() < 1e-12) b = v;
  }
  REQUIRE(a >= 0);
  REQUIRE(b >= 0);
  s.positions.conservativeResize(s.n_vertices() + 1, 3);
  s.positions.row(s.n_vertices() - 1) << 1.5, 0, 0;
  s.add_face(std::vector<int>{b, a, s.n_vertices() - 1});
  Eigen::MatrixX3d thin = grid.positions();
  for (int v = 0; v < grid.n_vertices(); ++v)
    if (std::abs(thin(v, 1) - 1.0 / 3) < 1e-12) thin(v, 1) = 1e-9;
  for (const Mesh& mesh : {Mesh(s), grid.with_positions(thin)}) {
    const OperatorSet ops = diamond_operators(mesh);
    CHECK(ops.n_degenerate_triangles > 0);
    CHECK(ops.S.coeffs().allFinite());
    CHECK(ops.G.coeffs().allFinite());
    CHECK(ops.M.coeffs().allFinite());
    const double sc = max_abs(ops.S);
    CHECK(relative_difference(ops.S, SparseMatrix(ops.S.transpose())) < 1e-13);
    CHECK((ops.S * Eigen::VectorXd::Ones(mesh.n_vertices())).cwiseAbs().maxCoeff() <= 1e-12 * sc);
    CHECK(relative_difference(SparseMatrix(ops.D * ops.G), ops.S) < 1e-12);
  }
}

TEST_CASE("diamond (volume) on a squashed cube: degenerate sub-diamonds counted, operators finite",
          "[diamond][robust]") {
  const VolumeMesh cube = hex_grid_volume(1, 1, 1);
  Eigen::MatrixX3d X = cube.positions();
  X.col(2) *= 1e-12;
  const OperatorSet ops = volume_diamond_operators(cube.with_positions(X));
  CHECK(ops.n_degenerate_triangles == 24);  // 6 faces x 4 edges, all flat
  CHECK(ops.S.coeffs().allFinite());
  CHECK(ops.G.coeffs().allFinite());
  CHECK(max_abs(ops.S) == 0);
}

TEST_CASE("diamond (volume): symmetric, null space, semi-definite, S = D G, mass = volume, linear precision",
          "[diamond][volume]") {
  std::vector<std::pair<std::string, VolumeMesh>> meshes{
      {"hex grid", hex_grid_volume(3, 4, 3)},
      {"jittered hex grid", hex_grid_volume(4, 4, 4, VolumeJitter{0.2, 5})},
      {"pyramids", pyramid_grid_volume(2, 3, 2)},
      {"truncated octahedra", truncated_octahedra_volume(2)},
      {"tets", tet_grid_volume(3, 3, 3)},
      {"jittered tets", tet_grid_volume(3, 3, 3, VolumeJitter{0.2, 6})}};
  add_shared(meshes, "volume/",
             {"cube_hexahedron_2.ovm", "cube_pyramids_2.ovm", "cube_truncated_2.ovm",
              "cube_tetrahedron_1.ovm", "noisycube.ovm"},
             [](const std::string& p) { return read_volume_mesh(p); });
  for (const auto& [name, mesh] : meshes) {
    INFO(name);
    const OperatorSet ops = build_volume_operators(mesh, parse_volume_laplacian("diamond"));
    CHECK(ops.name == "diamond");
    CHECK(ops.n_degenerate_triangles == 0);
    REQUIRE(ops.n_folded_triangles == 0);
    check_properties(ops, mesh.n_vertices());
    // The sub-diamonds tile the refinement's tetrahedra: the volume (up to the non-planar faces of the
    // noisy cube, which mesh.volume() splits at their vertex centroids instead of the face points).
    CHECK(ops.M_lumped.sum() == Approx(mesh.volume()).epsilon(name == "noisycube.ovm" ? 1e-3 : 1e-12));
    // Linear precision holds at interior vertices whatever the faces' planarity: every sub-diamond
    // boundary triangle not on the mesh boundary is shared by two sub-diamonds with opposite normals.
    CHECK(interior_linear_defect(mesh, ops.S) < 1e-11);
    const Eigen::Vector3d grad(0.4, -1.1, 0.8);
    const Eigen::VectorXd Gu = ops.G * (mesh.positions() * grad);
    CHECK((Gu - grad.replicate(Gu.size() / 3, 1)).cwiseAbs().maxCoeff() < 1e-10 * grad.norm());
    // VolumeLaplacian output agrees with the OperatorSet.
    const VolumeLaplacian V = assemble_volume_diamond(mesh, refine_volume(mesh));
    CHECK(relative_difference(V.S, ops.S) < 1e-14);
    CHECK(relative_difference(V.M, ops.M) < 1e-14);
  }
}

TEST_CASE("diamond (volume): S scales like h, M like h^3, rigid motions change nothing",
          "[diamond][volume]") {
  const VolumeMesh mesh = truncated_octahedra_volume(2, VolumeJitter{0.15, 9});
  const OperatorSet ops = volume_diamond_operators(mesh, {.with_gradient = false});
  for (double scale : {1e-4, 1e4}) {
    const OperatorSet sc =
        volume_diamond_operators(mesh.with_positions(scale * mesh.positions()), {.with_gradient = false});
    CHECK(relative_difference(SparseMatrix(sc.S / scale), ops.S) < 1e-10);
    CHECK(relative_difference(SparseMatrix(sc.M / (scale * scale * scale)), ops.M) < 1e-10);
  }
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(-1.1, Eigen::Vector3d(2, 1, -1).normalized()).toRotationMatrix();
  const OperatorSet rot = volume_diamond_operators(
      mesh.with_positions((mesh.positions() * R.transpose()).rowwise() + Eigen::RowVector3d(-4, 2, 9)),
      {.with_gradient = false});
  CHECK(relative_difference(rot.S, ops.S) < 1e-10);
  CHECK(relative_difference(rot.M, ops.M) < 1e-10);
}

TEST_CASE("diamond (volume): 3D Franke Poisson converges with slope 2 on hex grids", "[diamond][volume]") {
  // Measured (Galerkin-slot mass M = P^T M^fine P, the default): docs/volumes.md.
  std::vector<VolumeMesh> meshes;
  std::vector<std::string> labels;
  for (int n : {8, 16, 24}) {
    meshes.push_back(hex_grid_volume(n, n, n));
    labels.push_back(std::to_string(n));
  }
  const auto s =
      volume_franke_convergence("hex grid", meshes, labels, false, parse_volume_laplacian("diamond"));
  for (size_t i = 0; i < s.l2_slopes.size(); ++i) {
    INFO("level " << i << ": l2 slope " << s.l2_slopes[i] << ", rms slope " << s.rms_slopes[i]);
    CHECK(s.errors[i + 1].l2_error < s.errors[i].l2_error);
  }
  CHECK(std::abs(s.l2_slopes.back() - 2) < 0.3);
  CHECK(std::abs(s.rms_slopes.back() - 2) < 0.3);
}

}  // namespace test_diamond
