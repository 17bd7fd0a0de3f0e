// dec/surface/complex.h — the two cell complexes of FEEC on a polygon mesh (paper section 4.6) and
// their exterior derivatives d0, d1 (eq. 19).
//
// Coarse complex (the cells of the coarsened Whitney forms):
//   0-cells: the mesh vertices;
//   1-cells: the unordered vertex pairs {i, j} that share a face (polygon edges AND diagonals);
//   2-cells: the vertex triples {i, j, k} that share a face.
// Every cell is stored with increasing vertex indices, i < j < k, and oriented that way; the
// cells are numbered in lexicographic order of their sorted vertex indices. This numbering is
// stable: it depends on the connectivity only.
//
// Refined complex (the fan triangulation of paper section 4.1; see dec/surface/refinement.h):
//   0-cells: vertices 0..|V|-1 (the mesh's) and |V| + f (the virtual vertex of face f);
//   1-cells: first the |E| mesh edges in Mesh::edges() order, oriented i -> j with i < j; then
//            one spoke per halfedge h, 1-cell |E| + h = (source(h), |V| + face(h));
//   2-cells: one triangle per halfedge h with vertices {source(h), target(h), |V| + face(h)},
//            oriented by increasing vertex index, i.e. (min, max, |V| + f). Its orientation
//            agrees with the face's when source(h) < target(h) (refined_triangle_sign = +1).
// Both orientations are by increasing index, so d0 and d1 are the same combinatorial formula
// (eq. 19) on both complexes: (d0 u)_(ij) = u_j - u_i, (d1 c)_(ijk) = c_ij + c_jk - c_ik.
// Integer-valued, column-major sparse matrices; d1 d0 = 0 exactly.
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "polydec/dec/mesh/mesh.h"

namespace polydec {

class CoarseComplex {
 public:
  CoarseComplex() = default;
  explicit CoarseComplex(const Mesh& mesh);

  int n_vertices() const { return n_vertices_; }
  int n_faces() const { return int(face_order_offsets_.size()) - 1; }
  int n_pairs() const { return int(pairs_.rows()); }
  int n_triples() const { return int(triples_.rows()); }

  // Cell lists: |C1| x 2 rows (i, j), i < j, and |C2| x 3 rows (i, j, k), i < j < k, lexicographic.
  const Eigen::MatrixX2i& pairs() const { return pairs_; }
  const Eigen::MatrixX3i& triples() const { return triples_; }

  // Index of the cell with these vertices (any order), or -1 if they share no face.
  int pair_index(int i, int j) const;
  int triple_index(int i, int j, int k) const;

  // Whether pair p is a mesh edge (as opposed to a polygon diagonal).
  bool is_edge(int p) const { return pair_is_edge_[p] != 0; }

  // Face f's corners in increasing vertex index: positions in face order (0..n-1), i.e.
  // sorted_corners(f)[r] is the corner of rank r. Ranks define the face-local cell order.
  std::span<const int> sorted_corners(int f) const {
    return {face_order_.data() + face_order_offsets_[f],
            size_t(face_order_offsets_[f + 1] - face_order_offsets_[f])};
  }
  // The n(n-1)/2 pairs of face f, ids in lexicographic order of corner ranks (r < s), which is
  // increasing id order.
  std::span<const int> face_pairs(int f) const {
    return {face_pairs_.data() + face_pair_offsets_[f],
            size_t(face_pair_offsets_[f + 1] - face_pair_offsets_[f])};
  }
  // The n(n-1)(n-2)/6 triples of face f, likewise.
  std::span<const int> face_triples(int f) const {
    return {face_triples_.data() + face_triple_offsets_[f],
            size_t(face_triple_offsets_[f + 1] - face_triple_offsets_[f])};
  }

  // Coboundaries (eq. 19): d0 is |C1| x |V|, d1 is |C2| x |C1|.
  Eigen::SparseMatrix<double> d0() const;
  Eigen::SparseMatrix<double> d1() const;

 private:
  int n_vertices_ = 0;
  Eigen::MatrixX2i pairs_;
  Eigen::MatrixX3i triples_;
  std::vector<int> pair_start_{0}, triple_start_{0};  // CSR by first vertex
  std::vector<unsigned char> pair_is_edge_;
  std::vector<int> face_order_offsets_{0}, face_order_;
  std::vector<long> face_pair_offsets_{0}, face_triple_offsets_{0};
  std::vector<int> face_pairs_, face_triples_;
};

// Index of local pair (r, s), r < s, among the n(n-1)/2 pairs of an n-gon in lexicographic order.
inline int local_pair_index(int n, int r, int s) { return r * n - r * (r + 1) / 2 + (s - r - 1); }

// Index of local triple (r, s, t), r < s < t, among the n(n-1)(n-2)/6 triples in lexicographic order.
int local_triple_index(int n, int r, int s, int t);

// Refined complex sizes and maps (see the header comment for the numbering).
int refined_n_vertices(const Mesh& mesh);   // |V| + |F|
int refined_n_edges(const Mesh& mesh);      // |E| + |H|
int refined_n_triangles(const Mesh& mesh);  // |H|
// Vertex indices of refined 1-cell e, (low, high).
Eigen::Vector2i refined_edge(const Mesh& mesh, int e);
// Vertex indices of refined triangle h, increasing.
Eigen::Vector3i refined_triangle(const Mesh& mesh, int h);
// +1 when refined triangle h (oriented by increasing index) agrees with its face's orientation.
inline int refined_triangle_sign(const Mesh& mesh, int h) {
  return mesh.halfedge_source(h) < mesh.halfedge_target(h) ? 1 : -1;
}

// d0 on the refined complex, (|E| + |H|) x (|V| + |F|).
Eigen::SparseMatrix<double> refined_d0(const Mesh& mesh);
// d1 on the refined complex, |H| x (|E| + |H|).
Eigen::SparseMatrix<double> refined_d1(const Mesh& mesh);

}  // namespace polydec
