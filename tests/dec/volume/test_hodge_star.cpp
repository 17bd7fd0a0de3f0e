// tests/dec/volume/test_hodge_star.cpp — DEC on polyhedral volume meshes: the Whitney kernels of a
// tetrahedron against quadrature and their defining integrals, d_{k+1} d_k = 0, the commuting
// relations P_{k+1} d_k = d_k^tet P_k, S = -d0^T star1 d0 and star0 = M, the stars on tetrahedral
// meshes against the Whitney stars of the tetrahedra themselves, ranks, and solving on the span.
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <catch2/catch.hpp>
#include <random>

#include "polydec/apps/applications/volume/hodge_decomposition.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/dec/volume/mesh_complex.h"
#include "polydec/dec/volume/whitney.h"
#include "polydec/operators/solvers/span_solver.h"
#include "polydec/operators/volume/laplacian.h"
#include "tests/support/volume_meshes.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_dec {
using polydec::test::relative_difference;

namespace {

constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
constexpr int kTris[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};

// Gradients of the barycentric coordinates from the inverse of [1 p] (independent of the library).
Eigen::Matrix<double, 3, 4> plain_gradients(const Eigen::Vector3d p[4], double& vol) {
  Eigen::Matrix4d A;
  for (int a = 0; a < 4; ++a) A.row(a) << 1.0, p[a].transpose();
  vol = std::abs(A.determinant()) / 6.0;
  return A.inverse().bottomRows(3);
}

Eigen::Vector3d w1(const Eigen::Matrix<double, 3, 4>& G, int e, const Eigen::Vector4d& l) {
  const int a = kEdges[e][0], b = kEdges[e][1];
  return l(a) * G.col(b) - l(b) * G.col(a);
}
Eigen::Vector3d w2(const Eigen::Matrix<double, 3, 4>& G, int t, const Eigen::Vector4d& l) {
  const int a = kTris[t][0], b = kTris[t][1], c = kTris[t][2];
  return 2 * (l(a) * G.col(b).cross(G.col(c)) + l(b) * G.col(c).cross(G.col(a)) +
              l(c) * G.col(a).cross(G.col(b)));
}

double max_abs(const SparseMatrix& A) { return A.nonZeros() ? A.coeffs().cwiseAbs().maxCoeff() : 0.0; }

}  // namespace

TEST_CASE("Whitney forms of a tetrahedron: quadrature, unit integrals, d0/d1 energies",
          "[volume][volume-dec]") {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::Vector3d p[4];
    for (auto& q : p) q = Eigen::Vector3d(u(rng), u(rng), u(rng));
    double vol = 0;
    const Eigen::Matrix<double, 3, 4> G = plain_gradients(p, vol);
    // Degree-2 exact 4-point rule.
    const double alpha = 0.5854101966249685, beta = 0.1381966011250105;
    Matrix6d Q1 = Matrix6d::Zero();
    Eigen::Matrix4d Q2 = Eigen::Matrix4d::Zero();
    for (int q = 0; q < 4; ++q) {
      Eigen::Vector4d l = Eigen::Vector4d::Constant(beta);
      l(q) = alpha;
      Eigen::Matrix<double, 3, 6> W1;
      Eigen::Matrix<double, 3, 4> W2;
      for (int e = 0; e < 6; ++e) W1.col(e) = w1(G, e, l);
      for (int t = 0; t < 4; ++t) W2.col(t) = w2(G, t, l);
      Q1 += vol / 4 * W1.transpose() * W1;
      Q2 += vol / 4 * W2.transpose() * W2;
    }
    const Matrix6d M1 = tet_whitney1_mass(p[0], p[1], p[2], p[3]);
    const Eigen::Matrix4d M2 = tet_whitney2_mass(p[0], p[1], p[2], p[3]);
    CHECK((M1 - Q1).norm() <= 1e-11 * Q1.norm());
    CHECK((M2 - Q2).norm() <= 1e-11 * Q2.norm());
    CHECK(std::abs(tet_whitney3_mass(p[0], p[1], p[2], p[3]) - 1 / vol) <= 1e-12 / vol);
    // Each 1-form integrates to 1 along its own edge (a -> b), 0 along the others (midpoint rule).
    for (int e = 0; e < 6; ++e)
      for (int f = 0; f < 6; ++f) {
        Eigen::Vector4d l = Eigen::Vector4d::Zero();
        l(kEdges[f][0]) = l(kEdges[f][1]) = 0.5;
        const double integral = w1(G, e, l).dot(p[kEdges[f][1]] - p[kEdges[f][0]]);
        CHECK(std::abs(integral - (e == f ? 1.0 : 0.0)) < 1e-11);
      }
    // Each 2-form has flux 1 through its own triangle (a, b, c), 0 through the others.
    for (int t = 0; t < 4; ++t)
      for (int s = 0; s < 4; ++s) {
        const int a = kTris[s][0], b = kTris[s][1], c = kTris[s][2];
        Eigen::Vector4d l = Eigen::Vector4d::Zero();
        l(a) = l(b) = l(c) = 1.0 / 3;
        const double flux = w2(G, t, l).dot((p[b] - p[a]).cross(p[c] - p[a]) / 2);
        CHECK(std::abs(flux - (t == s ? 1.0 : 0.0)) < 1e-11);
      }
    // d0^T M1 d0 = -S and d1^T M2 d1 = vol curl^T curl (curl of phi_ab = 2 grad l_a x grad l_b).
    Eigen::Matrix<double, 6, 4> d0 = Eigen::Matrix<double, 6, 4>::Zero();
    Eigen::Matrix<double, 4, 6> d1 = Eigen::Matrix<double, 4, 6>::Zero();
    for (int e = 0; e < 6; ++e) d0(e, kEdges[e][0]) = -1, d0(e, kEdges[e][1]) = 1;
    for (int t = 0; t < 4; ++t) {
      const int a = kTris[t][0], b = kTris[t][1], c = kTris[t][2];
      d1(t, tet_local_edge(b, c)) += 1, d1(t, tet_local_edge(a, c)) -= 1, d1(t, tet_local_edge(a, b)) += 1;
    }
    const Eigen::Matrix4d S = tet_stiffness(p[0], p[1], p[2], p[3]);
    CHECK((d0.transpose() * M1 * d0 + S).norm() <= 1e-11 * S.norm());
    Eigen::Matrix<double, 3, 6> curl;
    for (int e = 0; e < 6; ++e) curl.col(e) = 2 * G.col(kEdges[e][0]).cross(G.col(kEdges[e][1]));
    const Matrix6d C = vol * curl.transpose() * curl;
    CHECK((d1.transpose() * M2 * d1 - C).norm() <= 1e-11 * C.norm());
    CHECK((d1 * d0).norm() == 0.0);
  }
}

TEST_CASE("volume DEC: d d = 0, commuting prolongations, S = -d0^T star1 d0, star0 = M",
          "[volume][volume-dec]") {
  Eigen::MatrixX3d Z = test::grid_positions(2, 2, 2);
  test::jitter_interior(Z, 2, 2, 2, 0.25, 9);
  Eigen::MatrixX3d T = test::grid_positions(2, 2, 2);
  test::jitter_interior(T, 2, 2, 2, 0.3, 4);
  const VolumeMesh meshes[] = {test::hex_grid_mesh(2, 2, 2, &Z), test::tet_grid_mesh(2, 2, 2, &T),
                               test::single_pyramid(), test::hex_solid_torus(5)};
  for (const VolumeMesh& mesh : meshes) {
    const VolumeRefinement R = refine_volume(mesh);
    const VolumeDec D = volume_dec(mesh, R);
    CHECK(max_abs(SparseMatrix(D.d[1] * D.d[0])) == 0.0);
    CHECK(max_abs(SparseMatrix(D.d[2] * D.d[1])) == 0.0);
    CHECK((D.d[0] * Eigen::VectorXd::Ones(mesh.n_vertices())).norm() == 0.0);
    SparseMatrix dr[3];
    for (int k = 0; k < 3; ++k) dr[k] = D.refined.d(k);
    CHECK(max_abs(SparseMatrix(dr[1] * dr[0])) == 0.0);
    CHECK(max_abs(SparseMatrix(dr[2] * dr[1])) == 0.0);
    for (int k = 0; k < 3; ++k) {
      const SparseMatrix lhs = D.P[k + 1] * D.d[k], rhs = dr[k] * D.P[k];
      CHECK(max_abs(SparseMatrix(lhs - rhs)) < 1e-12);
    }
    const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
    CHECK(relative_difference(SparseMatrix(-D.d[0].transpose() * D.star[1] * D.d[0]), L.S) < 1e-12);
    CHECK(relative_difference(D.star[0], L.M) < 1e-12);
    for (int k = 0; k < 4; ++k)
      CHECK(relative_difference(D.star[k], SparseMatrix(D.star[k].transpose())) < 1e-14);
  }
}

TEST_CASE("volume DEC on tetrahedral meshes: the stars are the Whitney stars of the tetrahedra",
          "[volume][volume-dec]") {
  Eigen::MatrixX3d T = test::grid_positions(2, 2, 1);
  test::jitter_interior(T, 2, 2, 1, 0.3, 8);
  const VolumeMesh mesh = test::tet_grid_mesh(2, 2, 1, &T);
  const VolumeDec D = volume_dec(mesh, refine_volume(mesh));
  std::vector<Eigen::Triplet<double>> t[4];
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const auto v = mesh.cell_vertices(c);  // ascending
    Eigen::Vector3d p[4];
    for (int a = 0; a < 4; ++a) p[a] = mesh.position(v[a]);
    const Eigen::Matrix4d M0 = tet_whitney0_mass(p[0], p[1], p[2], p[3]);
    const Matrix6d M1 = tet_whitney1_mass(p[0], p[1], p[2], p[3]);
    const Eigen::Matrix4d M2 = tet_whitney2_mass(p[0], p[1], p[2], p[3]);
    int e[6], f[4];
    for (int k = 0; k < 6; ++k) {
      const int s[2] = {v[kEdges[k][0]], v[kEdges[k][1]]};
      e[k] = D.coarse.index(s);
    }
    for (int k = 0; k < 4; ++k) {
      const int s[3] = {v[kTris[k][0]], v[kTris[k][1]], v[kTris[k][2]]};
      f[k] = D.coarse.index(s);
    }
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        t[0].emplace_back(v[a], v[b], M0(a, b)), t[2].emplace_back(f[a], f[b], M2(a, b));
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) t[1].emplace_back(e[a], e[b], M1(a, b));
    const int q[4] = {v[0], v[1], v[2], v[3]};
    t[3].emplace_back(D.coarse.index(q), D.coarse.index(q), tet_whitney3_mass(p[0], p[1], p[2], p[3]));
  }
  for (int k = 0; k < 4; ++k) {
    SparseMatrix W(D.coarse.n_simplices(k), D.coarse.n_simplices(k));
    W.setFromTriplets(t[k].begin(), t[k].end());
    CHECK(relative_difference(D.star[k], W) < 1e-11);
  }
  CHECK(D.coarse.n_quads() == mesh.n_cells());
}

TEST_CASE("volume DEC: ranks of the stars, positive definite on the span, solving on the span",
          "[volume][volume-dec]") {
  Eigen::MatrixX3d Z = test::grid_positions(2, 2, 1);
  test::jitter_interior(Z, 2, 2, 1, 0.25, 2);
  const VolumeMesh meshes[] = {test::hex_grid_mesh(1, 1, 1), test::hex_grid_mesh(2, 2, 1, &Z),
                               test::single_pyramid()};
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  for (const VolumeMesh& mesh : meshes) {
    const VolumeRefinement R = refine_volume(mesh);
    const VolumeDec D = volume_dec(mesh, R);
    for (int k = 1; k <= 3; ++k) {
      const FormSpan span = volume_form_span(D, mesh, R, k);
      const Eigen::MatrixXd star = Eigen::MatrixXd(D.star[k]);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(star);
      const double top = eig.eigenvalues().maxCoeff();
      CHECK(eig.eigenvalues().minCoeff() >= -1e-12 * top);
      int rank = 0;
      for (int i = 0; i < star.rows(); ++i) rank += eig.eigenvalues()(i) > 1e-10 * top;
      INFO("k = " << k << ", cells " << mesh.n_cells() << ", coarse simplices " << star.rows());
      CHECK(span.rank() == rank);
      const Eigen::MatrixXd reduced = Eigen::MatrixXd(span.R.transpose() * D.star[k] * span.R);
      CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(reduced).eigenvalues().minCoeff() > 1e-12 * top);
      const SpanSolver solver(D.star[k], span, "star" + std::to_string(k));
      Eigen::VectorXd y(star.rows());
      for (int i = 0; i < y.size(); ++i) y(i) = g(rng);
      const Eigen::VectorXd b = D.star[k] * y;
      const Eigen::VectorXd x = solver.solve(b);
      CHECK((D.star[k] * x - b).norm() <= 1e-9 * b.norm());
      // Same Whitney form: (x - y) has zero star-norm.
      CHECK(std::abs((x - y).dot(D.star[k] * (x - y))) <= 1e-12 * y.dot(b));
    }
    if (mesh.n_cells() == 1 && mesh.n_vertices() == 8) {
      // A single hexahedron: 28 pairs, 56 triples, 70 quadruples; report the ranks.
      CHECK(D.coarse.n_pairs() == 28);
      CHECK(D.coarse.n_triples() == 56);
      CHECK(D.coarse.n_quads() == 70);
    }
  }
}

TEST_CASE("volume Hodge decomposition: harmonic dimension is the first Betti number, on both complexes",
          "[volume][volume-dec][volume-mesh-complex]") {
  Eigen::MatrixX3d Z = test::grid_positions(2, 2, 2);
  test::jitter_interior(Z, 2, 2, 2, 0.2, 6);
  struct Case {
    VolumeMesh mesh;
    int betti1;
  };
  const Case cases[] = {{test::hex_grid_mesh(2, 2, 2, &Z), 0},
                        {test::tet_grid_mesh(2, 1, 1), 0},
                        {test::hex_solid_torus(6), 1}, {hex_torus_volume(8, 2, 1.0, 0.4, {0.15, 2}), 1},
                        {truncated_octahedra_volume(1), 0}};  // 24-vertex cells: the mesh complex only
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  for (DecComplex complex : {DecComplex::Complete, DecComplex::Mesh})
  for (const Case& c : cases) {
    if (complex == DecComplex::Complete && volume_dec_max_degree(c.mesh) < 2) continue;
    INFO(to_string(complex) << " complex, " << c.mesh.n_cells() << " cells");
    const VolumeHodgeDecomposer hodge(c.mesh, {}, complex);
    if (complex == DecComplex::Mesh) CHECK(hodge.dec().star[1].rows() == c.mesh.n_edges());
    CHECK(hodge.harmonic_dimension() == c.betti1);
    const VolumeDec& D = hodge.dec();
    const SparseMatrix& star1 = D.star[1];
    Eigen::VectorXd omega(star1.rows());
    for (int i = 0; i < omega.size(); ++i) omega(i) = g(rng);
    const HodgeParts p = hodge.decompose(omega);
    CHECK((p.exact + p.coexact + p.harmonic - omega).norm() <= 1e-12 * omega.norm());
    const double n2 = p.norm * p.norm;
    CHECK(std::abs(p.exact.dot(star1 * p.coexact)) <= 1e-9 * n2);
    CHECK(std::abs(p.exact.dot(star1 * p.harmonic)) <= 1e-9 * n2);
    CHECK(std::abs(p.coexact.dot(star1 * p.harmonic)) <= 1e-9 * n2);
    CHECK(std::abs(p.norm_exact * p.norm_exact + p.norm_coexact * p.norm_coexact +
                   p.norm_harmonic * p.norm_harmonic - n2) <= 1e-9 * n2);
    // Harmonic: closed (zero curl energy) and co-closed (d0^T star1 h = 0).
    const Eigen::VectorXd curl = D.d[1] * p.harmonic;
    const Eigen::VectorXd curl_omega = D.d[1] * omega;
    CHECK(curl.dot(D.star[2] * curl) <= 1e-16 * curl_omega.dot(D.star[2] * curl_omega));
    CHECK((D.d[0].transpose() * (star1 * p.harmonic)).norm() <=
          1e-9 * (D.d[0].transpose() * (star1 * omega)).norm() + 1e-12);
    if (c.betti1 > 0) CHECK(p.norm_harmonic > 1e-3 * p.norm);
    // The exact part of an exact form is the form itself.
    Eigen::VectorXd u(c.mesh.n_vertices());
    for (int i = 0; i < u.size(); ++i) u(i) = g(rng);
    const HodgeParts q = hodge.decompose(D.d[0] * u);
    CHECK(q.norm_coexact + q.norm_harmonic <= 1e-9 * q.norm);
    // On a refinement the caller holds: the same decomposition, bit for bit.
    const VolumeRefinement r = refine_volume(c.mesh);
    const HodgeParts p2 = VolumeHodgeDecomposer::on_refinement(c.mesh, r, complex).decompose(omega);
    CHECK(p2.exact == p.exact);
    CHECK(p2.harmonic == p.harmonic);
  }
  // Another mesh's refinement is refused.
  CHECK_THROWS_AS(VolumeHodgeDecomposer::on_refinement(cases[0].mesh, refine_volume(cases[1].mesh)),
                  std::invalid_argument);
}

}  // namespace test_volume_dec

namespace test_volume_dec {

namespace {

// Two meshes side by side as one (vertices, faces and cells of b after a's).
VolumeMesh disjoint_union(const VolumeMesh& a, const VolumeMesh& b) {
  PolyhedronSoup soup;
  soup.positions.resize(a.n_vertices() + b.n_vertices(), 3);
  soup.positions << a.positions(), b.positions();
  for (const VolumeMesh* m : {&a, &b}) {
    const int v0 = m == &a ? 0 : a.n_vertices(), f0 = m == &a ? 0 : a.n_faces();
    for (int f = 0; f < m->n_faces(); ++f) {
      std::vector<int> face(m->face(f).begin(), m->face(f).end());
      for (int& v : face) v += v0;
      soup.add_face(face);
    }
    for (int c = 0; c < m->n_cells(); ++c) {
      std::vector<int> hf(m->cell(c).begin(), m->cell(c).end());
      for (int& h : hf) h += 2 * f0;
      soup.add_cell(hf);
    }
  }
  return VolumeMesh(std::move(soup));
}

}  // namespace

TEST_CASE("closed_edge_generators: closed, not exact, as many as the first Betti number, on large meshes",
          "[volume][volume-mesh-complex]") {
  const VolumeMesh torus = hex_torus_volume(40, 5, 1.0, 0.4, {0.15, 4});
  const struct {
    VolumeMesh mesh;
    int betti1;
  } cases[] = {{torus, 1},
               {disjoint_union(torus, hex_torus_volume(12, 2, 1.0, 0.3)), 2},
               {hex_grid_volume(12, 10, 8, {0.2, 3}), 0},
               {truncated_octahedra_volume(4, {0.1, 5}), 0}};
  for (const auto& c : cases) {
    INFO(c.mesh.n_cells() << " cells, b1 = " << c.betti1);
    const SparseMatrix d0 = volume_mesh_d(c.mesh, 0), d1 = volume_mesh_d(c.mesh, 1);
    const Eigen::MatrixXd Z = closed_edge_generators(d0, d1);
    REQUIRE(Z.cols() == c.betti1);
    REQUIRE(Z.rows() == c.mesh.n_edges());
    for (long k = 0; k < Z.cols(); ++k) {
      CHECK((d1 * Z.col(k)).cwiseAbs().maxCoeff() <= 1e-12 * Z.col(k).cwiseAbs().maxCoeff());
      // Not exact: its least-squares distance to the exact cochains is a sizeable part of it.
      SparseMatrix Lr = d0.transpose() * d0;
      Lr.coeffRef(0, 0) += 1.0;  // the graph Laplacian made definite: one grounded vertex per component
      if (c.betti1 == 2) Lr.coeffRef(torus.n_vertices(), torus.n_vertices()) += 1.0;
      const Eigen::SimplicialLDLT<SparseMatrix> solver(Lr);
      const Eigen::VectorXd phi = solver.solve(Eigen::VectorXd(d0.transpose() * Z.col(k)));
      CHECK((Z.col(k) - d0 * phi).norm() > 0.1 * Z.col(k).norm());
    }
  }
  // The decomposition itself on the largest of them (the dense route of the complete complex would
  // need an eigen-decomposition of size |E|).
  const VolumeHodgeDecomposer hodge(cases[1].mesh, {}, DecComplex::Mesh);
  CHECK(hodge.harmonic_dimension() == 2);
  const Eigen::VectorXd omega = Eigen::VectorXd::LinSpaced(cases[1].mesh.n_edges(), -1.0, 1.0);
  const HodgeParts p = hodge.decompose(omega);
  const SparseMatrix& star1 = hodge.dec().star[1];
  CHECK((hodge.dec().d[0].transpose() * (star1 * p.harmonic)).norm() <=
        1e-9 * (hodge.dec().d[0].transpose() * (star1 * omega)).norm());
  CHECK((hodge.dec().d[1] * p.harmonic).norm() <= 1e-9 * (hodge.dec().d[1] * omega).norm());
  CHECK(std::abs(p.norm_exact * p.norm_exact + p.norm_coexact * p.norm_coexact +
                 p.norm_harmonic * p.norm_harmonic - p.norm * p.norm) <= 1e-9 * p.norm * p.norm);
}

TEST_CASE("volume stars store no exact zeros and equal P_k^T star_k^tet P_k exactly", "[volume][volume-dec][star-zeros]") {
  // Stored entries equal to zero, and those where two matrices differ.
  auto stored_zeros = [](const SparseMatrix& A) {
    long z = 0;
    for (int j = 0; j < A.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(A, j); it; ++it) z += it.value() == 0.0;
    return z;
  };
  auto differing_entries = [&](const SparseMatrix& A, const SparseMatrix& B) {
    const SparseMatrix D = A - B;
    return D.nonZeros() - stored_zeros(D);
  };
  Eigen::MatrixX3d Z = test::grid_positions(2, 2, 2);
  test::jitter_interior(Z, 2, 2, 2, 0.25, 9);
  const VolumeMesh meshes[] = {test::hex_grid_mesh(2, 2, 2, &Z), test::tet_grid_mesh(2, 2, 2), test::single_pyramid(),
                               test::prism_volume(5), test::hex_solid_torus(5)};
  for (const VolumeMesh& mesh : meshes) {
    const VolumeRefinement R = refine_volume(mesh);
    const VolumeDec D = volume_dec(mesh, R);
    for (int k = 0; k <= D.max_degree; ++k) {
      INFO("k = " << k);
      // The product as it was returned before: structural entries, zeros included.
      const SparseMatrix old =
          SparseMatrix(D.P[k].transpose() * volume_refined_star(mesh, R, D.refined, k) * D.P[k]);
      CHECK(stored_zeros(D.star[k]) == 0);
      CHECK(differing_entries(D.star[k], old) == 0);
      CHECK(D.star[k].nonZeros() == old.nonZeros() - stored_zeros(old));
    }
    const VolumeDec M = volume_dec(mesh, R, VolumeDecOptions{.complex = DecComplex::Mesh});
    for (int k = 0; k < 4; ++k) CHECK(stored_zeros(M.star[k]) == 0);
  }
}

}  // namespace test_volume_dec
