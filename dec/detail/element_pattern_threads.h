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
  constexpr bool with_slots = K != SlotKind::none;
  const int T = resolve_threads(threads);
  const element_pattern_impl::Incidences in =
      element_pattern_impl::incidences(n_nodes, n_elements, nodes_of, with_slots);
  const std::vector<int>& start = in.start;
  const size_t n_incidences = size_t(start[size_t(n_nodes)]);
  // Node ranges with about equal numbers of incidences, one per thread.
  std::vector<int> first(size_t(T) + 1, n_nodes);
  first[0] = 0;
  for (int t = 1; t < T; ++t)
    first[size_t(t)] = int(std::lower_bound(start.begin(), start.end(), int(n_incidences * size_t(t) / size_t(T))) -
                           start.begin());
  for (int t = 1; t <= T; ++t) first[size_t(t)] = std::max(first[size_t(t)], first[size_t(t) - 1]);
  std::vector<std::vector<int>> marks(static_cast<size_t>(T));
  std::vector<int> outer(size_t(n_nodes) + 1, 0), longest(size_t(T), 0);
  run_on_threads(T, [&](int t) {
    std::vector<int>& mark = marks[size_t(t)];
    mark.assign(size_t(n_nodes), -1);
    for (int v = first[size_t(t)]; v < first[size_t(t) + 1]; ++v) {
      int count = 0;
      element_pattern_impl::gather_column(in, v, nodes_of, mark.data(), v, [&](int) { ++count; });
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
  if (slotted) element_pattern_impl::allocate_slots<K>(ep, n_elements, nodes_of);
  // Column v's rows at their place, sorted; its values zero; its slots from where[u] (the row's
  // position, absolute or past the column's start), kept in the mark array (positions are >= 0,
  // the gather's tags of this pass are negative).
  run_on_threads(T, [&](int t) {
    std::vector<int>& mark = marks[size_t(t)];
    for (int v = first[size_t(t)]; v < first[size_t(t) + 1]; ++v) {
      const int col = outer[size_t(v)];
      int end = col;
      element_pattern_impl::gather_column(in, v, nodes_of, mark.data(), -2 - v, [&](int u) { inner[end++] = u; });
      sort_column(inner + col, inner + end);
      std::fill(values + col, values + end, 0.0);
      if (!slotted) continue;
      for (int k = col; k < end; ++k) mark[size_t(inner[k])] = absolute ? k : k - col;
      if constexpr (absolute)
        element_pattern_impl::column_slots<int>(in, v, nodes_of, ep.offsets.data(), mark.data(), ep.slots.data());
      else if constexpr (with_slots)
        element_pattern_impl::column_slots<std::uint16_t>(in, v, nodes_of, ep.offsets.data(), mark.data(),
                                                          ep.relative_slots.get());
    }
  });
  return ep;
}

}  // namespace polydec::detail
