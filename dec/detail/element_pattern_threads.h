// dec/detail/element_pattern_threads.h — element_pattern (dec/detail/element_pattern.h) on several
// threads: bitwise the same pattern and slots, with the columns counted, gathered into place,
// sorted and their slots written by ranges of nodes in parallel, so that the large arrays (rows,
// values, slots) are also first touched (page faults, page zeroing) by all threads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "polydec/dec/detail/element_pattern.h"
#include "polydec/dec/detail/threads.h"

namespace polydec::detail {

// element_pattern<K>(n_nodes, n_elements, nodes_of) on `threads` threads (0: all cores): each
// column is gathered twice (counted, then written at its final place) and sorted in place.
template <SlotKind K, class NodesOf>
ElementPattern element_pattern_threaded(int n_nodes, int n_elements, NodesOf&& nodes_of, int threads) {
  using element_pattern_impl::sort_column;
  using element_pattern_impl::with_size;
  constexpr bool with_slots = K != SlotKind::none;
  const int T = resolve_threads(threads);
  // The elements of each node (CSR), with the node's position in the element: as element_pattern.
  std::vector<int> start(size_t(n_nodes) + 1, 0);
  for (int e = 0; e < n_elements; ++e) {
    const auto& nodes = nodes_of(e);
    const int* p = std::data(nodes);
    for (size_t a = 0; a < std::size(nodes); ++a) ++start[size_t(p[a]) + 1];
  }
  for (int v = 0; v < n_nodes; ++v) start[size_t(v) + 1] += start[size_t(v)];
  const size_t n_incidences = size_t(start[size_t(n_nodes)]);
  const auto elements = uninitialized_on_huge_pages<int>(n_incidences);  // every entry written below
  const auto local = uninitialized_on_huge_pages<int>(with_slots ? n_incidences : 0);
  {
    std::vector<int> next(start.begin(), start.end() - 1);
    for (int e = 0; e < n_elements; ++e) {
      const auto& nodes = nodes_of(e);
      const int* p = std::data(nodes);
      const int m = int(std::size(nodes));
      for (int b = 0; b < m; ++b) {
        const int k = next[size_t(p[b])]++;
        elements[size_t(k)] = e;
        if constexpr (with_slots) local[size_t(k)] = b;
      }
    }
  }
  // Node ranges with about equal numbers of incidences, one per thread.
  std::vector<int> first(size_t(T) + 1, n_nodes);
  first[0] = 0;
  for (int t = 1; t < T; ++t)
    first[size_t(t)] = int(std::lower_bound(start.begin(), start.end(), int(n_incidences * size_t(t) / size_t(T))) -
                           start.begin());
  for (int t = 1; t <= T; ++t) first[size_t(t)] = std::max(first[size_t(t)], first[size_t(t) - 1]);
  // Calls row(u) for the rows u of column v in first-seen order, each once; mark[u] == tag
  // means u was seen (tags differ per column and pass).
  auto gather = [&](int v, std::vector<int>& mark, int tag, auto&& row) {
    for (int k = start[size_t(v)]; k < start[size_t(v) + 1]; ++k) {
      const auto& nodes = nodes_of(elements[size_t(k)]);
      const int* p = std::data(nodes);
      with_size(long(std::size(nodes)), [&](auto M) {
        const int m = M() > 0 ? M() : int(std::size(nodes));
        for (int a = 0; a < m; ++a) {
          const int u = p[a];
          if (mark[size_t(u)] != tag) {
            mark[size_t(u)] = tag;
            row(u);
          }
        }
      });
    }
  };
  std::vector<std::vector<int>> marks(static_cast<size_t>(T));
  std::vector<int> outer(size_t(n_nodes) + 1, 0), longest(size_t(T), 0);
  run_on_threads(T, [&](int t) {
    std::vector<int>& mark = marks[size_t(t)];
    mark.assign(size_t(n_nodes), -1);
    for (int v = first[size_t(t)]; v < first[size_t(t) + 1]; ++v) {
      int count = 0;
      gather(v, mark, v, [&](int) { ++count; });
      outer[size_t(v) + 1] = count;
      longest[size_t(t)] = std::max(longest[size_t(t)], count);
    }
  });
  for (int v = 0; v < n_nodes; ++v) outer[size_t(v) + 1] += outer[size_t(v)];
  const int nnz = outer[size_t(n_nodes)];
  const bool relative_fits = *std::max_element(longest.begin(), longest.end()) <= 65535;
  ElementPattern ep;
  Eigen::SparseMatrix<double>& pattern = ep.pattern;
  pattern.resize(n_nodes, n_nodes);
  pattern.resizeNonZeros(nnz);
  advise_huge_pages(pattern.innerIndexPtr(), sizeof(int) * size_t(nnz));
  advise_huge_pages(pattern.valuePtr(), sizeof(double) * size_t(nnz));
  std::copy(outer.begin(), outer.end(), pattern.outerIndexPtr());
  int* inner = pattern.innerIndexPtr();
  double* values = pattern.valuePtr();
  constexpr bool absolute = K == SlotKind::absolute;
  const bool slotted = with_slots && (absolute || relative_fits);
  if (slotted) {
    ep.offsets.resize(size_t(n_elements) + 1);
    ep.offsets[0] = 0;
    for (int e = 0; e < n_elements; ++e) {
      const long m = long(std::size(nodes_of(e)));
      ep.offsets[size_t(e) + 1] = ep.offsets[size_t(e)] + m * m;
    }
    const size_t n_slots = size_t(ep.offsets[size_t(n_elements)]);
    if constexpr (absolute) {
      ep.slots.reserve(n_slots);
      advise_huge_pages(ep.slots.data(), sizeof(int) * n_slots);
      ep.slots.resize(n_slots);  // zeroed here, overwritten by the threads
    } else if constexpr (with_slots) {
      ep.relative_slots = uninitialized_on_huge_pages<std::uint16_t>(n_slots);  // all written below
    }
  }
  // Column v's rows at their place, sorted; its values zero; its slots from where[u] (the row's
  // position, absolute or past the column's start), kept in the mark array (positions are >= 0,
  // the gather's tags of this pass are negative).
  run_on_threads(T, [&](int t) {
    std::vector<int>& mark = marks[size_t(t)];
    for (int v = first[size_t(t)]; v < first[size_t(t) + 1]; ++v) {
      const int col = outer[size_t(v)];
      int end = col;
      gather(v, mark, -2 - v, [&](int u) { inner[end++] = u; });
      sort_column(inner + col, inner + end);
      std::fill(values + col, values + end, 0.0);
      if (!slotted) continue;
      for (int k = col; k < end; ++k) mark[size_t(inner[k])] = absolute ? k : k - col;
      for (int k = start[size_t(v)]; k < start[size_t(v) + 1]; ++k) {
        const int e = elements[size_t(k)];
        const auto& nodes = nodes_of(e);
        const int* p = std::data(nodes);
        with_size(long(std::size(nodes)), [&](auto M) {
          const int m = M() > 0 ? M() : int(std::size(nodes));
          const long s0 = ep.offsets[size_t(e)] + local[size_t(k)];
          for (int a = 0; a < m; ++a) {
            const int where = mark[size_t(p[a])];
            if constexpr (absolute)
              ep.slots[size_t(s0 + long(a) * m)] = where;
            else if constexpr (with_slots)
              ep.relative_slots[size_t(s0 + long(a) * m)] = std::uint16_t(where);
          }
        });
      }
    }
  });
  return ep;
}

}  // namespace polydec::detail
