// dec/detail/edge_buckets.h — vertex pairs (the sides of faces) sorted as (smaller vertex, larger
// vertex, pair id) keys would be by a comparison sort, in linear time: a counting sort on the
// smaller vertex, then each bucket by (larger vertex, id). Surface and volume meshes number their
// edges in this order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "polydec/dec/detail/huge_pages.h"

namespace polydec::detail {

struct EdgeBuckets {
  std::vector<int> start;  // |V| + 1: bucket v (pairs whose smaller vertex is v) is [start[v], start[v + 1])
  std::vector<int> other;  // the larger vertex of each pair, ascending within a bucket
  std::vector<int> id;     // the pair's index, ascending among equal (v, other); empty unless asked for
};

// n pairs of vertices in [0, nv) (either order), numbered in the order in which each_pair(emit)
// calls emit(p, q); it is called twice. with_ids: fill EdgeBuckets::id.
template <class EachPair>
EdgeBuckets bucket_edges(int nv, int n, EachPair&& each_pair, bool with_ids) {
  EdgeBuckets b;
  assign_on_huge_pages(b.start, std::size_t(nv) + 1, 0);
  assign_on_huge_pages(b.other, std::size_t(n), 0);
  if (with_ids) assign_on_huge_pages(b.id, std::size_t(n), 0);
  each_pair([&](int p, int q) { ++b.start[std::size_t(std::min(p, q)) + 1]; });
  for (int v = 0; v < nv; ++v) b.start[std::size_t(v) + 1] += b.start[std::size_t(v)];
  {
    std::vector<int> fill(b.start.begin(), b.start.end() - 1);
    int i = 0;
    each_pair([&](int p, int q) {
      const int slot = fill[std::size_t(std::min(p, q))]++;
      b.other[std::size_t(slot)] = std::max(p, q);
      if (with_ids) b.id[std::size_t(slot)] = i;  // ascending within each bucket already
      ++i;
    });
  }
  // Each bucket by the larger vertex; ids stay ascending among equal ones (a stable sort). Small
  // buckets (the usual valences) by insertion, large ones (a fan around one vertex) by std::stable_sort.
  std::vector<std::pair<int, int>> large;
  for (int v = 0; v < nv; ++v) {
    const int lo = b.start[std::size_t(v)], hi = b.start[std::size_t(v) + 1];
    if (hi - lo <= 32) {
      for (int i = lo + 1; i < hi; ++i)
        for (int j = i; j > lo && b.other[std::size_t(j)] < b.other[std::size_t(j) - 1]; --j) {
          std::swap(b.other[std::size_t(j)], b.other[std::size_t(j) - 1]);
          if (with_ids) std::swap(b.id[std::size_t(j)], b.id[std::size_t(j) - 1]);
        }
      continue;
    }
    large.clear();
    for (int i = lo; i < hi; ++i) large.emplace_back(b.other[std::size_t(i)], with_ids ? b.id[std::size_t(i)] : 0);
    std::stable_sort(large.begin(), large.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (int i = lo; i < hi; ++i) {
      b.other[std::size_t(i)] = large[std::size_t(i - lo)].first;
      if (with_ids) b.id[std::size_t(i)] = large[std::size_t(i - lo)].second;
    }
  }
  return b;
}

}  // namespace polydec::detail
