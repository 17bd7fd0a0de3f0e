// tests/operators/surface/test_assembly_parallel.cpp — the fast assembly path: results bitwise identical
// for any thread count, re-assembly equal to a fresh assembly, S and M equal to the refined
// cotangent route P^T S_tri P (an independent construction), the allocation-free weights equal
// to the least-norm solution of eq. (38), and the CHOLMOD and Eigen Cholesky backends agreeing.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>

#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/dec/surface/refinement.h"
#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/surface/laplacian.h"
#include "tests/support/plain_cotan.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_assembly_parallel {

namespace {

bool bitwise_equal(const SparseMatrix& A, const SparseMatrix& B) {
  return A.rows() == B.rows() && A.nonZeros() == B.nonZeros() &&
         std::memcmp(A.outerIndexPtr(), B.outerIndexPtr(), sizeof(int) * (A.outerSize() + 1)) == 0 &&
         std::memcmp(A.innerIndexPtr(), B.innerIndexPtr(), sizeof(int) * A.nonZeros()) == 0 &&
         std::memcmp(A.valuePtr(), B.valuePtr(), sizeof(double) * A.nonZeros()) == 0;
}

bool bitwise_equal(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

// The same surface with its faces in a random order: most vertices then have faces in several
// of the threads' face ranges (the serial seam pass of the threaded assembly does most work).
Mesh shuffle_faces(const Mesh& mesh, unsigned seed) {
  std::vector<int> order(size_t(mesh.n_faces()));
  for (int f = 0; f < mesh.n_faces(); ++f) order[size_t(f)] = f;
  std::mt19937 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  PolygonSoup soup;
  soup.positions = mesh.positions();
  for (int f : order) soup.add_face(mesh.face(f));
  return Mesh(std::move(soup));
}

// Meshes large enough for the threaded path (at least 8192 halfedges per thread for 4 threads),
// with mixed face sizes, in coherent and in random face order.
std::vector<std::pair<std::string, Mesh>> threaded_meshes() {
  return {{"cube sphere (quads)", cube_sphere(48)},
          {"cube sphere, faces shuffled", shuffle_faces(cube_sphere(48), 11)},
          {"noisy hexagon sphere (5-, 6-gons)", add_noise(hex_sphere(5), 0.2, 7)},
          {"uv sphere (triangles and quads)", uv_sphere(120, 160)}};
}

}  // namespace

TEST_CASE("assembly is bitwise identical for any thread count", "[perf]") {
  for (const auto& [name, mesh] : threaded_meshes()) {
    INFO(name);
    REQUIRE(mesh.n_halfedges() > 4 * 8192);  // otherwise the threaded path is not exercised
    const Refinement r = refine(mesh);
    const Laplacian one = assemble_laplacian(mesh, r, {}, nullptr, {1});
    CHECK(one.S.nonZeros() > 0);
    // Without M the lumped mass is summed face by face (another rounding than M's column sums).
    const Laplacian alone = assemble_laplacian(mesh, r, {false, false, true}, nullptr, {1});
    for (int T : {2, 3, 4}) {
      INFO("threads " << T);
      const Laplacian many = assemble_laplacian(mesh, r, {}, nullptr, {T});
      CHECK(bitwise_equal(one.S, many.S));
      CHECK(bitwise_equal(one.M, many.M));
      CHECK(bitwise_equal(one.M_lumped, many.M_lumped));
      CHECK(bitwise_equal(alone.M_lumped,
                          assemble_laplacian(mesh, r, {false, false, true}, nullptr, {T}).M_lumped));
      const Laplacian with_S = assemble_laplacian(mesh, r, {true, false, true}, nullptr, {T});
      CHECK(bitwise_equal(one.S, with_S.S));
      CHECK(bitwise_equal(alone.M_lumped, with_S.M_lumped));
      // The threaded refinement (split by faces).
      RefinementOptions options;
      options.threads = T;
      const Refinement rT = refine(mesh, options);
      CHECK(std::memcmp(r.weights.data(), rT.weights.data(), sizeof(double) * r.weights.size()) == 0);
      CHECK(std::memcmp(r.virtual_points.data(), rT.virtual_points.data(),
                        sizeof(double) * r.virtual_points.size()) == 0);
      CHECK(r.fan == rT.fan);
      CHECK(r.quality.n_degenerate == rT.quality.n_degenerate);
      CHECK(r.quality.n_inverted == rT.quality.n_inverted);
      CHECK(r.quality.n_faces_affected == rT.quality.n_faces_affected);
    }
    // Symmetric bit for bit, so that lumped row sums equal column sums.
    CHECK(bitwise_equal(one.S, SparseMatrix(one.S.transpose())));
    CHECK(bitwise_equal(one.M, SparseMatrix(one.M.transpose())));
    const Eigen::VectorXd rows = one.M * Eigen::VectorXd::Ones(mesh.n_vertices());
    CHECK((rows - one.M_lumped).cwiseAbs().maxCoeff() <= 1e-14 * one.M_lumped.cwiseAbs().maxCoeff());
    CHECK((rows - alone.M_lumped).cwiseAbs().maxCoeff() <= 1e-14 * one.M_lumped.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("re-assembly on moved vertices equals a fresh assembly", "[perf]") {
  const Mesh mesh = add_noise(cube_sphere(40), 0.1, 3);
  const Mesh moved = add_noise(mesh, 0.3, 11);
  const FacePattern fp = face_pattern(mesh), fp_patches = face_pattern(mesh, 2);
  REQUIRE(fp.face_rank.empty());
  REQUIRE(fp_patches.face_rank.size() == size_t(mesh.n_faces()));
  std::vector<int> sorted = fp_patches.face_rank;  // a permutation of the faces
  std::sort(sorted.begin(), sorted.end());
  for (int f = 0; f < mesh.n_faces(); ++f) REQUIRE(sorted[size_t(f)] == f);
  for (int T : {1, 2, 3})
    for (const FacePattern* p : {&fp, &fp_patches}) {
      INFO("threads " << T << (p == &fp ? ", file order" : ", breadth-first patches"));
      Laplacian L = assemble_laplacian(mesh, refine(mesh), {}, p, {T});
      const double* s_storage = L.S.valuePtr();
      const Refinement r2 = refine(moved);
      reassemble_laplacian(moved, r2, *p, {}, L, {T});
      const Laplacian fresh = assemble_laplacian(moved, r2, {}, nullptr, {1});
      CHECK(L.S.valuePtr() == s_storage);  // storage reused
      CHECK(bitwise_equal(L.S, fresh.S));
      CHECK(bitwise_equal(L.M, fresh.M));
      CHECK(bitwise_equal(L.M_lumped, fresh.M_lumped));
      // Only the mass parts: S untouched, M and lumped M as fresh.
      Laplacian Lm;
      reassemble_laplacian(moved, r2, *p, {false, true, true}, Lm, {T});
      CHECK(Lm.S.nonZeros() == 0);
      CHECK(bitwise_equal(Lm.M, fresh.M));
      CHECK(bitwise_equal(Lm.M_lumped, fresh.M_lumped));
      // Only S and the lumped mass: M untouched, the lumped mass as a fresh one without M.
      Laplacian Ll;
      reassemble_laplacian(moved, r2, *p, {true, false, true}, Ll, {T});
      CHECK(Ll.M.nonZeros() == 0);
      CHECK(bitwise_equal(Ll.S, fresh.S));
      CHECK(bitwise_equal(Ll.M_lumped,
                          assemble_laplacian(moved, r2, {false, false, true}, nullptr, {1}).M_lumped));
    }
}

TEST_CASE("fast S and M equal the refined cotangent route P^T S_tri P", "[perf]") {
  // Independent construction: the explicit fan triangulation, a plain cotangent Laplacian and
  // Galerkin mass on it (tests/support/plain_cotan.h), coarsened with the prolongation P (eq. 11-13).
  for (const Mesh& mesh : {add_noise(hex_sphere(2), 0.3, 5), add_noise(genus2(1), 0.2, 9), hex_grid(6, 5)}) {
    const Refinement r = refine(mesh);
    REQUIRE(r.quality.n_degenerate == 0);
    const Laplacian L = assemble_laplacian(mesh, r);
    const test::PlainCotan fine = test::plain_cotan(refined_mesh(mesh, r));
    const SparseMatrix P = prolongation(mesh, r);
    const SparseMatrix S = P.transpose() * fine.S * P, M = P.transpose() * fine.M * P;
    CHECK(test::relative_difference(L.S, S) < 1e-13);
    CHECK(test::relative_difference(L.M, M) < 1e-13);
    CHECK((L.S * Eigen::VectorXd::Ones(mesh.n_vertices())).cwiseAbs().maxCoeff() <
          1e-12 * L.S.diagonal().cwiseAbs().maxCoeff());
  }
}

TEST_CASE("allocation-free squared-area weights equal an SVD route and eq. (38)", "[perf]") {
  // Eq. (38) solved as in the authors' code: the normal equations of the squared fan areas plus
  // the affine constraint, least-norm by a complete orthogonal decomposition.
  auto reference = [](const PolygonPositions& X) {
    const int n = int(X.rows());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + 1, n);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d e = (X.row((k + 1) % n) - X.row(k)).transpose();
      const Eigen::Vector3d d = e.cross(Eigen::Vector3d(X.row(k).transpose()));
      Eigen::MatrixXd c(3, n);
      for (int i = 0; i < n; ++i) c.col(i) = e.cross(Eigen::Vector3d(X.row(i).transpose()));
      K.topRows(n) += c.transpose() * c;
      rhs.head(n) += c.transpose() * d;
    }
    K.row(n).setOnes();
    rhs(n) = 1.0;
    return Eigen::VectorXd(K.completeOrthogonalDecomposition().solve(rhs));
  };
  // An independent route: the minimizer by an eigen-decomposition of A, the least-norm weights by
  // the SVD of the centred corners (the library uses LDL^T, Householder QR and R^-T, or the
  // SVD of R near the rank cut).
  auto svd_route = [](const PolygonPositions& X) {
    const int n = int(X.rows());
    const PolygonPositions Y = X.rowwise() - X.colwise().mean();
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d e = (Y.row((k + 1) % n) - Y.row(k)).transpose();
      const Eigen::Matrix3d B = e.squaredNorm() * Eigen::Matrix3d::Identity() - e * e.transpose();
      A += B;
      b += B * Y.row(k).transpose();
    }
    const Eigen::Vector3d y = A.ldlt().solve(b);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(Y), Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::Vector3d sigma = svd.singularValues();
    Eigen::Vector3d z = svd.matrixV().transpose() * y;
    for (int i = 0; i < 3; ++i) z[i] = sigma[i] > 1e-5 * sigma[0] ? z[i] / sigma[i] : 0.0;
    return Eigen::VectorXd(Eigen::VectorXd::Constant(n, 1.0 / n) + svd.matrixU() * z);
  };
  // The raw-pointer route used by refine(), with the SVD route's fixed relative cut 1e-5 (the
  // default decision, from the data's precision, is tested in tests/dec/surface/test_planarity.cpp).
  const PlanarityCut cut{0.0, 1e-5};
  auto fast = [&cut](const PolygonPositions& X) {
    const int n = int(X.rows());
    std::vector<double> x(3 * n), work(3 * n);
    for (int k = 0; k < n; ++k)
      for (int d = 0; d < 3; ++d) x[3 * k + d] = X(k, d);
    Eigen::VectorXd w(n);
    squared_area_weights(x.data(), n, w.data(), work.data(), cut);
    return w;
  };
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int n = 3; n <= 12; ++n)
    // Planar, planar up to 1e-9 (both routes drop the normal direction), nearly planar but
    // kept, non-planar. Bumps near the rank cut (~1e-5 of the size) are avoided: there the
    // weights jump between the two cases by design.
    for (double bump : {0.0, 1e-9, 1e-3, 0.05, 0.3}) {
      PolygonPositions X(n, 3);
      for (int k = 0; k < n; ++k) {
        const double phi = 2 * M_PI * (k + 0.3 * U(rng)) / n, rad = 1.0 + 0.3 * U(rng);
        X.row(k) << rad * std::cos(phi), rad * std::sin(phi), bump * U(rng);
      }
      INFO("n " << n << " bump " << bump);
      const Eigen::VectorXd w = fast(X), general = svd_route(X);
      CHECK(std::abs(w.sum() - 1.0) < 1e-13);
      CHECK((w - general).norm() < 1e-9 * general.norm());
      CHECK((squared_area_weights(X, cut) - w).norm() == 0.0);
      if (bump >= 0.05 || bump == 0.0) CHECK((w - reference(X)).norm() < 1e-9 * w.norm());
      // Moved and shrunk: the weights do not depend on position or scale.
      const PolygonPositions Y = (X * 1e-3).rowwise() + Eigen::RowVector3d(2e-3, -1e-3, 5e-4);
      CHECK((fast(Y) - w).norm() < 1e-9 * w.norm());
    }
}

TEST_CASE("CHOLMOD and Eigen Cholesky backends agree, refactorization reuses the analysis", "[perf]") {
  const Mesh mesh = add_noise(hex_sphere(3), 0.2, 2);
  const Laplacian L = assemble_laplacian(mesh, refine(mesh));
  const double t = mesh.mean_edge_length() * mesh.mean_edge_length();
  const SparseMatrix A = L.M - t * L.S, A2 = L.M - 4 * t * L.S;
  Eigen::VectorXd b(mesh.n_vertices());
  for (int i = 0; i < b.size(); ++i) b[i] = std::sin(0.37 * i + 0.1);
  SparseCholesky eig(A, "M - t S", {CholeskyBackend::Eigen});
  CHECK(eig.backend() == "eigen-simplicial-ldlt");
  const Eigen::VectorXd xe = eig.solve(b);
  CHECK((A * xe - b).norm() < 1e-10 * b.norm());
  // Singular or indefinite input is a SolverError naming the operator.
  CHECK_THROWS_WITH(SparseCholesky(L.S, "S", {CholeskyBackend::Eigen}), Catch::Contains("S"));
  if (!SparseCholesky::cholmod_available()) {
    WARN("CHOLMOD not compiled in: only the Eigen backend tested");
    return;
  }
  for (auto ordering :
       {CholeskyOrdering::Automatic, CholeskyOrdering::Metis, CholeskyOrdering::NestedDissection}) {
    SparseCholesky chol(A, "M - t S", {CholeskyBackend::Cholmod, ordering});
    INFO("ordering " << chol.ordering());
    CHECK(chol.backend() == "cholmod-supernodal");
    const Eigen::VectorXd xc = chol.solve(b);
    CHECK((xc - xe).norm() < 1e-10 * xe.norm());
    Eigen::MatrixXd B(b.size(), 2);
    B << b, Eigen::VectorXd::Ones(b.size());
    const Eigen::MatrixXd X = chol.solve(B);
    CHECK((X.col(0) - xc).norm() < 1e-14 * xc.norm());
    CHECK((A * X.col(1) - B.col(1)).norm() < 1e-10 * B.col(1).norm());
    // Numeric refactorization with new values on the same pattern equals a fresh factorization.
    chol.refactor(A2);
    SparseCholesky eig2(A2, "M - 4t S", {CholeskyBackend::Eigen});
    CHECK((chol.solve(b) - eig2.solve(b)).norm() < 1e-10 * eig2.solve(b).norm());
  }
  CHECK_THROWS_AS(SparseCholesky(L.S, "S", {CholeskyBackend::Cholmod}), SolverError);
  CHECK_THROWS_WITH(SparseCholesky(L.S, "stiffness S", {CholeskyBackend::Cholmod}),
                    Catch::Contains("stiffness S"));
}

TEST_CASE("polydec operators --repeat --threads --json times the assembly without writing files", "[perf]") {
  POLYDEC_SHARED_MESH(path, "quad-sphere.off");
  const std::string cmd =
      std::string(POLYDEC_CLI_PATH) + " operators " + path + " --repeat 3 --threads 2 --json";
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p);
  std::string out;
  char buf[4096];
  while (size_t k = fread(buf, 1, sizeof buf, p)) out.append(buf, k);
  REQUIRE(pclose(p) == 0);
  const auto j = nlohmann::json::parse(out);
  CHECK(j.at("threads").get<int>() == 2);
  CHECK(j.at("repeat").get<int>() == 3);
  CHECK(j.at("median_ms").get<double>() > 0);
  CHECK(j.at("faces").get<int>() == 512);
  CHECK(j.at("S_nonzeros").get<long>() ==
        assemble_laplacian(read_mesh(path), refine(read_mesh(path))).S.nonZeros());
}

}  // namespace test_assembly_parallel
