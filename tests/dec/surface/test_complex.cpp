// tests/dec/surface/test_complex.cpp — coarse and refined cell complexes, d0 and d1.
#include <catch2/catch.hpp>
#include <set>

#include "polydec/dec/surface/complex.h"
#include "polydec/dec/surface/refinement.h"
#include "tests/support/feec_meshes.h"

using namespace polydec;

namespace test_complex {

TEST_CASE("coarse complex of one hexagon lists all pairs and triples lexicographically", "[feec]") {
  const Mesh mesh = test::random_polygon(6, 4);  // shuffled vertex order
  const CoarseComplex K(mesh);
  REQUIRE(K.n_pairs() == 15);
  REQUIRE(K.n_triples() == 20);
  int edges = 0;
  for (int p = 0; p < K.n_pairs(); ++p) {
    CHECK(K.pairs()(p, 0) < K.pairs()(p, 1));
    if (p > 0)
      CHECK((K.pairs()(p - 1, 0) < K.pairs()(p, 0) ||
             (K.pairs()(p - 1, 0) == K.pairs()(p, 0) && K.pairs()(p - 1, 1) < K.pairs()(p, 1))));
    CHECK(K.pair_index(K.pairs()(p, 1), K.pairs()(p, 0)) == p);
    edges += K.is_edge(p);
  }
  CHECK(edges == 6);
  for (int t = 0; t < K.n_triples(); ++t) {
    const int i = K.triples()(t, 0), j = K.triples()(t, 1), k = K.triples()(t, 2);
    CHECK((i < j && j < k));
    CHECK(K.triple_index(k, i, j) == t);
  }
  CHECK(K.pair_index(0, 0) == -1);
  CHECK(K.triple_index(0, 1, 1) == -1);
}

TEST_CASE("face-local cell lists follow the corner ranks", "[feec]") {
  for (const auto& [name, mesh] : test::feec_meshes()) {
    INFO(name);
    const CoarseComplex K(mesh);
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const auto face = mesh.face(f);
      const auto order = K.sorted_corners(f);
      const int n = int(face.size());
      for (int r = 0; r + 1 < n; ++r) REQUIRE(face[order[r]] < face[order[r + 1]]);
      for (int r = 0; r < n; ++r)
        for (int s = r + 1; s < n; ++s) {
          REQUIRE(K.face_pairs(f)[local_pair_index(n, r, s)] == K.pair_index(face[order[r]], face[order[s]]));
          for (int t = s + 1; t < n; ++t)
            REQUIRE(K.face_triples(f)[local_triple_index(n, r, s, t)] ==
                    K.triple_index(face[order[r]], face[order[s]], face[order[t]]));
        }
    }
  }
}

TEST_CASE("coarse cell counts: every edge and diagonal once, every triple of a face once", "[feec]") {
  for (const auto& [name, mesh] : test::feec_meshes()) {
    INFO(name);
    const CoarseComplex K(mesh);
    // Independent count with std::set over the faces.
    std::set<std::pair<int, int>> pairs;
    std::set<std::array<int, 3>> triples;
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const auto face = mesh.face(f);
      for (int a : face)
        for (int b : face) {
          if (a < b) pairs.insert({a, b});
          for (int c : face)
            if (a < b && b < c) triples.insert({a, b, c});
        }
    }
    CHECK(K.n_pairs() == long(pairs.size()));
    CHECK(K.n_triples() == long(triples.size()));
    long p = 0;
    for (auto [a, b] : pairs) {
      REQUIRE(K.pairs()(p, 0) == a);
      REQUIRE(K.pairs()(p, 1) == b);
      ++p;
    }
    int edges = 0;
    for (int q = 0; q < K.n_pairs(); ++q) edges += K.is_edge(q);
    CHECK(edges == mesh.n_edges());
  }
}

TEST_CASE("d1 d0 = 0 exactly on the coarse and the refined complex", "[feec]") {
  for (const auto& [name, mesh] : test::feec_meshes()) {
    INFO(name);
    const CoarseComplex K(mesh);
    const Eigen::SparseMatrix<double> d0 = K.d0(), d1 = K.d1();
    CHECK(d0.rows() == K.n_pairs());
    CHECK(d1.cols() == K.n_pairs());
    const Eigen::SparseMatrix<double> dd = d1 * d0;
    CHECK(dd.norm() == 0.0);
    // d0 of a constant vanishes, and every row of d1 has the pattern +1 +1 -1.
    CHECK((d0 * Eigen::VectorXd::Ones(mesh.n_vertices())).cwiseAbs().maxCoeff() == 0.0);
    CHECK((d1 * Eigen::VectorXd::Ones(K.n_pairs())).cwiseAbs().maxCoeff() == 1.0);
    const Eigen::SparseMatrix<double> rd = refined_d1(mesh) * refined_d0(mesh);
    CHECK(rd.norm() == 0.0);
  }
}

TEST_CASE("refined complex = coarse complex of the explicit fan triangulation, up to numbering", "[feec]") {
  for (const auto& [name, mesh] : test::feec_meshes()) {
    INFO(name);
    const Mesh R = refined_mesh(mesh, refine(mesh));
    const CoarseComplex KR(R);  // on a triangle mesh: pairs = edges, triples = triangles
    REQUIRE(KR.n_pairs() == refined_n_edges(mesh));
    REQUIRE(KR.n_triples() == refined_n_triangles(mesh));
    const Eigen::SparseMatrix<double> d0 = refined_d0(mesh), d1 = refined_d1(mesh);
    const Eigen::SparseMatrix<double> D0 = KR.d0(), D1 = KR.d1();
    std::vector<int> edge_map(refined_n_edges(mesh)), tri_map(refined_n_triangles(mesh));
    std::set<int> seen;
    for (int e = 0; e < refined_n_edges(mesh); ++e) {
      const Eigen::Vector2i v = refined_edge(mesh, e);
      REQUIRE(v[0] < v[1]);
      edge_map[e] = KR.pair_index(v[0], v[1]);
      REQUIRE(edge_map[e] >= 0);
      seen.insert(edge_map[e]);
    }
    CHECK(seen.size() == edge_map.size());
    for (int h = 0; h < refined_n_triangles(mesh); ++h) {
      const Eigen::Vector3i t = refined_triangle(mesh, h);
      tri_map[h] = KR.triple_index(t[0], t[1], t[2]);
      REQUIRE(tri_map[h] >= 0);
      // The orientation sign: does (min, max, v) run like (source, target, v)?
      const int s = mesh.halfedge_source(h), e = mesh.halfedge_target(h);
      CHECK(refined_triangle_sign(mesh, h) == ((t[0] == s && t[1] == e) ? 1 : -1));
    }
    // Permutations to the explicit mesh's numbering: E maps our 1-cells, T our triangles.
    std::vector<Eigen::Triplet<double>> te, tt;
    for (int e = 0; e < refined_n_edges(mesh); ++e) te.emplace_back(edge_map[e], e, 1.0);
    for (int h = 0; h < refined_n_triangles(mesh); ++h) tt.emplace_back(tri_map[h], h, 1.0);
    Eigen::SparseMatrix<double> E(KR.n_pairs(), refined_n_edges(mesh)),
        T(KR.n_triples(), refined_n_triangles(mesh));
    E.setFromTriplets(te.begin(), te.end());
    T.setFromTriplets(tt.begin(), tt.end());
    const Eigen::SparseMatrix<double> e0 = E * d0 - D0,
                                      e1 = T * d1 * Eigen::SparseMatrix<double>(E.transpose()) - D1;
    CHECK(e0.norm() == 0.0);
    CHECK(e1.norm() == 0.0);
  }
}

}  // namespace test_complex
