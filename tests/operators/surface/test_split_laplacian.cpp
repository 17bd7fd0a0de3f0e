// tests/operators/surface/test_split_laplacian.cpp — the operators of several virtual vertices per face:
// the paper's operators bit for bit where no face is split, S = P^T S^f P against an independent
// cotangent Laplacian of the refined triangles, symmetry, S 1 = 0, negative semi-definiteness,
// positive mass summing to the area, S = D G, the patch test (linear precision) and exact
// gradients of linear functions on planar non-convex meshes, the registry name "split".
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/sawtooth_grid.h"
#include "polydec/operators/registry/laplacians.h"
#include "polydec/operators/surface/split_laplacian.h"
#include "tests/support/plain_cotan.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_split_laplacian {
using polydec::test::relative_difference;

namespace {

bool identical(const SparseMatrix& A, const SparseMatrix& B) {
  return A.rows() == B.rows() && A.cols() == B.cols() && A.nonZeros() == B.nonZeros() && (A - B).norm() == 0.0;
}

// Twice the vector area of the mesh (the sum of its faces'): normal times twice the area for a planar mesh.
Eigen::Vector3d vector_area2(const Mesh& mesh) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const PolygonPositions X = face_positions(mesh, f);
    for (int k = 0; k < X.rows(); ++k) a += X.row(k).cross(X.row((k + 1) % X.rows())).transpose();
  }
  return a;
}

// Properties every split operator set has, on a planar mesh of any plane:
// symmetric S with S 1 = 0, negative semi-definite (one zero eigenvalue), M positive definite with
// 1^T M 1 = area, positive lumped mass, S = D G, S = P^T S^f P with an independent cotangent
// Laplacian of the refined triangles, and the patch test: (S u)_i = 0 at interior vertices and
// G u = grad u on every refined triangle for linear u.
void check_planar(const Mesh& mesh) {
  const Eigen::Vector3d a2 = vector_area2(mesh);
  const double area = 0.5 * a2.norm();
  const Eigen::Vector3d n = a2.normalized();
  const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  const SplitLaplacian L = split_laplacian(mesh);
  const int nv = mesh.n_vertices();
  const double s = L.S.norm();
  CHECK(relative_difference(L.S, SparseMatrix(L.S.transpose())) == 0.0);
  CHECK((L.S * Eigen::VectorXd::Ones(nv)).cwiseAbs().maxCoeff() < 1e-13 * s);
  CHECK(std::abs(Eigen::VectorXd::Ones(nv).dot(L.M * Eigen::VectorXd::Ones(nv)) - area) < 1e-12 * area);
  CHECK(L.M_lumped.minCoeff() > 0);
  if (nv <= 400) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(L.S)), em(Eigen::MatrixXd(L.M));
    CHECK(es.eigenvalues().maxCoeff() < 1e-12 * s);
    CHECK(es.eigenvalues()(nv - 2) < -1e-8 * s);  // one zero eigenvalue: the mesh is connected
    CHECK(em.eigenvalues().minCoeff() > 0);
  }
  CHECK(relative_difference(L.S, SparseMatrix(L.D * L.G)) < 1e-13);
  // An independent cotangent Laplacian of the explicit refined triangle mesh.
  PolygonSoup soup;
  soup.positions = split_positions(mesh, L.split);
  for (const auto& t : split_triangles(mesh, L.split)) soup.add_face(std::vector<int>{t[0], t[1], t[2]});
  const test::PlainCotan C = test::plain_cotan(Mesh(std::move(soup)));
  CHECK(relative_difference(L.S, SparseMatrix(L.P.transpose() * C.S * L.P)) < 1e-13);
  CHECK(relative_difference(L.M, SparseMatrix(L.P.transpose() * C.M * L.P)) < 1e-13);
  // Linear precision.
  const double h = mesh.mean_edge_length();
  for (const Eigen::Vector3d& g : {t1, t2, Eigen::Vector3d(0.3 * t1 - 1.7 * t2)}) {
    const Eigen::VectorXd u = mesh.positions() * g;
    const Eigen::VectorXd Su = L.S * u;
    double worst = 0;
    for (int v = 0; v < nv; ++v)
      if (!mesh.is_boundary_vertex(v)) worst = std::max(worst, std::abs(Su[v]));
    CHECK(worst < 1e-12 * s * (u.cwiseAbs().maxCoeff() + h));
    const Eigen::VectorXd Gu = L.G * u;
    for (long t = 0; t < Gu.size() / 3; ++t)
      CHECK((Gu.segment<3>(3 * t) - g).norm() < 1e-10 * g.norm());
  }
}

}  // namespace

TEST_CASE("split operators equal the paper's bit for bit where no face is split", "[split]") {
  for (const Mesh& mesh : {quad_grid(4, 3), hex_grid(4, 4), hex_sphere(1), chevron_grid(4, 4, 0.3),
                           add_noise(torus(8, 5), 0.1, 3), sawtooth_grid(3, 1, 2, 0.7)}) {
    REQUIRE(split_refine(mesh).n_faces_split == 0);
    const OperatorSet a = build_operators(mesh, parse_laplacian("ours"));
    const OperatorSet b = build_operators(mesh, parse_laplacian("split"));
    CHECK(b.name == "split");
    CHECK(identical(a.S, b.S));
    CHECK(identical(a.M, b.M));
    CHECK(identical(a.G, b.G));
    CHECK(identical(a.D, b.D));
    CHECK((a.M_lumped.array() == b.M_lumped.array()).all());
    const SplitLaplacian L = split_laplacian(mesh);
    CHECK(identical(a.S, L.S));
    CHECK(identical(a.G, L.G));
  }
}

TEST_CASE("split operators on sawtooth grids are linearly precise", "[split]") {
  for (const double scale : {1e-6, 1.0, 1e6}) {
    INFO("scale " << scale);
    const Mesh m0 = sawtooth_grid(5, 5, 2, 0.7);
    PolygonSoup soup;
    soup.positions = scale * m0.positions();
    soup.positions.col(0).array() += 2 * scale;
    for (int f = 0; f < m0.n_faces(); ++f) soup.add_face(m0.face(f));
    const Mesh mesh(std::move(soup));
    REQUIRE(split_refine(mesh).n_faces_split == 20);
    check_planar(mesh);
    CHECK(std::abs(0.5 * vector_area2(mesh).norm() - scale * scale) < 1e-12 * scale * scale);
  }
  // Three teeth: deeper non-convexity, more pieces.
  const Mesh three = sawtooth_grid(4, 4, 3, 0.6);
  const SplitRefinement s = split_refine(three);
  CHECK(s.after.ok());
  check_planar(three);
}

TEST_CASE("split operators on the paper's non-convex meshes", "[split]") {
  for (const char* name : {"L-plane.obj", "tetris.obj", "tetris_2.obj"}) {
    POLYDEC_SHARED_MESH(path, name);
    INFO(name);
    const Mesh mesh = read_mesh(path);
    check_planar(mesh);
    CHECK(build_operators(mesh, parse_laplacian("split")).quality.ok());
  }
}

TEST_CASE("the registry offers split without lifts", "[split]") {
  CHECK(parse_laplacian("split").canonical_name() == "split");
  const auto names = laplacian_names();
  CHECK(std::find(names.begin(), names.end(), "split") != names.end());
  CHECK_THROWS_AS(parse_laplacian("split:1"), std::invalid_argument);
  OperatorOptions o;
  o.lift = parse_virtual_lift("quadric");
  CHECK_THROWS_AS(build_operators(sawtooth_grid(3, 3), parse_laplacian("split"), o), std::invalid_argument);
}

}  // namespace test_split_laplacian
