// tests/dec/surface/test_mesh_complex.cpp — DEC on the mesh's own cells: the per-polygon kernel's
// identities, d1 d0 = 0, P_{k+1} d_k = d_k^f P_k to round-off, the stars against P_k^T star_k^f P_k
// built from the refined stars, S = -d0^T star1 d0 against the paper's S, positive definiteness by
// Cholesky, independence of where a face's vertex list starts, and constant 2-forms reproduced.
#include <Eigen/SparseCholesky>
#include <catch2/catch.hpp>
#include <random>

#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/surface/mesh_complex.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/operators/surface/laplacian.h"
#include "tests/support/feec_meshes.h"

using namespace polydec;

namespace test_mesh_complex {
using polydec::test::relative_difference;

namespace {

// Blocks of 2 x 2 unit squares, each an L-shaped octagon (three squares, a reflex corner and
// collinear corners) and one quad, jittered off the plane by `lift`.
Mesh l_block_grid(int bx, int by, double lift) {
  PolygonSoup s;
  const int nx = 2 * bx + 1, ny = 2 * by + 1;
  s.positions.resize(nx * ny, 3);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) s.positions.row(i + nx * j) << i, j, lift * U(rng);
  auto v = [&](int i, int j) { return i + nx * j; };
  for (int J = 0; J < by; ++J)
    for (int I = 0; I < bx; ++I) {
      const int i = 2 * I, j = 2 * J;
      const int L[8] = {v(i, j), v(i + 1, j), v(i + 2, j), v(i + 2, j + 1), v(i + 1, j + 1), v(i + 1, j + 2),
                        v(i, j + 2), v(i, j + 1)};
      const int Q[4] = {v(i + 1, j + 1), v(i + 2, j + 1), v(i + 2, j + 2), v(i + 1, j + 2)};
      s.add_face(L);
      s.add_face(Q);
    }
  return Mesh(std::move(s));
}

std::vector<std::pair<std::string, Mesh>> meshes() {
  auto m = polydec::test::feec_meshes();
  m.emplace_back("L-shaped octagons and quads", l_block_grid(3, 2, 0.0));
  m.emplace_back("non-planar L-shaped octagons", l_block_grid(2, 2, 0.15));
  return m;
}

// The same mesh with every face's vertex list started at another corner.
Mesh rotated_faces(const Mesh& mesh) {
  PolygonSoup s;
  s.positions = mesh.positions();
  s.precision = mesh.precision();  // the same planarity decisions
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    std::vector<int> r(face.begin(), face.end());
    std::rotate(r.begin(), r.begin() + (f % int(r.size())), r.end());
    s.add_face(r);
  }
  return Mesh(std::move(s));
}

}  // namespace

TEST_CASE("polygon_cochain_maps: commutation on one polygon, start independence, both rules",
          "[mesh-complex]") {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(0.05, 1.0);
  for (int n : {3, 4, 5, 8, 13}) {
    std::vector<double> w(n), a(n);
    double sw = 0;
    for (int k = 0; k < n; ++k) sw += (w[k] = U(rng));
    for (double& x : w) x /= sw;
    for (double& x : a) x = U(rng);
    a[1] = -0.1;  // an inverted fan triangle
    for (SpokeRule rule : {SpokeRule::AreaConsistent, SpokeRule::MinimumNorm}) {
      const PolygonCochainMaps K = polygon_cochain_maps(w, a, rule);
      REQUIRE(std::abs(K.fractions.sum() - 1) <= 1e-14);
      // Fan triangle k's boundary: side k + spoke k+1 - spoke k = alpha_k times the face cycle.
      for (int k = 0; k < n; ++k) {
        Eigen::RowVectorXd row = K.spokes.row((k + 1) % n) - K.spokes.row(k);
        row[k] += 1.0;
        CHECK((row.array() - K.fractions[k]).abs().maxCoeff() <= 1e-14);
      }
      // Exact 1-forms: spoke i carries sum_j w_j (u_j - u_i).
      Eigen::VectorXd u = Eigen::VectorXd::Random(n), e(n);
      for (int k = 0; k < n; ++k) e[k] = u[(k + 1) % n] - u[k];
      const Eigen::VectorXd wv = Eigen::Map<const Eigen::VectorXd>(w.data(), n);
      for (int i = 0; i < n; ++i) CHECK(std::abs(K.spokes.row(i).dot(e) - (wv.dot(u) - u[i])) <= 1e-14);
      if (rule == SpokeRule::MinimumNorm) {
        CHECK((K.fractions.array() - 1.0 / n).abs().maxCoeff() <= 1e-15);
        CHECK(K.spokes.rowwise().sum().cwiseAbs().maxCoeff() <= 1e-14);  // each row orthogonal to the cycle
      } else {
        const double total = Eigen::Map<const Eigen::VectorXd>(a.data(), n).sum();
        for (int k = 0; k < n; ++k) CHECK(std::abs(K.fractions[k] - a[k] / total) <= 1e-15);
      }
      // Start the polygon at corner 2: the same maps, rotated.
      std::vector<double> w2(n), a2(n);
      for (int k = 0; k < n; ++k) w2[k] = w[(k + 2) % n], a2[k] = a[(k + 2) % n];
      const PolygonCochainMaps K2 = polygon_cochain_maps(w2, a2, rule);
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) CHECK(std::abs(K2.spokes(i, k) - K.spokes((i + 2) % n, (k + 2) % n)) <= 1e-14);
    }
  }
  CHECK_THROWS_AS(polygon_cochain_maps(std::vector<double>{0.5, 0.5}, std::vector<double>{1, 1}),
                  std::invalid_argument);
  CHECK(parse_dec_complex("mesh") == DecComplex::Mesh);
  CHECK(parse_spoke_rule(to_string(SpokeRule::MinimumNorm)) == SpokeRule::MinimumNorm);
  CHECK_THROWS_AS(parse_dec_complex("full"), std::invalid_argument);
}

TEST_CASE("mesh complex: d1 d0 = 0, P commutes with d, stars are P^T star^f P and S = -d0^T star1 d0",
          "[mesh-complex]") {
  for (const auto& [name, mesh] : meshes()) {
    INFO(name);
    const Refinement R = refine(mesh);
    for (SpokeRule rule : {SpokeRule::AreaConsistent, SpokeRule::MinimumNorm}) {
      INFO(to_string(rule));
      const SurfaceDec D = surface_dec(mesh, R, {.max_degree = 2, .complex = DecComplex::Mesh, .spoke_rule = rule});
      REQUIRE(D.d[0].rows() == mesh.n_edges());
      REQUIRE(D.d[0].cols() == mesh.n_vertices());
      REQUIRE(D.d[1].rows() == mesh.n_faces());
      CHECK((D.d[1] * D.d[0]).norm() == 0.0);
      const SparseMatrix rd0 = refined_d0(mesh), rd1 = refined_d1(mesh);
      // Commutation to round-off (P entries are O(1)).
      CHECK(relative_difference(D.P[1] * D.d[0], rd0 * D.P[0]) <= 1e-13);
      CHECK(relative_difference(D.P[2] * D.d[1], rd1 * D.P[1]) <= 1e-13);
      // Stars through an independent route: the refined stars and the prolongations.
      const SparseMatrix s1 = D.P[1].transpose() * refined_star1(mesh, R) * D.P[1];
      const SparseMatrix s2 = D.P[2].transpose() * refined_star2(mesh, R) * D.P[2];
      CHECK(relative_difference(D.star[1], s1) <= 1e-12);
      CHECK(relative_difference(D.star[2], s2) <= 1e-12);
      CHECK(relative_difference(D.star[1], SparseMatrix(D.star[1].transpose())) == 0.0);
      // The paper's stiffness from the mesh complex.
      const SparseMatrix S = stiffness(mesh, R);
      CHECK(relative_difference(SparseMatrix(-D.d[0].transpose() * D.star[1] * D.d[0]), S) <= 1e-12);
      CHECK(relative_difference(D.star[0], mass(mesh, R)) <= 1e-13);
      // Positive definite: Cholesky succeeds (no degenerate fan triangle on these meshes).
      if (R.quality.n_degenerate == 0) {
        Eigen::SimplicialLDLT<SparseMatrix> c1(D.star[1]), c2(D.star[2]);
        REQUIRE(c1.info() == Eigen::Success);
        REQUIRE(c2.info() == Eigen::Success);
        CHECK(c1.vectorD().minCoeff() > 0);
        CHECK(c2.vectorD().minCoeff() > 0);
      }
    }
  }
}

TEST_CASE("mesh complex: star2 is 1/area, constant 2-forms reproduced, no dependence on the list start",
          "[mesh-complex]") {
  for (const auto& [name, mesh] : meshes()) {
    INFO(name);
    const Refinement R = refine(mesh);
    const SurfaceDec D = surface_dec(mesh, R, {.complex = DecComplex::Mesh});
    const Eigen::VectorXd a = signed_fan_areas(mesh, R);
    // The area cochain of the face (A_f = sum of signed fan areas) prolongs to the signed fan areas.
    Eigen::VectorXd A = Eigen::VectorXd::Zero(mesh.n_faces());
    for (int h = 0; h < mesh.n_halfedges(); ++h) A[mesh.halfedge_face(h)] += a[h];
    const Eigen::VectorXd fine = D.P[2] * A;
    bool inverted = false;
    for (int h = 0; h < mesh.n_halfedges(); ++h) {
      CHECK(std::abs(fine[h] - refined_triangle_sign(mesh, h) * a[h]) <= 1e-13 * std::abs(A[mesh.halfedge_face(h)]));
      inverted = inverted || a[h] < 0;
    }
    if (!inverted && R.quality.n_degenerate == 0)
      for (int f = 0; f < mesh.n_faces(); ++f) CHECK(std::abs(D.star[2].coeff(f, f) * A[f] - 1) <= 1e-12);
    // Another start of every face's list: same edges and faces, so the same d and stars.
    const Mesh rot = rotated_faces(mesh);
    const SurfaceDec E = surface_dec(rot, refine(rot), {.complex = DecComplex::Mesh});
    CHECK(relative_difference(D.d[1], E.d[1]) == 0.0);
    CHECK(relative_difference(D.star[1], E.star[1]) <= 1e-12);
    CHECK(relative_difference(D.star[2], E.star[2]) <= 1e-12);
  }
}

TEST_CASE("mesh complex: sizes, the shorthand overload and bad input", "[mesh-complex]") {
  const Mesh mesh = polydec::hex_grid(3, 3);
  const Refinement R = refine(mesh);
  const SurfaceDec D = surface_dec(mesh, R, {.max_degree = 1, .complex = DecComplex::Mesh});
  CHECK(D.complex == DecComplex::Mesh);
  CHECK(D.star[1].rows() == mesh.n_edges());
  CHECK(D.d[1].size() == 0);
  CHECK(D.star[2].size() == 0);
  // Non-zeros: an n-gon couples its n sides only.
  long bound = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) bound += long(mesh.face_size(f)) * mesh.face_size(f);
  CHECK(D.star[1].nonZeros() <= bound);
  const SurfaceDec C = surface_dec(mesh, R, 1);
  CHECK(C.complex == DecComplex::Complete);
  CHECK(C.star[1].rows() == C.coarse.n_pairs());
  Refinement other = refine(polydec::hex_grid(2, 2));
  CHECK_THROWS_AS(mesh_star1(mesh, other), std::invalid_argument);
  CHECK_THROWS_AS(surface_dec(mesh, R, {.max_degree = 3, .complex = DecComplex::Mesh}), std::invalid_argument);
}

}  // namespace test_mesh_complex
