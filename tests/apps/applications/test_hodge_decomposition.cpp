// tests/apps/applications/test_hodge_decomposition.cpp — Hodge decomposition of 1-cochains: orthogonality,
// closedness and co-closedness of the harmonic part, harmonic dimension = first Betti number
// (checked against an independent dense rank count), co-exact part orthogonal to every closed
// form, and recovery of parts built from known potentials.
#include <Eigen/LU>
#include <Eigen/SVD>
#include <catch2/catch.hpp>
#include <algorithm>
#include <random>

#include "polydec/apps/applications/hodge_decomposition.h"
#include "polydec/dec/surface/form_span.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/surface/mesh_complex.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/operators/surface/laplacian.h"
#include "polydec/operators/solvers/span_solver.h"
#include "tests/support/feec_meshes.h"

using namespace polydec;

namespace test_hodge_decomposition {

namespace {

Eigen::VectorXd random_vector(long n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  Eigen::VectorXd x(n);
  for (long i = 0; i < n; ++i) x[i] = N(rng);
  return x;
}

// First Betti number of a connected surface from its Euler characteristic.
int betti1(const Mesh& mesh) {
  return mesh.n_boundary_edges() > 0 ? 1 - mesh.euler_characteristic() : 2 - mesh.euler_characteristic();
}

std::vector<std::pair<std::string, Mesh>> hodge_meshes() {
  std::vector<std::pair<std::string, Mesh>> m;
  m.emplace_back("pentagon/hexagon sphere", test::dual_mesh(test::icosphere(1), true));
  m.emplace_back("noisy quad torus", test::torus(16, 8, 0.2, false));
  m.emplace_back("noisy hexagon torus", test::torus(12, 8, 0.15, true));
  m.emplace_back("genus-2 quad surface", test::genus2(2, 0.1, false));
  m.emplace_back("genus-2 hexagon surface", test::genus2(1, 0.1, true));
  m.emplace_back("mixed planar grid", test::planar_grid(8, 6, 0.2, true));
  m.emplace_back("noisy torus (library)", add_noise(polydec::torus(16, 8), 0.15, 2));
  m.emplace_back("noisy genus2 (library)", add_noise(polydec::genus2(1), 0.1, 3));
  m.emplace_back("hex_sphere (library)", hex_sphere(2));
  m.emplace_back("hex_grid (library)", hex_grid(5, 5));
  for (const char* name : {"quad-sphere.off", "noisy-sphere.off", "L-plane.obj", "suzanne-half.obj"}) {
    const std::string path = test::shared_path(name);
    if (!path.empty()) m.emplace_back(name, read_mesh(path));
  }
  return m;
}

}  // namespace

TEST_CASE("generated test surfaces have the intended topology", "[feec]") {
  CHECK(test::torus(16, 8, 0.2, false).euler_characteristic() == 0);
  CHECK(test::torus(12, 8, 0.15, true).euler_characteristic() == 0);
  CHECK(test::genus2(2, 0.1, false).euler_characteristic() == -2);
  CHECK(test::genus2(1, 0.1, true).euler_characteristic() == -2);
  CHECK(test::genus2(1, 0.1, true).n_boundary_edges() == 0);
  CHECK(test::genus2(1, 0.1, true).max_face_size() == 6);
  CHECK(test::dual_mesh(test::icosphere(1), true).euler_characteristic() == 2);
  CHECK(polydec::genus2(1).euler_characteristic() == -2);
}

TEST_CASE("Hodge parts are star1-orthogonal, harmonic part closed and co-closed, sum exact", "[feec]") {
  for (const auto& [name, mesh] : hodge_meshes()) {
    INFO(name);
    REQUIRE(mesh.n_components() == 1);
    const HodgeDecomposer hd(mesh);
    CHECK(hd.harmonic_dimension() == betti1(mesh));
    const Eigen::SparseMatrix<double>& S1 = hd.star1();
    const Eigen::SparseMatrix<double> d0 = hd.d0(), d1 = hd.complex().d1();
    const Eigen::VectorXd omega = random_vector(hd.complex().n_pairs(), 31);
    const HodgeParts p = hd.decompose(omega);
    const double w2 = omega.dot(S1 * omega);
    REQUIRE(w2 > 0);
    CHECK(std::abs(p.exact.dot(S1 * p.coexact)) <= 1e-10 * w2);
    CHECK(std::abs(p.exact.dot(S1 * p.harmonic)) <= 1e-10 * w2);
    CHECK(std::abs(p.coexact.dot(S1 * p.harmonic)) <= 1e-10 * w2);
    CHECK((omega - p.exact - p.coexact - p.harmonic).norm() <= 1e-14 * omega.norm());
    CHECK((p.exact - d0 * p.potential).norm() == 0.0);
    // Harmonic: d1 h = 0 and d0^T star1 h = 0; co-exact: d0^T star1 c = 0.
    const double hs = std::max(p.harmonic.cwiseAbs().maxCoeff(), 1e-300);
    CHECK((d1 * p.harmonic).cwiseAbs().maxCoeff() <= 1e-12 * hs);
    const double scale = (Eigen::SparseMatrix<double>(d0.transpose()) * S1).norm() * std::sqrt(w2);
    CHECK((d0.transpose() * (S1 * p.harmonic)).norm() <= 1e-10 * scale);
    CHECK((d0.transpose() * (S1 * p.coexact)).norm() <= 1e-10 * scale);
    CHECK(p.norm * p.norm == Approx(p.norm_exact * p.norm_exact + p.norm_coexact * p.norm_coexact +
                                    p.norm_harmonic * p.norm_harmonic)
                                 .epsilon(1e-9));
    // The harmonic basis is star1-orthonormal.
    const Eigen::MatrixXd& H = hd.harmonic_basis();
    if (H.cols() > 0)
      CHECK((H.transpose() * (S1 * H) - Eigen::MatrixXd::Identity(H.cols(), H.cols())).norm() <= 1e-10);
  }
}

TEST_CASE(
    "harmonic dimension = dim W1 - rank d0 - rank d1 counted densely, co-exact part is orthogonal to ker d1",
    "[feec]") {
  for (const auto& [name, mesh] : std::vector<std::pair<std::string, Mesh>>{
           {"noisy hexagon torus", test::torus(8, 6, 0.15, true)},
           {"genus-2 hexagon surface", test::genus2(1, 0.1, true)},
           {"pentagon/hexagon sphere", test::dual_mesh(test::icosphere(1), true)},
           {"mixed planar grid", test::planar_grid(5, 4, 0.2, true)}}) {
    INFO(name);
    const Refinement r = refine(mesh);
    const CoarseComplex K(mesh);
    const Eigen::MatrixXd P1 = Eigen::MatrixXd(prolongation1(mesh, r, K));
    const Eigen::MatrixXd D = Eigen::MatrixXd(prolongation2(mesh, r, K) * K.d1());  // d1 on Whitney forms
    Eigen::FullPivLU<Eigen::MatrixXd> lu1(P1), luD(D);
    lu1.setThreshold(1e-10);
    luD.setThreshold(1e-10);
    const int dim_w1 = int(lu1.rank()), rank_d1 = int(luD.rank()), rank_d0 = mesh.n_vertices() - 1;
    const HodgeDecomposer hd(mesh);
    CHECK(hd.harmonic_dimension() == dim_w1 - rank_d0 - rank_d1);
    CHECK(hd.harmonic_dimension() == betti1(mesh));
    // ker d1 (as Whitney forms: P2 d1 x = 0) is exact + harmonic; the co-exact part is orthogonal to it.
    const Eigen::MatrixXd Z = luD.kernel();
    const Eigen::VectorXd omega = random_vector(K.n_pairs(), 5);
    const HodgeParts p = hd.decompose(omega);
    const Eigen::MatrixXd SZ = hd.star1() * Z;
    const double scale = std::sqrt(omega.dot(hd.star1() * omega));
    // Cauchy-Schwarz scale |c|_star1 |z|_star1, floored for kernel vectors of P1 (|z|_star1 ~ 0).
    const double floor = 1e-7 * std::sqrt(hd.star1().norm());
    for (long k = 0; k < Z.cols(); ++k) {
      const double zn = std::sqrt(std::max(0.0, Z.col(k).dot(SZ.col(k))));
      REQUIRE(std::abs(p.coexact.dot(SZ.col(k))) <= 1e-9 * scale * std::max(zn, floor * Z.col(k).norm()));
    }
    // And it is not orthogonal to everything: it carries the part of omega outside ker d1.
    CHECK(p.norm_coexact > 1e-3 * p.norm);
  }
}

TEST_CASE("decomposition recovers parts built from known potentials", "[feec]") {
  for (const auto& [name, mesh] : std::vector<std::pair<std::string, Mesh>>{
           {"pentagon/hexagon sphere", test::dual_mesh(test::icosphere(1), true)},
           {"noisy hexagon torus", test::torus(12, 8, 0.15, true)},
           {"genus-2 hexagon surface", test::genus2(1, 0.1, true)}}) {
    INFO(name);
    const Refinement r = refine(mesh);
    const HodgeDecomposer hd(mesh);
    const CoarseComplex& K = hd.complex();
    const HodgeStars H = hodge_stars(mesh, r, K, {false, false, true, true});
    // Co-exact part delta beta = star1^+ d1^T star2 beta, solved on the span of the 1-forms.
    const SpanSolver s1(H.star1, form_span(mesh, r, K, 1), "star1");
    const Eigen::VectorXd beta = random_vector(K.n_triples(), 3);
    const Eigen::VectorXd c0 = s1.solve(Eigen::SparseMatrix<double>(K.d1().transpose()) * (H.star2 * beta));
    const Eigen::VectorXd alpha = random_vector(mesh.n_vertices(), 4);
    const Eigen::VectorXd a0 = hd.d0() * alpha;
    const Eigen::VectorXd h0 = hd.harmonic_basis() * random_vector(hd.harmonic_dimension(), 6);
    const HodgeParts p = hd.decompose(a0 + c0 + h0);
    auto norm = [&](const Eigen::VectorXd& x) { return std::sqrt(std::max(0.0, x.dot(H.star1 * x))); };
    const double tol = 1e-8 * p.norm;
    CHECK(norm(p.exact - a0) <= tol);
    CHECK(norm(p.coexact - c0) <= tol);
    CHECK(norm(p.harmonic - h0) <= tol);
    CHECK(norm(c0) > 1e-3 * p.norm);
    // alpha is recovered up to a constant.
    const Eigen::VectorXd da = p.potential - alpha;
    CHECK((da.array() - da.mean()).matrix().norm() <= 1e-8 * alpha.norm());
  }
}

TEST_CASE("the gradient of a function is purely exact, bad input is rejected", "[feec]") {
  const Mesh mesh = test::torus(12, 8, 0.15, true);
  const HodgeDecomposer hd(mesh);
  const Eigen::VectorXd f = mesh.positions().col(0) + mesh.positions().col(2).array().square().matrix();
  const HodgeParts p = hd.decompose(hd.d0() * f);
  CHECK(p.norm_coexact <= 1e-9 * p.norm);
  CHECK(p.norm_harmonic <= 1e-9 * p.norm);
  CHECK(p.norm_exact == Approx(p.norm).epsilon(1e-9));
  CHECK_THROWS_AS(hd.decompose(Eigen::VectorXd::Zero(3)), std::invalid_argument);
  Eigen::VectorXd bad = Eigen::VectorXd::Zero(hd.complex().n_pairs());
  bad[1] = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(hd.decompose(bad), std::invalid_argument);
}

TEST_CASE("docs/feec.md example: operators composed from d0, d1 and the stars", "[feec]") {
  const Mesh mesh = test::torus(12, 8, 0.15, true);
  const Refinement r = refine(mesh);
  const CoarseComplex K(mesh);
  const HodgeStars H = hodge_stars(mesh, r, K);
  const SparseMatrix d0 = K.d0(), d1 = K.d1();
  const SparseMatrix S = -SparseMatrix(d0.transpose()) * H.star1 * d0;
  CHECK(test::relative_difference(S, stiffness(mesh, r)) <= 1e-12);
  const SpanSolver S1(H.star1, form_span(mesh, r, K, 1), "star1");
  auto lap1 = [&](const Eigen::VectorXd& omega) -> Eigen::VectorXd {
    return d0 * ((d0.transpose() * (H.star1 * omega)).cwiseQuotient(H.star0_lumped)) +
           S1.solve(d1.transpose() * (H.star2 * (d1 * omega)));
  };
  const HodgeDecomposer hd(mesh);
  REQUIRE(hd.harmonic_dimension() == 2);
  auto norm = [&](const Eigen::VectorXd& x) { return std::sqrt(std::max(0.0, x.dot(H.star1 * x))); };
  const Eigen::VectorXd omega = random_vector(K.n_pairs(), 8);
  const double typical = norm(lap1(omega)) / norm(omega);
  REQUIRE(typical > 0);
  for (long k = 0; k < 2; ++k) CHECK(norm(lap1(hd.harmonic_basis().col(k))) <= 1e-8 * typical);
  // Weak divergence of the gradient of f is the core Laplacian's S f.
  const Eigen::VectorXd f = mesh.positions().col(2);
  const Eigen::VectorXd div = -(d0.transpose() * (H.star1 * (d0 * f)));
  const Eigen::VectorXd Sf = stiffness(mesh, r) * f;
  CHECK((div - Sf).norm() <= 1e-12 * Sf.norm());
}

TEST_CASE("several components and an unreferenced vertex: Betti numbers add up", "[feec]") {
  const Mesh a = test::torus(10, 6, 0.1, true), b = test::dual_mesh(test::icosphere(1), true);
  PolygonSoup s;
  s.positions.resize(a.n_vertices() + b.n_vertices() + 1, 3);
  s.positions.topRows(a.n_vertices()) = a.positions();
  s.positions.middleRows(a.n_vertices(), b.n_vertices()) = b.positions().rowwise() + Eigen::RowVector3d(5, 0, 0);
  s.positions.bottomRows(1) << 9, 9, 9;  // unreferenced
  for (int f = 0; f < a.n_faces(); ++f) s.add_face(a.face(f));
  for (int f = 0; f < b.n_faces(); ++f) {
    std::vector<int> face(b.face(f).begin(), b.face(f).end());
    for (int& v : face) v += a.n_vertices();
    s.add_face(face);
  }
  const Mesh mesh(std::move(s));
  REQUIRE(mesh.n_components() == 2);
  const HodgeDecomposer hd(mesh);
  CHECK(hd.harmonic_dimension() == 2);
  const Eigen::VectorXd omega = random_vector(hd.complex().n_pairs(), 12);
  const HodgeParts p = hd.decompose(omega);
  const double w2 = omega.dot(hd.star1() * omega);
  CHECK(std::abs(p.exact.dot(hd.star1() * p.coexact)) <= 1e-10 * w2);
  CHECK(std::abs(p.coexact.dot(hd.star1() * p.harmonic)) <= 1e-10 * w2);
  CHECK((hd.complex().d1() * p.harmonic).cwiseAbs().maxCoeff() <= 1e-12 * p.harmonic.cwiseAbs().maxCoeff());
  CHECK(std::isfinite(p.potential.sum()));
}

// A planar quad grid with some interior faces removed: a disk with `holes` holes.
Mesh grid_with_holes(int n, const std::vector<int>& removed) {
  const Mesh grid = quad_grid(n, n);
  PolygonSoup s;
  s.positions = grid.positions();
  for (int f = 0; f < grid.n_faces(); ++f)
    if (std::find(removed.begin(), removed.end(), f) == removed.end()) s.add_face(grid.face(f));
  return Mesh(std::move(s));
}

TEST_CASE("mesh complex: ordinary solves, harmonic dimension = b1, parts orthogonal, closed and co-closed",
          "[feec][mesh-complex]") {
  auto cases = hodge_meshes();
  cases.emplace_back("disk with two holes", grid_with_holes(8, {18, 45}));
  cases.emplace_back("disk with three holes", grid_with_holes(9, {10, 40, 70}));
  for (const auto& [name, mesh] : cases) {
    INFO(name);
    const HodgeDecomposer hd(mesh, {}, DecComplex::Mesh);
    CHECK(hd.dec_complex() == DecComplex::Mesh);
    CHECK(hd.harmonic_dimension() == betti1(mesh));
    const Eigen::SparseMatrix<double>& S1 = hd.star1();
    const Eigen::SparseMatrix<double> d0 = hd.d0(), d1 = mesh_d1(mesh);
    REQUIRE(d0.rows() == mesh.n_edges());
    // The same count by dense ranks: dim H = |E| - rank d0 - rank d1.
    if (mesh.n_edges() <= 2000) {
      const long r0 = Eigen::FullPivLU<Eigen::MatrixXd>(Eigen::MatrixXd(d0)).rank();
      const long r1 = Eigen::FullPivLU<Eigen::MatrixXd>(Eigen::MatrixXd(d1)).rank();
      CHECK(hd.harmonic_dimension() == mesh.n_edges() - r0 - r1);
    }
    const Eigen::VectorXd omega = random_vector(mesh.n_edges(), 17);
    const HodgeParts p = hd.decompose(omega);
    const double w2 = omega.dot(S1 * omega);
    REQUIRE(w2 > 0);
    CHECK(std::abs(p.exact.dot(S1 * p.coexact)) <= 1e-10 * w2);
    CHECK(std::abs(p.exact.dot(S1 * p.harmonic)) <= 1e-10 * w2);
    CHECK(std::abs(p.coexact.dot(S1 * p.harmonic)) <= 1e-10 * w2);
    CHECK((omega - p.exact - p.coexact - p.harmonic).norm() <= 1e-14 * omega.norm());
    const double hs = std::max(p.harmonic.cwiseAbs().maxCoeff(), 1e-300);
    CHECK((d1 * p.harmonic).cwiseAbs().maxCoeff() <= 1e-12 * hs);
    const double scale = (Eigen::SparseMatrix<double>(d0.transpose()) * S1).norm() * std::sqrt(w2);
    CHECK((d0.transpose() * (S1 * p.harmonic)).norm() <= 1e-10 * scale);
    CHECK((d0.transpose() * (S1 * p.coexact)).norm() <= 1e-10 * scale);
    // The co-exact part is star1^-1 d1^T beta: star1 c lies in the range of d1^T (checked by
    // least squares against d1^T).
    const Eigen::VectorXd sc = S1 * p.coexact;
    if (mesh.n_edges() <= 2000 && sc.norm() > 0) {
      const Eigen::MatrixXd D1T = Eigen::MatrixXd(d1).transpose();
      const Eigen::VectorXd beta = D1T.colPivHouseholderQr().solve(sc);
      CHECK((D1T * beta - sc).norm() <= 1e-8 * sc.norm());
    }
  }
}

TEST_CASE("mesh complex: a gradient is exact, a rotation on a torus has a harmonic part, bad sizes are refused",
          "[feec][mesh-complex]") {
  const Mesh mesh = test::torus(16, 8, 0.1, false);
  const HodgeDecomposer hd(mesh, {}, DecComplex::Mesh);
  REQUIRE(hd.harmonic_dimension() == 2);
  const Eigen::VectorXd u = random_vector(mesh.n_vertices(), 3);
  const HodgeParts g = hd.decompose(mesh_d0(mesh) * u);
  CHECK(g.norm_coexact <= 1e-10 * g.norm);
  CHECK(g.norm_harmonic <= 1e-10 * g.norm);
  // The harmonic basis, decomposed, is purely harmonic.
  const HodgeParts h = hd.decompose(hd.harmonic_basis().col(0));
  CHECK(h.norm_harmonic == Approx(1.0).epsilon(1e-10));
  CHECK_THROWS_AS(hd.decompose(Eigen::VectorXd::Zero(mesh.n_edges() + 1)), std::invalid_argument);
}

}  // namespace test_hodge_decomposition
