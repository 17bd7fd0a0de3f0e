// tests/dec/surface/test_prolongation.cpp — P1 and P2: their definition from P (eq. 23), the commuting
// relations with d, the rank table of a single n-gon, and linear precision of the Whitney
// reconstruction.
#include <Eigen/SVD>
#include <catch2/catch.hpp>

#include "polydec/dec/surface/form_span.h"
#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/dec/surface/whitney.h"
#include "tests/support/feec_meshes.h"

using namespace polydec;

namespace test_prolongation {

namespace {

// Numerical rank by SVD, singular values above rel_tol times the largest.
int svd_rank(const Eigen::MatrixXd& A, double rel_tol = 1e-9) {
  if (A.size() == 0) return 0;
  Eigen::BDCSVD<Eigen::MatrixXd> svd(A);
  const auto& s = svd.singularValues();
  int r = 0;
  for (long k = 0; k < s.size(); ++k) r += s[k] > rel_tol * s[0];
  return r;
}

}  // namespace

TEST_CASE("P1 and P2 equal the antisymmetrised products of P entries (eq. 23-26)", "[feec]") {
  for (const auto& mesh :
       {test::random_polygon(7, 2), test::planar_grid(3, 3, 0.2, true), test::torus(8, 4, 0.1, true)}) {
    const Refinement r = refine(mesh);
    const CoarseComplex K(mesh);
    const Eigen::MatrixXd P = Eigen::MatrixXd(prolongation(mesh, r));
    const Eigen::MatrixXd P1 = Eigen::MatrixXd(prolongation1(mesh, r, K));
    const Eigen::MatrixXd P2 = Eigen::MatrixXd(prolongation2(mesh, r, K));
    for (int e = 0; e < refined_n_edges(mesh); ++e) {
      const Eigen::Vector2i kl = refined_edge(mesh, e);
      for (int p = 0; p < K.n_pairs(); ++p) {
        const int i = K.pairs()(p, 0), j = K.pairs()(p, 1);
        REQUIRE(P1(e, p) == Approx(P(kl[0], i) * P(kl[1], j) - P(kl[1], i) * P(kl[0], j)).margin(1e-15));
      }
    }
    for (int h = 0; h < refined_n_triangles(mesh); ++h) {
      const Eigen::Vector3i t = refined_triangle(mesh, h);
      for (int q = 0; q < K.n_triples(); ++q) {
        Eigen::Matrix3d B;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) B(a, b) = P(t[a], K.triples()(q, b));
        REQUIRE(P2(h, q) == Approx(B.determinant()).margin(1e-15));
      }
    }
  }
}

TEST_CASE("prolongations commute with d: P1 d0 = d0^f P0, P2 d1 = d1^f P1", "[feec]") {
  for (const auto& [name, mesh] : test::feec_meshes()) {
    INFO(name);
    const Refinement r = refine(mesh);
    const CoarseComplex K(mesh);
    const Eigen::SparseMatrix<double> P0 = prolongation(mesh, r), P1 = prolongation1(mesh, r, K),
                                      P2 = prolongation2(mesh, r, K);
    const Eigen::SparseMatrix<double> A = P1 * K.d0(), B = refined_d0(mesh) * P0;
    const Eigen::SparseMatrix<double> C = P2 * K.d1(), D = refined_d1(mesh) * P1;
    // The identities hold exactly when every face's weights sum to 1; the refinement delivers
    // that to round-off (up to ~1e-11 on small, thin faces), which bounds the entry errors.
    double defect = 0;
    for (int f = 0; f < mesh.n_faces(); ++f) {
      double sum = 0;
      for (int h = mesh.face_offsets()[f]; h < mesh.face_offsets()[f + 1]; ++h) sum += r.weights[h];
      defect = std::max(defect, std::abs(1 - sum));
    }
    const double slack = 4 * defect * std::sqrt(double(mesh.n_halfedges()));
    CHECK((A - B).norm() <= 1e-14 * B.norm() + slack);
    CHECK((C - D).norm() <= 1e-14 * D.norm() + slack);
    CHECK(D.norm() > 0);
  }
}

TEST_CASE("rank table of a single n-gon: P1, star1, P2, star2", "[feec]") {
  // n, coarse pairs, rank P1 = rank star1, coarse triples, rank P2 = rank star2 (the rank
  // table of docs/feec.md, first measured with an independent implementation).
  const int table[6][5] = {{3, 3, 3, 1, 1},    {4, 6, 6, 4, 3},    {5, 10, 9, 10, 5},
                           {6, 15, 11, 20, 6}, {7, 21, 13, 35, 7}, {8, 28, 15, 56, 8}};
  for (const auto& row : table) {
    const int n = row[0];
    for (int variant = 0; variant < 4; ++variant) {
      const Mesh mesh = variant == 0 ? test::regular_polygon(n) : test::random_polygon(n, 100 * n + variant);
      INFO("n = " << n << (variant ? " random non-planar" : " regular planar"));
      const Refinement r = refine(mesh);
      const CoarseComplex K(mesh);
      REQUIRE(K.n_pairs() == row[1]);
      REQUIRE(K.n_triples() == row[3]);
      const HodgeStars H = hodge_stars(mesh, r, K);
      CHECK(svd_rank(Eigen::MatrixXd(prolongation1(mesh, r, K))) == row[2]);
      CHECK(svd_rank(Eigen::MatrixXd(H.star1)) == row[2]);
      CHECK(svd_rank(Eigen::MatrixXd(prolongation2(mesh, r, K))) == row[4]);
      CHECK(svd_rank(Eigen::MatrixXd(H.star2)) == row[4]);
      // The closed forms of the explanation in docs/feec.md.
      CHECK(row[2] == std::min(n * (n - 1) / 2, 2 * n - 1));
      CHECK(row[4] == row[2] - (n - 1));
      // The reduced bases pick exactly that many cells.
      CHECK(form_span(mesh, r, K, 1).rank() == row[2]);
      CHECK(form_span(mesh, r, K, 2).rank() == row[4]);
      // The one constraint on the spokes: sum_a w_a (P1 c)_(a, v) = 0 for every c.
      const Eigen::MatrixXd P1 = Eigen::MatrixXd(prolongation1(mesh, r, K));
      Eigen::RowVectorXd y = Eigen::RowVectorXd::Zero(P1.rows());
      for (int h = 0; h < n; ++h) y[mesh.n_edges() + h] = r.weights[h];
      CHECK((y * P1).cwiseAbs().maxCoeff() <= 1e-14);
    }
  }
}

TEST_CASE("global ranks on a pentagon/hexagon sphere: |E| + sum over faces of (n-1)", "[feec]") {
  const Mesh mesh = test::dual_mesh(test::icosphere(1), true);
  REQUIRE(mesh.n_faces() == 42);
  const Refinement r = refine(mesh);
  const CoarseComplex K(mesh);
  CHECK(K.n_pairs() == 450);
  const FormSpan s1 = form_span(mesh, r, K, 1), s2 = form_span(mesh, r, K, 2);
  CHECK(s1.rank() == 318);  // 120 edges + 12 * 4 + 30 * 5
  CHECK(s2.rank() == 240);  // one 2-form per fan triangle
  CHECK(svd_rank(Eigen::MatrixXd(star1(mesh, r, K))) == 318);
  CHECK(svd_rank(Eigen::MatrixXd(prolongation1(mesh, r, K))) == 318);
}

TEST_CASE("Whitney reconstruction of d0 f for linear f is grad f on every refined triangle", "[feec]") {
  std::vector<std::pair<std::string, Mesh>> meshes = {
      {"mixed planar grid", test::planar_grid(6, 6, 0.3, true)}, {"random heptagon (flattened)", Mesh()}};
  {
    Mesh hept = test::random_polygon(7, 9);
    Eigen::MatrixX3d X = hept.positions();
    X.col(2).setZero();
    meshes[1].second = hept.with_positions(X);
  }
  for (const char* name : {"L-plane.obj", "tetris.obj", "tetris_2.obj", "quad-plane.obj"}) {
    const std::string path = test::shared_path(name);
    if (!path.empty()) meshes.emplace_back(name, read_mesh(path));
  }
  const Eigen::Vector3d a(0.7, -1.3, 0.4);
  for (const auto& [name, mesh] : meshes) {
    INFO(name);
    // The mesh's plane (some files lie in the xz plane): normal from the total vector area.
    Eigen::Vector3d nrm = Eigen::Vector3d::Zero();
    for (int h = 0; h < mesh.n_halfedges(); ++h)
      nrm += mesh.position(mesh.halfedge_source(h)).cross(mesh.position(mesh.halfedge_target(h)));
    nrm.normalize();
    const Eigen::Vector3d grad = a - a.dot(nrm) * nrm;  // gradient of f = a . x within the plane
    const Refinement r = refine(mesh);
    const CoarseComplex K(mesh);
    const Eigen::VectorXd f = mesh.positions() * a;
    const Eigen::VectorXd c = prolongation1(mesh, r, K) * (K.d0() * f);
    int checked = 0;
    for (int h = 0; h < mesh.n_halfedges(); ++h) {
      if (r.fan[h] == FanTriangle::Degenerate) continue;
      const Eigen::Vector3i t = refined_triangle(mesh, h);
      const int fc = mesh.halfedge_face(h);
      auto pos = [&](int v) -> Eigen::Vector3d {
        return v < mesh.n_vertices() ? mesh.position(v)
                                     : Eigen::Vector3d(r.virtual_points.row(fc).transpose());
      };
      // Edge values in the local order (0,1), (0,2), (1,2): mesh edge, spoke of t[0], spoke of t[1].
      const int ne = mesh.n_edges(), spoke_s = ne + h, spoke_t = ne + mesh.halfedge_next(h);
      const bool up = t[0] == mesh.halfedge_source(h);
      const Eigen::Vector3d ce(c[mesh.halfedge_edge(h)], c[up ? spoke_s : spoke_t],
                               c[up ? spoke_t : spoke_s]);
      for (const Eigen::Vector3d& bary : {Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3),
                                         Eigen::Vector3d(0.6, 0.3, 0.1), Eigen::Vector3d(0.05, 0.15, 0.8)}) {
        const Eigen::Vector3d v = whitney1_value(pos(t[0]), pos(t[1]), pos(t[2]), ce, bary);
        REQUIRE((v - grad).norm() <= 1e-9 * a.norm());
      }
      ++checked;
    }
    CHECK(checked > 0);
  }
}

}  // namespace test_prolongation
