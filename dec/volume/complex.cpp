// dec/volume/complex.cpp — coarse and refined simplicial complexes of a polyhedral mesh, d0..d2.
#include "polydec/dec/volume/complex.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace polydec {

namespace volume_complex_detail {
namespace {

template <size_t K>
void sort_unique(std::vector<std::array<int, K>>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

template <size_t K>
int find(const std::vector<std::array<int, K>>& v, std::span<const int> s) {
  std::array<int, K> key;
  std::copy(s.begin(), s.end(), key.begin());
  const auto it = std::lower_bound(v.begin(), v.end(), key);
  return it != v.end() && *it == key ? int(it - v.begin()) : -1;
}

template <size_t K>
Eigen::SparseMatrix<double> coboundary(const SimplexComplex3& cx,
                                       const std::vector<std::array<int, K>>& cells, int n_faces) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(cells.size() * K);
  std::array<int, K - 1> face;
  for (size_t s = 0; s < cells.size(); ++s)
    for (size_t i = 0; i < K; ++i) {
      for (size_t j = 0, l = 0; j < K; ++j)
        if (j != i) face[l++] = cells[s][j];
      const int f = K == 2 ? face[0] : cx.index(face);
      if (f < 0) throw std::logic_error("volume complex: face of a simplex missing");
      t.emplace_back(int(s), f, i % 2 == 0 ? 1.0 : -1.0);
    }
  Eigen::SparseMatrix<double> d(long(cells.size()), n_faces);
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

}  // namespace
}  // namespace volume_complex_detail

SimplexComplex3::SimplexComplex3(int n_vertices, const std::vector<int>& offsets,
                                 const std::vector<int>& groups, int max_dimension)
    : n_vertices_(n_vertices) {
  // Each dimension on its own, made unique every kChunk groups: neighbouring groups (the
  // sub-tetrahedra of one cell) share most of their simplices, so the lists never grow much beyond
  // their final size (all subsets at once, 14 per tetrahedron, would be several times it).
  constexpr size_t kChunk = 1 << 14;
  const size_t n_groups = offsets.empty() ? 0 : offsets.size() - 1;
  std::vector<int> g;
  auto generate = [&](auto& out, auto emit) {
    for (size_t begin = 0; begin < n_groups; begin += kChunk) {
      const size_t first = out.size();
      for (size_t k = begin; k < std::min(n_groups, begin + kChunk); ++k) {
        g.assign(groups.begin() + offsets[k], groups.begin() + offsets[k + 1]);
        std::sort(g.begin(), g.end());
        emit(out);
      }
      std::sort(out.begin() + long(first), out.end());
      out.erase(std::unique(out.begin() + long(first), out.end()), out.end());
    }
    volume_complex_detail::sort_unique(out);
  };
  if (max_dimension >= 1)
    generate(pairs_, [&](auto& out) {
      const int m = int(g.size());
      for (int a = 0; a < m; ++a)
        for (int b = a + 1; b < m; ++b) out.push_back({g[a], g[b]});
    });
  if (max_dimension >= 2)
    generate(triples_, [&](auto& out) {
      const int m = int(g.size());
      for (int a = 0; a < m; ++a)
        for (int b = a + 1; b < m; ++b)
          for (int c = b + 1; c < m; ++c) out.push_back({g[a], g[b], g[c]});
    });
  if (max_dimension >= 3)
    generate(quads_, [&](auto& out) {
      const int m = int(g.size());
      for (int a = 0; a < m; ++a)
        for (int b = a + 1; b < m; ++b)
          for (int c = b + 1; c < m; ++c)
            for (int d = c + 1; d < m; ++d) out.push_back({g[a], g[b], g[c], g[d]});
    });
}

int SimplexComplex3::n_simplices(int k) const {
  switch (k) {
    case 0:
      return n_vertices_;
    case 1:
      return n_pairs();
    case 2:
      return n_triples();
    case 3:
      return n_quads();
    default:
      throw std::invalid_argument("simplex dimension " + std::to_string(k) + " (0..3)");
  }
}

int SimplexComplex3::index(std::span<const int> s) const {
  switch (s.size()) {
    case 1:
      return s[0] >= 0 && s[0] < n_vertices_ ? s[0] : -1;
    case 2:
      return volume_complex_detail::find(pairs_, s);
    case 3:
      return volume_complex_detail::find(triples_, s);
    case 4:
      return volume_complex_detail::find(quads_, s);
    default:
      return -1;
  }
}

Eigen::SparseMatrix<double> SimplexComplex3::d(int k) const {
  switch (k) {
    case 0:
      return volume_complex_detail::coboundary(*this, pairs_, n_vertices_);
    case 1:
      return volume_complex_detail::coboundary(*this, triples_, n_pairs());
    case 2:
      return volume_complex_detail::coboundary(*this, quads_, n_triples());
    default:
      throw std::invalid_argument("d_k for k = " + std::to_string(k) + " (0..2)");
  }
}

Eigen::MatrixXi SimplexComplex3::simplices(int k) const {
  Eigen::MatrixXi out(n_simplices(k), k + 1);
  for (int s = 0; s < out.rows(); ++s)
    for (int j = 0; j <= k; ++j) out(s, j) = k == 1 ? pairs_[s][j] : k == 2 ? triples_[s][j] : quads_[s][j];
  return out;
}

int max_dec_cell_vertices(int k) {
  if (k < 0 || k > 3) throw std::invalid_argument("DEC degree " + std::to_string(k) + " (0..3)");
  if (k == 0) return std::numeric_limits<int>::max();
  // The largest m with C(m, k+1)^2 <= kMaxDecLocalBlock.
  auto block = [k](long m) {
    long c = 1;
    for (long i = 0; i <= k; ++i) c = c * (m - i) / (i + 1);
    return c * c;
  };
  int m = k + 1;
  while (block(m + 1) <= kMaxDecLocalBlock) ++m;
  return m;
}

int volume_dec_max_degree(const VolumeMesh& mesh) {
  size_t largest = 0;
  for (int c = 0; c < mesh.n_cells(); ++c) largest = std::max(largest, mesh.cell_vertices(c).size());
  int k = 0;
  while (k < 3 && int(largest) <= max_dec_cell_vertices(k + 1)) ++k;
  return k;
}

SimplexComplex3 volume_coarse_complex(const VolumeMesh& mesh, int max_degree) {
  const int limit = max_dec_cell_vertices(max_degree);
  std::vector<int> offsets{0}, groups;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const auto v = mesh.cell_vertices(c);
    if (int(v.size()) > limit)
      throw std::invalid_argument("cell " + std::to_string(c) + " has " + std::to_string(v.size()) +
                                  " vertices; DEC of degree " + std::to_string(max_degree) +
                                  " on volumes supports cells of at most " + std::to_string(limit) +
                                  " (this mesh allows degree " + std::to_string(volume_dec_max_degree(mesh)) + ")");
    groups.insert(groups.end(), v.begin(), v.end());
    offsets.push_back(int(groups.size()));
  }
  return SimplexComplex3(mesh.n_vertices(), offsets, groups, max_degree);
}

SimplexComplex3 volume_refined_complex(const VolumeMesh& mesh, const VolumeRefinement& refinement) {
  check_refinement(mesh, refinement, "volume_refined_complex");
  std::vector<int> offsets{0}, groups;
  for (const RefinedTet& t : refined_tets(mesh, refinement)) {
    groups.insert(groups.end(), t.v, t.v + 4);
    offsets.push_back(int(groups.size()));
  }
  return SimplexComplex3(mesh.n_vertices() + mesh.n_faces() + mesh.n_cells(), offsets, groups);
}

}  // namespace polydec
