// dec/surface/complex.cpp — coarse cell lists, face-local cell ids, and d0, d1 on both complexes.
#include "polydec/dec/surface/complex.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace polydec {

using Triplet = Eigen::Triplet<double>;

CoarseComplex::CoarseComplex(const Mesh& mesh) : n_vertices_(mesh.n_vertices()) {
  const int nv = mesh.n_vertices(), nf = mesh.n_faces();
  // Pairs: for each i, the vertices j > i on faces of i.
  std::vector<int> js;
  std::vector<std::pair<int, int>> pair_list;
  std::vector<std::array<int, 3>> triple_list;
  std::vector<long> jk;
  pair_start_.assign(nv + 1, 0);
  triple_start_.assign(nv + 1, 0);
  for (int i = 0; i < nv; ++i) {
    js.clear();
    jk.clear();
    for (int f : mesh.vertex_faces(i)) {
      const auto face = mesh.face(f);
      for (int u : face)
        if (u > i) js.push_back(u);
      for (size_t a = 0; a < face.size(); ++a)
        for (size_t b = 0; b < face.size(); ++b)
          if (face[a] > i && face[b] > face[a]) jk.push_back(long(face[a]) * nv + face[b]);
    }
    std::sort(js.begin(), js.end());
    js.erase(std::unique(js.begin(), js.end()), js.end());
    for (int j : js) pair_list.emplace_back(i, j);
    pair_start_[i + 1] = int(pair_list.size());
    std::sort(jk.begin(), jk.end());
    jk.erase(std::unique(jk.begin(), jk.end()), jk.end());
    for (long key : jk) triple_list.push_back({i, int(key / nv), int(key % nv)});
    triple_start_[i + 1] = int(triple_list.size());
  }
  pairs_.resize(long(pair_list.size()), 2);
  for (size_t p = 0; p < pair_list.size(); ++p)
    pairs_.row(long(p)) << pair_list[p].first, pair_list[p].second;
  triples_.resize(long(triple_list.size()), 3);
  for (size_t t = 0; t < triple_list.size(); ++t)
    triples_.row(long(t)) << triple_list[t][0], triple_list[t][1], triple_list[t][2];

  pair_is_edge_.assign(pair_list.size(), 0);
  for (int e = 0; e < mesh.n_edges(); ++e)
    pair_is_edge_[pair_index(mesh.edges()(e, 0), mesh.edges()(e, 1))] = 1;

  // Face-local cells in rank order.
  face_order_offsets_.assign(nf + 1, 0);
  face_pair_offsets_.assign(nf + 1, 0);
  face_triple_offsets_.assign(nf + 1, 0);
  for (int f = 0; f < nf; ++f) {
    const long n = mesh.face_size(f);
    face_order_offsets_[f + 1] = face_order_offsets_[f] + int(n);
    face_pair_offsets_[f + 1] = face_pair_offsets_[f] + n * (n - 1) / 2;
    face_triple_offsets_[f + 1] = face_triple_offsets_[f] + n * (n - 1) * (n - 2) / 6;
  }
  face_order_.resize(face_order_offsets_[nf]);
  face_pairs_.resize(face_pair_offsets_[nf]);
  face_triples_.resize(face_triple_offsets_[nf]);
  for (int f = 0; f < nf; ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size());
    int* order = face_order_.data() + face_order_offsets_[f];
    std::iota(order, order + n, 0);
    std::sort(order, order + n, [&](int a, int b) { return face[a] < face[b]; });
    int* fp = face_pairs_.data() + face_pair_offsets_[f];
    int* ft = face_triples_.data() + face_triple_offsets_[f];
    for (int r = 0; r < n; ++r)
      for (int s = r + 1; s < n; ++s) {
        *fp++ = pair_index(face[order[r]], face[order[s]]);
        for (int t = s + 1; t < n; ++t) *ft++ = triple_index(face[order[r]], face[order[s]], face[order[t]]);
      }
  }
}

int CoarseComplex::pair_index(int i, int j) const {
  if (i > j) std::swap(i, j);
  if (i == j || i < 0 || j >= n_vertices_) return -1;
  const int* col = pairs_.col(1).data();
  const int* b = col + pair_start_[i];
  const int* e = col + pair_start_[i + 1];
  const int* it = std::lower_bound(b, e, j);
  return it != e && *it == j ? int(it - col) : -1;
}

int CoarseComplex::triple_index(int i, int j, int k) const {
  if (i > j) std::swap(i, j);
  if (j > k) std::swap(j, k);
  if (i > j) std::swap(i, j);
  if (i == j || j == k || i < 0 || k >= n_vertices_) return -1;
  int lo = triple_start_[i], hi = triple_start_[i + 1];
  while (lo < hi) {  // lower bound of (j, k) among rows lo..hi-1
    const int mid = (lo + hi) / 2;
    const int mj = triples_(mid, 1), mk = triples_(mid, 2);
    if (mj < j || (mj == j && mk < k))
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < triple_start_[i + 1] && triples_(lo, 1) == j && triples_(lo, 2) == k ? lo : -1;
}

Eigen::SparseMatrix<double> CoarseComplex::d0() const {
  std::vector<Triplet> t;
  t.reserve(2 * size_t(n_pairs()));
  for (int p = 0; p < n_pairs(); ++p) {
    t.emplace_back(p, pairs_(p, 0), -1.0);
    t.emplace_back(p, pairs_(p, 1), 1.0);
  }
  Eigen::SparseMatrix<double> d(n_pairs(), n_vertices_);
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

Eigen::SparseMatrix<double> CoarseComplex::d1() const {
  std::vector<Triplet> t;
  t.reserve(3 * size_t(n_triples()));
  for (int q = 0; q < n_triples(); ++q) {
    const int i = triples_(q, 0), j = triples_(q, 1), k = triples_(q, 2);
    t.emplace_back(q, pair_index(i, j), 1.0);
    t.emplace_back(q, pair_index(j, k), 1.0);
    t.emplace_back(q, pair_index(i, k), -1.0);
  }
  Eigen::SparseMatrix<double> d(n_triples(), n_pairs());
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

int local_triple_index(int n, int r, int s, int t) {
  // Triples starting with a rank below r, then pairs (s, t) of the n - r - 1 ranks above r.
  const int before = n * (n - 1) * (n - 2) / 6 - (n - r) * (n - r - 1) * (n - r - 2) / 6;
  return before + local_pair_index(n - r - 1, s - r - 1, t - r - 1);
}

int refined_n_vertices(const Mesh& mesh) { return mesh.n_vertices() + mesh.n_faces(); }
int refined_n_edges(const Mesh& mesh) { return mesh.n_edges() + mesh.n_halfedges(); }
int refined_n_triangles(const Mesh& mesh) { return mesh.n_halfedges(); }

Eigen::Vector2i refined_edge(const Mesh& mesh, int e) {
  if (e < mesh.n_edges()) return mesh.edges().row(e).transpose();
  const int h = e - mesh.n_edges();
  return {mesh.halfedge_source(h), mesh.n_vertices() + mesh.halfedge_face(h)};
}

Eigen::Vector3i refined_triangle(const Mesh& mesh, int h) {
  const int s = mesh.halfedge_source(h), t = mesh.halfedge_target(h);
  return {std::min(s, t), std::max(s, t), mesh.n_vertices() + mesh.halfedge_face(h)};
}

Eigen::SparseMatrix<double> refined_d0(const Mesh& mesh) {
  const int ne = refined_n_edges(mesh);
  std::vector<Triplet> t;
  t.reserve(2 * size_t(ne));
  for (int e = 0; e < ne; ++e) {
    const Eigen::Vector2i v = refined_edge(mesh, e);
    t.emplace_back(e, v[0], -1.0);
    t.emplace_back(e, v[1], 1.0);
  }
  Eigen::SparseMatrix<double> d(ne, refined_n_vertices(mesh));
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

Eigen::SparseMatrix<double> refined_d1(const Mesh& mesh) {
  const int ne = mesh.n_edges(), nh = mesh.n_halfedges();
  std::vector<Triplet> t;
  t.reserve(3 * size_t(nh));
  for (int h = 0; h < nh; ++h) {
    // Triangle (a, b, v) with a < b: +[a,b] + [b,v] - [a,v]; spoke [x,v] is that of the corner x.
    const int s = mesh.halfedge_source(h), n = mesh.halfedge_next(h);
    const int spoke_s = ne + h, spoke_t = ne + n;
    const bool up = s < mesh.halfedge_target(h);
    t.emplace_back(h, mesh.halfedge_edge(h), 1.0);
    t.emplace_back(h, up ? spoke_t : spoke_s, 1.0);
    t.emplace_back(h, up ? spoke_s : spoke_t, -1.0);
  }
  Eigen::SparseMatrix<double> d(nh, ne + nh);
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

}  // namespace polydec
