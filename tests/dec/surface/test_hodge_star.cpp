// tests/dec/surface/test_hodge_star.cpp — Whitney stars: the closed-form triangle kernels against
// quadrature, the coarse stars against P_k^T star_k^f P_k and against a plain per-triangle
// implementation on triangle meshes, S = -d0^T star1 d0, symmetry, semi-definiteness, scaling,
// and solving on the span.
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <random>

#include "polydec/dec/surface/form_span.h"
#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/dec/surface/whitney.h"
#include "polydec/operators/surface/laplacian.h"
#include "polydec/operators/solvers/span_solver.h"
#include "tests/support/feec_meshes.h"

using namespace polydec;

namespace test_hodge_star {
using polydec::test::relative_difference;

namespace {

// Plain reference: hat gradients from the tangent frame, Whitney 1-forms of the global pairs
// (u < v) evaluated at the edge midpoints (exact for the quadratic integrands).
struct PlainTriangle {
  Eigen::Matrix3d grad;  // columns: gradients of the barycentric coordinates of corners 0, 1, 2
  double area;
};

PlainTriangle plain_triangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                             const Eigen::Vector3d& p2) {
  Eigen::Matrix<double, 3, 2> T;
  T << p1 - p0, p2 - p0;
  const Eigen::Matrix<double, 3, 2> Tinv = T * (T.transpose() * T).inverse();  // g . t_k = rhs_k
  PlainTriangle t;
  t.grad.col(1) = Tinv * Eigen::Vector2d(1, 0);
  t.grad.col(2) = Tinv * Eigen::Vector2d(0, 1);
  t.grad.col(0) = -t.grad.col(1) - t.grad.col(2);
  t.area = 0.5 * std::sqrt((T.transpose() * T).determinant());
  return t;
}

// Mass of the Whitney 1-forms of corner pairs (a, b) in `edges`, by midpoint quadrature.
Eigen::Matrix3d quadrature_whitney1_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                         const Eigen::Vector3d& p2, const int edges[3][2]) {
  const PlainTriangle t = plain_triangle(p0, p1, p2);
  const Eigen::Vector3d mids[3] = {{0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (const auto& l : mids) {
    Eigen::Matrix3d W;
    for (int e = 0; e < 3; ++e) {
      const int a = edges[e][0], b = edges[e][1];
      W.col(e) = l[a] * t.grad.col(b) - l[b] * t.grad.col(a);
    }
    M += t.area / 3 * W.transpose() * W;
  }
  return M;
}

Eigen::SparseMatrix<double> symmetric_part_error(const Eigen::SparseMatrix<double>& A) {
  return A - Eigen::SparseMatrix<double>(A.transpose());
}

}  // namespace

TEST_CASE("closed-form Whitney 1-form mass equals quadrature on random 3D triangles", "[feec]") {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const int local[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d p0(U(rng), U(rng), U(rng)), p1(U(rng), U(rng), U(rng)), p2(U(rng), U(rng), U(rng));
    const Eigen::Matrix3d A = whitney1_mass(p0, p1, p2), B = quadrature_whitney1_mass(p0, p1, p2, local);
    CHECK((A - B).norm() <= 1e-11 * B.norm());
    CHECK((hat_gradients(p0, p1, p2) - plain_triangle(p0, p1, p2).grad).norm() <=
          1e-11 * hat_gradients(p0, p1, p2).norm());
    const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    CHECK(whitney2_mass(p0, p1, p2) == Approx(1 / area).epsilon(1e-13));
    CHECK(whitney0_mass(p0, p1, p2).sum() == Approx(area).epsilon(1e-13));
  }
}

TEST_CASE("on triangle meshes star1 is the standard Whitney mass and star2 = diag(1/area)", "[feec]") {
  std::vector<std::pair<std::string, Mesh>> meshes = {{"icosphere", test::icosphere(2)}};
  {
    // A jittered planar grid split into triangles, in 3D (tilted, with height noise).
    const Mesh g = test::planar_grid(6, 5, 0.3, false);
    PolygonSoup s;
    s.positions = g.positions();
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> U(-0.2, 0.2);
    for (long v = 0; v < s.positions.rows(); ++v) s.positions(v, 2) = 0.3 * s.positions(v, 0) + U(rng);
    for (int f = 0; f < g.n_faces(); ++f) {
      const auto q = g.face(f);
      s.add_face(std::vector<int>{q[0], q[1], q[2]});
      s.add_face(std::vector<int>{q[0], q[2], q[3]});
    }
    meshes.emplace_back("tilted triangulated grid", Mesh(std::move(s)));
  }
  if (const std::string p = test::shared_path("unit-sphere-low.off"); !p.empty())
    meshes.emplace_back("unit-sphere-low.off", read_mesh(p));
  for (const auto& [name, mesh] : meshes) {
    INFO(name);
    REQUIRE(mesh.max_face_size() == 3);
    const Refinement r = refine(mesh);
    const CoarseComplex K(mesh);
    REQUIRE(K.n_pairs() == mesh.n_edges());
    REQUIRE(K.n_triples() == mesh.n_faces());
    const HodgeStars H = hodge_stars(mesh, r, K);
    std::vector<Eigen::Triplet<double>> t1, t2;
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const auto v = mesh.face(f);
      // Global orientation: pair (u < w) gets lambda_u d lambda_w - lambda_w d lambda_u.
      int edges[3][2], cell[3], k = 0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          if (v[a] < v[b]) {
            edges[k][0] = a, edges[k][1] = b;
            cell[k++] = K.pair_index(v[a], v[b]);
          }
      const Eigen::Matrix3d M =
          quadrature_whitney1_mass(mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2]), edges);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) t1.emplace_back(cell[a], cell[b], M(a, b));
      const double area =
          0.5 *
          (mesh.position(v[1]) - mesh.position(v[0])).cross(mesh.position(v[2]) - mesh.position(v[0])).norm();
      t2.emplace_back(K.triple_index(v[0], v[1], v[2]), K.triple_index(v[0], v[1], v[2]), 1 / area);
    }
    Eigen::SparseMatrix<double> S1(K.n_pairs(), K.n_pairs()), S2(K.n_triples(), K.n_triples());
    S1.setFromTriplets(t1.begin(), t1.end());
    S2.setFromTriplets(t2.begin(), t2.end());
    CHECK(relative_difference(H.star1, S1) <= 1e-11);
    CHECK(relative_difference(H.star2, S2) <= 1e-11);
  }
}

TEST_CASE("coarse stars assembled face by face equal P_k^T star_k^f P_k, star0 equals M", "[feec]") {
  for (const auto& [name, mesh] : test::feec_meshes()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const CoarseComplex K(mesh);
    const HodgeStars H = hodge_stars(mesh, r, K);
    const Eigen::SparseMatrix<double> P0 = prolongation(mesh, r), P1 = prolongation1(mesh, r, K),
                                      P2 = prolongation2(mesh, r, K);
    const Eigen::SparseMatrix<double> G0 = P0.transpose() * refined_star0(mesh, r) * P0;
    const Eigen::SparseMatrix<double> G1 = P1.transpose() * refined_star1(mesh, r) * P1;
    const Eigen::SparseMatrix<double> G2 = P2.transpose() * refined_star2(mesh, r) * P2;
    CHECK(relative_difference(H.star0, G0) <= 1e-12);
    CHECK(relative_difference(H.star1, G1) <= 1e-12);
    CHECK(relative_difference(H.star2, G2) <= 1e-12);
    const Laplacian L = assemble_laplacian(mesh, r);
    CHECK(relative_difference(H.star0, L.M) <= 1e-12);
    CHECK((H.star0_lumped - L.M_lumped).norm() <= 1e-12 * L.M_lumped.norm());
    // Refined star0 carries the refined surface area; refined star2 is the inverse fan areas.
    CHECK(refined_star0(mesh, r).sum() == Approx(H.star0.sum()).epsilon(1e-12));
  }
}

TEST_CASE("surface_dec holds the building blocks' d, P and star, as VolumeDec does", "[feec]") {
  for (const auto& [name, mesh] : test::feec_meshes()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const SurfaceDec D = surface_dec(mesh, r);
    const CoarseComplex K(mesh);
    REQUIRE(D.coarse.n_pairs() == K.n_pairs());
    REQUIRE(D.coarse.n_triples() == K.n_triples());
    CHECK(relative_difference(D.d[0], K.d0()) == 0.0);
    CHECK(relative_difference(D.d[1], K.d1()) == 0.0);
    CHECK(relative_difference(D.P[0], prolongation(mesh, r)) == 0.0);
    CHECK(relative_difference(D.P[1], prolongation1(mesh, r, K)) == 0.0);
    CHECK(relative_difference(D.P[2], prolongation2(mesh, r, K)) == 0.0);
    const HodgeStars H = hodge_stars(mesh, r, K);
    CHECK(relative_difference(D.star[0], H.star0) == 0.0);
    CHECK(relative_difference(D.star[1], H.star1) == 0.0);
    CHECK(relative_difference(D.star[2], H.star2) == 0.0);
    // The identities read the same on both kinds of mesh: d1 d0 = 0, S = -d0^T star1 d0.
    CHECK(Eigen::SparseMatrix<double>(D.d[1] * D.d[0]).norm() == 0.0);
    const Eigen::SparseMatrix<double> S =
        -Eigen::SparseMatrix<double>(D.d[0].transpose()) * D.star[1] * D.d[0];
    CHECK(relative_difference(S, stiffness(mesh, r)) <= 1e-12);
    // Up to degree 1: no d1, P2 or star2.
    const SurfaceDec D1 = surface_dec(mesh, r, 1);
    CHECK(D1.d[1].size() == 0);
    CHECK(D1.P[2].size() == 0);
    CHECK(D1.star[2].size() == 0);
    CHECK(relative_difference(D1.star[1], H.star1) == 0.0);
  }
  CHECK_THROWS_AS(surface_dec(quad_grid(2, 2), refine(quad_grid(2, 2)), 3), std::invalid_argument);
}

TEST_CASE("S = -d0^T star1 d0 to 1e-12 relative", "[feec]") {
  for (const auto& [name, mesh] : test::feec_meshes()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const CoarseComplex K(mesh);
    const Eigen::SparseMatrix<double> d0 = K.d0();
    const Eigen::SparseMatrix<double> S =
        -Eigen::SparseMatrix<double>(d0.transpose()) * star1(mesh, r, K) * d0;
    CHECK(relative_difference(S, stiffness(mesh, r)) <= 1e-12);
  }
}

TEST_CASE("star0, star1, star2 are symmetric positive semi-definite", "[feec]") {
  for (const auto& [name, mesh] : test::feec_meshes()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const CoarseComplex K(mesh);
    const HodgeStars H = hodge_stars(mesh, r, K);
    for (const auto* A : {&H.star0, &H.star1, &H.star2}) {
      CHECK(symmetric_part_error(*A).norm() <= 1e-14 * A->norm());
      if (A->rows() > 700) continue;  // dense spectra only on the small meshes
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(*A), Eigen::EigenvaluesOnly);
      CHECK(eig.eigenvalues().minCoeff() >= -1e-12 * eig.eigenvalues().maxCoeff());
      CHECK(eig.eigenvalues().maxCoeff() > 0);
    }
    CHECK(H.star0_lumped.minCoeff() >= 0);
  }
}

TEST_CASE("stars scale as s^2, s^0, s^-2 under uniform scaling (1e-8 and 1e8)", "[feec]") {
  const Mesh mesh = test::torus(8, 6, 0.2, true);
  const CoarseComplex K(mesh);
  const HodgeStars H = hodge_stars(mesh, refine(mesh), K);
  for (double s : {1e-8, 1e8}) {
    const Mesh m = mesh.with_positions(s * mesh.positions());
    const HodgeStars Hs = hodge_stars(m, refine(m), K);
    CHECK(relative_difference(Hs.star0, s * s * H.star0) <= 1e-12);
    CHECK(relative_difference(Hs.star1, H.star1) <= 1e-12);
    CHECK(relative_difference(Hs.star2, H.star2 / (s * s)) <= 1e-12);
  }
}

TEST_CASE("solving with star1 and star2 on their span", "[feec]") {
  std::vector<std::pair<std::string, Mesh>> meshes = {
      {"pentagon/hexagon sphere", test::dual_mesh(test::icosphere(1), true)},
      {"mixed planar grid", test::planar_grid(8, 6, 0.2, true)},
      {"genus-2 hexagon surface", test::genus2(1, 0.1, true)},
      {"random octagon", test::random_polygon(8, 5)}};
  for (const char* name : {"L-plane.obj", "tetris.obj"})  // tetris: degenerate fan triangles
    if (const std::string p = test::shared_path(name); !p.empty()) meshes.emplace_back(name, read_mesh(p));
  std::mt19937 rng(23);
  std::normal_distribution<double> N(0.0, 1.0);
  for (const auto& [name, mesh] : meshes) {
    INFO(name);
    const Refinement r = refine(mesh);
    const CoarseComplex K(mesh);
    const HodgeStars H = hodge_stars(mesh, r, K);
    for (int k = 1; k <= 2; ++k) {
      INFO("degree " << k);
      const Eigen::SparseMatrix<double>& star = k == 1 ? H.star1 : H.star2;
      const Eigen::SparseMatrix<double> P = k == 1 ? prolongation1(mesh, r, K) : prolongation2(mesh, r, K);
      FormSpan span = form_span(mesh, r, K, k);
      const SpanSolver solver(star, span, k == 1 ? "star1 on its span" : "star2 on its span");
      Eigen::VectorXd x(star.rows());
      for (long i = 0; i < x.size(); ++i) x[i] = N(rng);
      const Eigen::VectorXd b = star * x;
      const Eigen::VectorXd y = solver.solve(b);
      CHECK((star * y - b).norm() <= 1e-10 * b.norm());
      // The same Whitney form: equal on every fan triangle with mass (all, without degenerate ones).
      const Eigen::VectorXd dx = y - x;
      CHECK(std::sqrt(std::max(0.0, dx.dot(star * dx))) <= 1e-8 * std::sqrt(x.dot(star * x)));
      if (r.quality.n_degenerate == 0) CHECK((P * dx).norm() <= 1e-9 * (P * x).norm());
      // y lives on the span cells; canonical() is idempotent.
      Eigen::VectorXd off = y;
      for (int c : span.cells) off[c] = 0;
      CHECK(off.norm() == 0.0);
      CHECK((solver.canonical(y) - y).norm() <= 1e-9 * y.norm());
      // Dense check: the span has the dimension of star's range.
      if (star.rows() <= 700) {
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(star), Eigen::EigenvaluesOnly);
        const double mx = eig.eigenvalues().maxCoeff();
        int rank = 0;
        for (long i = 0; i < eig.eigenvalues().size(); ++i) rank += eig.eigenvalues()[i] > 1e-10 * mx;
        CHECK(rank == span.rank());
      }
    }
  }
}

TEST_CASE("re-assembly with precomputed star patterns on moved vertices", "[feec]") {
  const Mesh mesh = test::torus(10, 6, 0.1, true);
  const CoarseComplex K(mesh);
  const StarPatterns patterns = star_patterns(mesh, K);
  const Mesh moved = mesh.with_positions(test::torus(10, 6, 0.3, true, 9).positions());
  const Refinement r = refine(moved);
  const HodgeStars fresh = hodge_stars(moved, r, K), reused = hodge_stars(moved, r, K, {}, &patterns);
  CHECK(relative_difference(fresh.star0, reused.star0) == 0.0);
  CHECK(relative_difference(fresh.star1, reused.star1) == 0.0);
  CHECK(relative_difference(fresh.star2, reused.star2) == 0.0);
  CHECK((fresh.star0_lumped - reused.star0_lumped).norm() == 0.0);
  const StarPatterns only1 = star_patterns(mesh, K, {false, false, true, false});
  CHECK_THROWS_AS(hodge_stars(moved, r, K, {}, &only1), std::invalid_argument);
  CHECK(relative_difference(hodge_stars(moved, r, K, {false, false, true, false}, &only1).star1, fresh.star1) == 0.0);
}


namespace {

// The route before the exact zeros were dropped: every face's whole block (polygon_star1 or
// polygon_star2, pairs or triples in face_pairs / face_triples order) summed by triplets, in face
// order, zeros stored.
SparseMatrix summed_face_blocks(const Mesh& mesh, const Refinement& r, const CoarseComplex& K, int degree) {
  std::vector<Eigen::Triplet<double>> t;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const PolygonPositions X = face_positions(mesh, f);
    const int h0 = mesh.face_offsets()[f];
    const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(r.weights.data() + h0, X.rows());
    const Eigen::Vector3d xf = r.virtual_points.row(f).transpose();
    const FanTriangle* fan = r.fan.data() + h0;
    const Eigen::MatrixXd A = degree == 1 ? polygon_star1(X, w, xf, fan, K.sorted_corners(f))
                                          : polygon_star2(X, w, xf, fan, K.sorted_corners(f));
    const std::span<const int> cells = degree == 1 ? K.face_pairs(f) : K.face_triples(f);
    for (long a = 0; a < A.rows(); ++a)
      for (long b = 0; b < A.cols(); ++b) t.emplace_back(cells[size_t(a)], cells[size_t(b)], A(a, b));
  }
  const int n = degree == 1 ? K.n_pairs() : K.n_triples();
  SparseMatrix S(n, n);
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

// Stored entries equal to zero.
long stored_zeros(const SparseMatrix& A) {
  long z = 0;
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) z += it.value() == 0.0;
  return z;
}

// Stored entries where A and B differ (as dense matrices: A - B has no non-zero value).
long differing_entries(const SparseMatrix& A, const SparseMatrix& B) {
  const SparseMatrix D = A - B;
  long n = 0;
  for (int j = 0; j < D.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(D, j); it; ++it) n += it.value() != 0.0;
  return n;
}

}  // namespace

TEST_CASE("the stars store no exact zeros and equal the summed face blocks exactly", "[feec][star-zeros]") {
  long dropped2 = 0;
  for (const auto& [name, mesh] : test::feec_meshes()) {
    if (mesh.n_faces() > 5000) continue;
    INFO(name);
    const Refinement r = refine(mesh);
    const CoarseComplex K(mesh);
    const HodgeStars H = hodge_stars(mesh, r, K);
    CHECK(stored_zeros(H.star0) == 0);
    CHECK(stored_zeros(H.star1) == 0);
    CHECK(stored_zeros(H.star2) == 0);
    const SparseMatrix old1 = summed_face_blocks(mesh, r, K, 1), old2 = summed_face_blocks(mesh, r, K, 2);
    CHECK(differing_entries(H.star1, old1) == 0);
    CHECK(differing_entries(H.star2, old2) == 0);
    // Nothing but the zeros went: the stored entries are the old non-zeros.
    CHECK(H.star1.nonZeros() == old1.nonZeros() - stored_zeros(old1));
    CHECK(H.star2.nonZeros() == old2.nonZeros() - stored_zeros(old2));
    if (mesh.max_face_size() >= 6) dropped2 += stored_zeros(old2);
    // The shorthands and surface_dec return the same matrices.
    CHECK(differing_entries(star2(mesh, r, K), H.star2) == 0);
    const SurfaceDec D = surface_dec(mesh, r);
    for (int k = 0; k < 3; ++k) CHECK(stored_zeros(D.star[k]) == 0);
    CHECK(relative_difference(-SparseMatrix(K.d0().transpose()) * H.star1 * K.d0(), assemble_laplacian(mesh, r).S) <=
          1e-12);
  }
  // Hexagons' triples without a common polygon edge met in zeros: the test saw some dropped.
  CHECK(dropped2 > 0);
}

}  // namespace test_hodge_star
