// tests/operators/surface/test_numerics.cpp — floating-point robustness: S and M do not depend on where
// a mesh sits or how large it is; the virtual-vertex weights equal a direct least-squares
// solution of eq. (38) and, unlike a literal port of it, keep their digits far from the origin;
// failed factorizations raise SolverError naming the operator.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/QR>
#include <catch2/catch.hpp>
#include <dlfcn.h>
#include <random>

#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/surface/refinement.h"
#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/surface/laplacian.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_numerics {

namespace {

// The mesh moved to the origin and scaled to bounding-box diagonal 1.
Mesh unit_size(const Mesh& m) {
  const Eigen::RowVector3d lo = m.positions().colwise().minCoeff(), hi = m.positions().colwise().maxCoeff();
  return m.with_positions((m.positions().rowwise() - 0.5 * (lo + hi)) / (hi - lo).norm());
}

struct NamedMesh {
  std::string name;
  Mesh mesh;
};

std::vector<NamedMesh> test_meshes() {
  std::vector<NamedMesh> v = {{"hex_sphere(2)", hex_sphere(2)},
                              {"noisy quad grid", add_noise(quad_grid(6, 6), 0.2, 5)},
                              {"torus", torus(12, 8)},
                              {"hex_grid", hex_grid(5, 5)}};
  for (const char* name : {"noisy-sphere.off", "L-plane.obj", "tetris.obj"}) {
    const std::string p = test::shared_path(name);
    if (!p.empty()) v.push_back({name, read_mesh(p)});
  }
  for (auto& m : v) m.mesh = unit_size(m.mesh);
  return v;
}

// Eq. (37)-(38) as printed: A and b from cross products with the raw positions, the (n+1) x n
// system solved in the least-squares, least-norm sense by a complete orthogonal decomposition.
// Its rank threshold is relative to the largest pivot (1e-10), generous enough that unit-size
// polygons at the origin get the exact rank (3 planar, 4 non-planar).
Eigen::VectorXd eq38_weights(const PolygonPositions& X) {
  const int n = int(X.rows());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 1, n);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d xk = X.row(k).transpose(), e = (X.row((k + 1) % n) - X.row(k)).transpose();
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d ci = X.row(i).transpose().cross(e);
      for (int j = 0; j < n; ++j) A(i, j) += 2 * X.row(j).transpose().cross(e).dot(ci);
      rhs[i] -= 2 * ci.dot(e.cross(xk));
    }
  }
  A.row(n).setOnes();
  rhs[n] = 1;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  cod.setThreshold(1e-10);
  cod.compute(A);
  return cod.solve(rhs);
}

// Random polygons: corner k at angle 2 pi (k + 0.6 u) / n (u uniform in [0, 1): jittered but
// never collapsing into a sliver), radius from [r_min, 1] (convex for r_min = 1, non-convex star
// shapes for small r_min), out-of-plane height `bump`, then a random rotation.
PolygonPositions random_polygon(std::mt19937& rng, int n, double r_min, double bump) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> angles(n);
  for (int k = 0; k < n; ++k) angles[k] = 2 * M_PI * (k + 0.6 * u(rng)) / n;
  PolygonPositions X(n, 3);
  for (int k = 0; k < n; ++k) {
    const double r = r_min + (1 - r_min) * u(rng);
    X.row(k) << r * std::cos(angles[k]), r * std::sin(angles[k]), bump * (2 * u(rng) - 1);
  }
  const Eigen::Matrix3d R =
      Eigen::Quaterniond(Eigen::Vector4d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized())
          .toRotationMatrix();
  return X * R.transpose();
}

double rel(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).norm() / b.norm(); }

// The Cholesky tests' matrix: A = M - 0.01 S of a noisy hexagon sphere (a heat step).
struct HeatStep {
  Mesh mesh = add_noise(hex_sphere(3), 0.1, 5);
  Refinement r = refine(mesh);
  SparseMatrix S = stiffness(mesh, r), M = mass(mesh, r);
  SparseMatrix A = M - 0.01 * S;
};

}  // namespace

TEST_CASE("S and M are invariant under translation and scaling", "[robust][numerics]") {
  for (const auto& [name, mesh] : test_meshes()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const Laplacian L = assemble_laplacian(mesh, r);
    auto moved = [&](const Eigen::MatrixX3d& P) {
      const Mesh m = mesh.with_positions(P);
      return assemble_laplacian(m, refine(m));
    };
    for (double offset : {1e3, 1e6}) {
      INFO("offset " << offset);
      const Laplacian T = moved(mesh.positions().rowwise() + Eigen::RowVector3d::Constant(offset));
      const double tol = offset <= 1e3 ? 1e-11 : 1e-8;
      CHECK(test::relative_difference(T.S, L.S) <= tol);
      CHECK(test::relative_difference(T.M, L.M) <= tol);
    }
    for (double s : {1e-8, 1e8}) {
      INFO("scale " << s);
      const Laplacian T = moved(s * mesh.positions());
      CHECK(test::relative_difference(T.S, L.S) <= 1e-9);
      CHECK(test::relative_difference(SparseMatrix(T.M / (s * s)), L.M) <= 1e-9);
    }
  }
}

TEST_CASE("squared-area weights equal the least-norm solution of eq. (38)", "[robust][numerics]") {
  std::mt19937 rng(11);
  int n_tested = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 8;
    const double r_min =
        trial % 3 == 0 ? 1.0 : (trial % 3 == 1 ? 0.7 : 0.2);  // convex .. strongly non-convex
    const double bump = trial % 2 == 0 ? 0.0 : 0.3;           // planar (rotated) or not
    const PolygonPositions X = random_polygon(rng, n, r_min, bump);
    const Eigen::VectorXd w = squared_area_weights(X), ref = eq38_weights(X);
    INFO("trial " << trial << " n " << n << " r_min " << r_min << " bump " << bump << " rel "
                  << fmt::format("{:.3e}", rel(w, ref)));
    CHECK(std::abs(w.sum() - 1) <= 1e-14);
    CHECK(rel(w, ref) <= 1e-12);
    ++n_tested;
  }
  CHECK(n_tested == 200);
}

TEST_CASE("squared-area weights do not depend on position or size, eq. (38) does", "[robust][numerics]") {
  std::mt19937 rng(12);
  double worst_ours = 0, worst_direct_1e4 = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 4 + trial % 6;
    const PolygonPositions X = random_polygon(rng, n, trial % 2 ? 0.3 : 1.0, trial % 4 < 2 ? 0.0 : 0.3);
    const Eigen::VectorXd w = squared_area_weights(X);
    INFO("trial " << trial);
    for (double s : {1e-8, 1e8}) {
      const double e = rel(squared_area_weights(s * X), w);
      CHECK(e <= 1e-12);
      worst_ours = std::max(worst_ours, e);
    }
    for (double offset : {1e3, 1e4}) {
      const PolygonPositions Y = X.rowwise() + Eigen::RowVector3d(offset, -offset, offset);
      // Rounding the translated corners alone moves them by ~offset * 1e-16 relative to the size.
      const double e = rel(squared_area_weights(Y), w);
      CHECK(e <= 1e-9);
      worst_ours = std::max(worst_ours, e);
      if (offset == 1e4) worst_direct_1e4 = std::max(worst_direct_1e4, rel(eq38_weights(Y), w));
    }
  }
  // A literal port of eq. (38) loses about (offset / size)^2 in accuracy: at offset 1e4 its
  // weights are off by orders of magnitude more than ours.
  CHECK(worst_ours <= 1e-9);
  CHECK(worst_direct_1e4 >= 1e-3);
}

TEST_CASE("failed factorizations raise SolverError naming the operator", "[robust][numerics]") {
  const Mesh mesh = quad_grid(4, 4);
  const SparseMatrix S = stiffness(mesh, refine(mesh));
  // -S is positive semi-definite with the constants in its kernel: singular.
  CHECK_THROWS_WITH(SparseCholesky(SparseMatrix(-S), "Poisson operator -S"),
                    Catch::Contains("Poisson operator -S"));
  CHECK_THROWS_AS(SparseCholesky(SparseMatrix(-S), "Poisson operator -S"), SolverError);
  // S itself is negative semi-definite: not positive definite.
  CHECK_THROWS_AS(SparseCholesky(S, "stiffness S"), SolverError);
  CHECK_THROWS_WITH(SparseCholesky(S, "stiffness S"), Catch::Contains("stiffness S"));
  // An all-zero matrix.
  SparseMatrix Z(5, 5);
  CHECK_THROWS_WITH(SparseCholesky(Z, "zero matrix"), Catch::Contains("zero matrix"));
  // A good factorization that is refactored with singular values.
  SparseMatrix A = SparseMatrix(-S);
  for (int v = 0; v < A.rows(); ++v) A.coeffRef(v, v) += 1.0;
  SparseCholesky chol(A, "shifted -S");
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  CHECK((A * chol.solve(b) - b).norm() <= 1e-12 * b.norm());
  CHECK_THROWS_WITH(chol.refactor(SparseMatrix(-S)), Catch::Contains("shifted -S"));
}

TEST_CASE("Cholesky: the better of AMD and nested dissection by fill, one analysis for two matrices of a pattern",
          "[robust][numerics][cholesky]") {
  const Mesh mesh = add_noise(hex_sphere(3), 0.1, 11);
  const Refinement r = refine(mesh);
  const SparseMatrix S = stiffness(mesh, r), M = mass(mesh, r);
  const SparseMatrix A = M - 0.01 * S, B = 2.0 * M - 0.5 * S;
  const int n = int(A.rows());
  CholeskyOptions amd, nesdis, best;
  amd.ordering = CholeskyOrdering::Amd;
  nesdis.ordering = CholeskyOrdering::NestedDissection;
  best.ordering = CholeskyOrdering::BestFill;
  const SparseCholesky a(A, "A (AMD)", amd), m(A, "A (NESDIS)", nesdis), chol(A, "A", best);
  if (chol.backend() == "cholmod-supernodal") {
    CHECK(chol.factor_nonzeros() == std::min(a.factor_nonzeros(), m.factor_nonzeros()));
    CHECK(chol.ordering() == (m.factor_nonzeros() < a.factor_nonzeros() ? "nesdis" : "amd"));
  }
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const Eigen::VectorXd xa = chol.solve(b);
  CHECK((A * xa - b).norm() <= 1e-12 * b.norm() * (1 + A.norm()));
  // B factored with A's analysis: the solution of a fresh factorization, and A's factor unchanged.
  const SparseCholesky shared = chol.with_values(B, "B");
  const Eigen::VectorXd xb = shared.solve(b), xb_fresh = SparseCholesky(B, "B").solve(b);
  CHECK((xb - xb_fresh).norm() <= 1e-12 * xb_fresh.norm());
  CHECK(chol.solve(b) == xa);
  CHECK(shared.factor_nonzeros() == chol.factor_nonzeros());
  // Another pattern is refused, by with_values and by refactor.
  SparseMatrix C = A;
  C.coeffRef(n - 1, 0) += 1e-9;
  C.coeffRef(0, n - 1) += 1e-9;
  if (A.coeff(n - 1, 0) == 0 && C.nonZeros() > A.nonZeros()) {
    CHECK_THROWS_WITH(chol.with_values(C, "C"), Catch::Contains("pattern"));
    SparseCholesky copy = chol.with_values(B, "B again");
    CHECK_THROWS_AS(copy.refactor(C), SolverError);
  }
  // Pinning that keeps the pattern: the same solutions as pinning that drops the entries, and
  // matrices pinned at different vertices share one analysis.
  std::vector<unsigned char> pin1(n, 0), pin2(n, 0);
  pin1[3] = 1;
  pin2[3] = pin2[n / 2] = pin2[n - 1] = 1;
  const SparseMatrix P1 = pin_to_identity(A, pin1, true), P2 = pin_to_identity(-S, pin2, true);
  CHECK(P1.nonZeros() == A.nonZeros());
  CHECK(P1.coeff(3, 3) == 1.0);
  CHECK(P1.coeff(3, 4) == 0.0);
  const SparseCholesky c1(P1, "P1", best);
  const SparseCholesky c2 = c1.with_values(SparseMatrix(0.0 * A + P2), "P2");
  const Eigen::VectorXd x1 = c1.solve(b), x1_dropped = SparseCholesky(pin_to_identity(A, pin1), "P1'").solve(b);
  const Eigen::VectorXd x2 = c2.solve(b), x2_dropped = SparseCholesky(pin_to_identity(-S, pin2), "P2'").solve(b);
  CHECK((x1 - x1_dropped).norm() <= 1e-12 * x1_dropped.norm());
  CHECK((x2 - x2_dropped).norm() <= 1e-10 * x2_dropped.norm());
  CHECK(x2[3] == Approx(b[3]).epsilon(1e-13));
}

TEST_CASE("Cholesky: a sparse right-hand side solves as the dense one, after refactor too",
          "[robust][numerics][cholesky]") {
  const HeatStep h;
  const SparseMatrix &S = h.S, &M = h.M, &A = h.A;
  const int n = int(A.rows());
  for (CholeskyOrdering ordering : {CholeskyOrdering::Amd, CholeskyOrdering::BestFill}) {
    CholeskyOptions o;
    o.ordering = ordering;
    o.relaxed_supernodes = false;
    SparseCholesky chol(A, "A", o);
    auto check = [&](const std::vector<int>& rows, const std::vector<double>& values) {
      Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
      for (size_t k = 0; k < rows.size(); ++k) b[rows[k]] = values[k];
      const Eigen::VectorXd dense = chol.solve(b), sparse = chol.solve_sparse(rows, values);
      INFO(rows.size() << " rows");
      CHECK((sparse - dense).norm() <= 1e-12 * dense.norm());
      CHECK(sparse.cwiseAbs().minCoeff() > 0);  // the whole solution, not only the reach
    };
    check({7}, {1.0});
    check({n - 1, 0, n / 2}, {0.5, -2.0, 3.0});
    check({11}, {2.5});  // the workspace is clean between calls
    // New values: the sparse solve follows the new factor.
    chol.refactor(SparseMatrix(2.0 * M - 0.5 * S));
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    b[7] = 1.0;
    const Eigen::VectorXd dense = chol.solve(b), sparse = chol.solve_sparse(std::vector<int>{7}, std::vector<double>{1.0});
    CHECK((sparse - dense).norm() <= 1e-12 * dense.norm());
    CHECK(chol.solve_sparse(std::vector<int>{}, std::vector<double>{}).norm() == 0.0);
    CHECK_THROWS_AS(chol.solve_sparse(std::vector<int>{3, 3}, std::vector<double>{1.0, 1.0}), std::invalid_argument);
    CHECK_THROWS_AS(chol.solve_sparse(std::vector<int>{n}, std::vector<double>{1.0}), std::invalid_argument);
  }
}

TEST_CASE("Cholesky: the sparse solve over the supernodal reach, for many rows, relaxed supernodes and a shared analysis",
          "[robust][numerics][cholesky]") {
  const HeatStep h;
  const SparseMatrix &S = h.S, &M = h.M, &A = h.A;
  const int n = int(A.rows());
  std::vector<int> many;
  std::vector<double> many_values;
  for (int v = n - 1; v >= 0; v -= 5) {
    many.push_back(v);
    many_values.push_back(1.0 + 0.01 * v);
  }
  // The default (relaxed) supernodes store explicit zeros; the second factor reuses the analysis.
  for (bool relaxed : {true, false}) {
    CholeskyOptions o;
    o.relaxed_supernodes = relaxed;
    const SparseCholesky heat(A, "A", o);
    const SparseCholesky other = heat.with_values(SparseMatrix(2.0 * M - 0.3 * S), "B");
    for (const SparseCholesky* chol : {&heat, &other}) {
      auto check = [&](const std::vector<int>& rows, const std::vector<double>& values) {
        Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
        for (size_t k = 0; k < rows.size(); ++k) b[rows[k]] = values[k];
        const Eigen::VectorXd dense = chol->solve(b);
        Eigen::VectorXd sparse(n);
        chol->solve_sparse(rows, values, sparse.data());
        INFO(chol->name() << ", relaxed " << relaxed << ", " << rows.size() << " rows");
        CHECK((sparse - dense).norm() <= 1e-12 * dense.norm());
        CHECK((chol->solve_sparse(rows, values) - sparse).norm() == 0.0);
      };
      check({0}, {1.0});
      check(many, many_values);
      check({n / 3, 2 * n / 3}, {-1.0, 4.0});  // after a wide reach, the workspace is clean again
      // Alternating with multi-column solves (their own workspace) changes nothing.
      const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, 3);
      const Eigen::MatrixXd X = chol->solve(B);
      CHECK((X.col(1) - chol->solve(Eigen::VectorXd(B.col(1)))).norm() <= 1e-12 * X.col(1).norm());
      check({5}, {2.0});
    }
  }
  // The Eigen backend answers with its dense solve.
  CholeskyOptions eigen;
  eigen.backend = CholeskyBackend::Eigen;
  const SparseCholesky e(A, "A", eigen);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  b[4] = 3.0;
  CHECK((e.solve_sparse(std::vector<int>{4}, std::vector<double>{3.0}) - e.solve(b)).norm() <= 1e-12 * e.solve(b).norm());
}

TEST_CASE("Cholesky: a one-column solve with a right-hand side zero on a region equals the Eigen backend's",
          "[robust][numerics][cholesky]") {
  // The forward solve skips the supernodes that stay zero (no non-zero in their rows or below them
  // in the elimination tree); the Eigen backend's LDL^T solves everything. Both routes must agree
  // wherever the zeros lie, including a lone non-zero deep inside the zero region.
  const HeatStep h;
  const Mesh& mesh = h.mesh;
  const SparseMatrix& A = h.A;
  const int n = int(A.rows());
  CholeskyOptions eigen_options;
  eigen_options.backend = CholeskyBackend::Eigen;
  const SparseCholesky oracle(A, "A", eigen_options);
  for (CholeskyOrdering ordering : {CholeskyOrdering::Amd, CholeskyOrdering::BestFill}) {
    CholeskyOptions o;
    o.ordering = ordering;
    o.relaxed_supernodes = false;
    const SparseCholesky chol(A, "A", o);
    auto check = [&](const Eigen::VectorXd& b, const char* what) {
      const Eigen::VectorXd x = chol.solve(b), ref = oracle.solve(b);
      INFO(what << ", " << (b.array() != 0).count() << " non-zeros");
      CHECK((x - ref).norm() <= 1e-12 * ref.norm());
    };
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    for (int v = 0; v < n; ++v)
      if (mesh.positions()(v, 0) < -0.2) b[v] = 1.0 + 0.1 * mesh.positions()(v, 1);
    check(b, "a cap");
    const Eigen::VectorXd cap = b;
    for (int v = 0; v < n; ++v)
      if (mesh.positions()(v, 2) > 0.3) b[v] = 0.0;
    check(b, "part of a cap");
    int lone = 0;
    for (int v = 0; v < n; ++v)
      if (mesh.positions()(v, 0) > mesh.positions()(lone, 0)) lone = v;
    b.setZero();
    b[lone] = 2.0;
    check(b, "one row");
    check(Eigen::VectorXd(Eigen::VectorXd::Ones(n) - cap), "everything but a cap");
    CHECK(chol.solve(Eigen::VectorXd(Eigen::VectorXd::Zero(n))).norm() == 0.0);
    b = Eigen::VectorXd::Random(n);
    check(b, "dense");  // after the pruned solves, a full one
  }
}

}  // namespace test_numerics

TEST_CASE("Cholesky: a factorization leaves the calling thread's OpenMP nesting setting as it was",
          "[robust][numerics][cholesky]") {
  // CHOLMOD's OpenMP loops are kept on the calling thread while the BLAS policy is one thread, by a
  // per-call setting that must be undone (other code of the program may use OpenMP).
  using Get = int (*)();
  using Set = void (*)(int);
  const auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
  const auto set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  if (!get || !set || !SparseCholesky::cholmod_available()) {
    WARN("skipped: no OpenMP runtime mapped or no CHOLMOD");
    return;
  }
  const Mesh mesh = hex_sphere(4);
  const Refinement r = refine(mesh);
  const SparseMatrix A = mass(mesh, r) - 0.1 * stiffness(mesh, r);
  for (int levels : {3, 1}) {
    set(levels);
    const SparseCholesky chol(A, "A");
    CHECK(get() == levels);
    const SparseCholesky again = chol.with_values(A, "A again");
    CHECK(get() == levels);
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
    CHECK((A * again.solve(b) - b).norm() < 1e-8 * b.norm());
  }
}

TEST_CASE("Cholesky: row-major blocks solved in place equal the column-major solve", "[robust][numerics][cholesky]") {
  const Mesh mesh = add_noise(hex_sphere(3), 0.1, 11);
  const Refinement r = refine(mesh);
  const SparseMatrix A = mass(mesh, r) - 0.05 * stiffness(mesh, r);
  const int n = int(A.rows());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (auto backend : {CholeskyBackend::Automatic, CholeskyBackend::Eigen})
    for (bool relaxed : {true, false}) {
      CholeskyOptions o;
      o.backend = backend;
      o.relaxed_supernodes = relaxed;
      const SparseCholesky chol(A, "A", o);
      const SparseCholesky other = chol.with_values(SparseMatrix(2.0 * A), "2A");
      for (int m : {1, 3, 64, 5, 3}) {  // sizes change between calls: the kept block is remade
        INFO(chol.backend() << ", relaxed " << relaxed << ", " << m << " columns");
        Eigen::MatrixXd B(n, m);
        for (int i = 0; i < B.size(); ++i) B.data()[i] = U(rng);
        for (const SparseCholesky* c : {&chol, &other}) {
          const Eigen::MatrixXd X = c->solve(B);
          Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> R = B;
          c->solve_rows(R.data(), m);
          CHECK((Eigen::MatrixXd(R) - X).cwiseAbs().maxCoeff() <= 1e-12 * X.cwiseAbs().maxCoeff());
          // The same rows in the factor's order, solved in place; with a few non-zero rows named,
          // the forward solve over their reach only.
          const std::span<const int> order = c->factor_order();
          auto at = [&](int k) { return order.empty() ? k : order[size_t(k)]; };
          Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> P(n, m), Q(n, m);
          for (int k = 0; k < n; ++k) P.row(k) = B.row(at(k));
          c->solve_rows_in_factor_order(P.data(), m);
          double e = 0;
          for (int k = 0; k < n; ++k) e = std::max(e, (P.row(k) - X.row(at(k))).cwiseAbs().maxCoeff());
          CHECK(e <= 1e-12 * X.cwiseAbs().maxCoeff());
          const std::vector<int> few = {3, n / 2, 3, n - 1};  // a repeated row is allowed
          Q.setZero();
          for (int k : few) Q.row(k) = P.row(0);
          Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, m);
          for (int k : few) dense.row(at(k)) = P.row(0);
          const Eigen::MatrixXd Xd = c->solve(dense);
          c->solve_rows_in_factor_order(Q.data(), m, few);
          e = 0;
          for (int k = 0; k < n; ++k) e = std::max(e, (Q.row(k) - Xd.row(at(k))).cwiseAbs().maxCoeff());
          CHECK(e <= 1e-12 * Xd.cwiseAbs().maxCoeff());
          if (!order.empty())
            CHECK_THROWS_AS(c->solve_rows_in_factor_order(Q.data(), m, std::vector<int>{n}), std::invalid_argument);
        }
      }
    }
}
