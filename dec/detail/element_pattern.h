// dec/detail/element_pattern.h — the symbolic part of every element-by-element assembly (surface
// and volume S and M, the coarse stars): the sparsity pattern of all node pairs sharing an
// element, and for every element the slots of its dense local block in the pattern's value array.
#pragma once

#include <Eigen/Sparse>
#include <algorithm>
#include <cstdint>
#include <iterator>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "polydec/dec/detail/huge_pages.h"

namespace polydec::detail {

// How element_pattern records where the local entries of an element sit.
enum class SlotKind {
  none,             // the pattern only
  absolute,         // ElementPattern::slots: int index into pattern.valuePtr()
  column_relative,  // ElementPattern::relative_slots: uint16 offset past the start of the entry's
                    // column (half the memory and bandwidth of absolute slots)
};

// How element_pattern orders each column's rows, which are collected in first-seen order.
enum class ColumnOrder {
  transpose,  // one transposition of the whole pattern (it is symmetric): no comparisons, one
              // extra buffer of nnz ints; faster for long columns (hexahedra: 27 rows)
  sort,       // each column sorted in place in the pattern's own arrays (insertion sort up to 32
              // rows), which keep the capacity of the bound sum m_e^2 (pages never touched):
              // faster for short columns whose rows are far apart (star1: ~9 rows)
};

// Element e's slots are [offsets[e], offsets[e + 1]), m_e^2 of them for its m_e nodes, row-major:
// slot a m_e + b is entry (nodes[a], nodes[b]), i.e. row nodes[a] of column nodes[b]. Absolute,
// it indexes pattern.valuePtr(); column-relative, pattern.valuePtr() + outerIndexPtr()[nodes[b]].
// Moving swaps the pattern (Eigen 3.4's SparseMatrix copies on move); copying is not allowed.
struct ElementPattern {
  ElementPattern() = default;
  ElementPattern(ElementPattern&& other) noexcept { *this = std::move(other); }
  ElementPattern& operator=(ElementPattern&& other) noexcept {
    pattern.swap(other.pattern);
    offsets = std::move(other.offsets);
    slots = std::move(other.slots);
    relative_slots = std::move(other.relative_slots);
    return *this;
  }

  Eigen::SparseMatrix<double> pattern;  // n_nodes x n_nodes, symmetric, values zero, rows ascending
  std::vector<long> offsets;            // |E| + 1 prefix sums of m_e^2; empty without slots
  std::vector<int> slots;               // SlotKind::absolute
  std::unique_ptr<std::uint16_t[]> relative_slots;  // SlotKind::column_relative; null when a column
                                                    // has more than 65535 entries
};

namespace element_pattern_impl {

// Calls f with std::integral_constant<int, m> for the common element sizes (triangles, quads,
// hexagons and a quad's 6 vertex pairs, hexahedra), else with 0 (any size), so that the
// per-element loops unroll.
// Sorts [b, e): insertion sort for short ranges (columns are short and often nearly sorted).
inline void sort_column(int* b, int* e) {
  if (e - b > 32) {
    std::sort(b, e);
    return;
  }
  for (int* i = b + 1; i < e; ++i) {
    const int x = *i;
    int* j = i;
    for (; j > b && j[-1] > x; --j) *j = j[-1];
    *j = x;
  }
}

template <class F>
inline void with_size(long m, F&& f) {
  switch (m) {
    case 3:
      f(std::integral_constant<int, 3>{});
      break;
    case 4:
      f(std::integral_constant<int, 4>{});
      break;
    case 6:
      f(std::integral_constant<int, 6>{});
      break;
    case 8:
      f(std::integral_constant<int, 8>{});
      break;
    default:
      f(std::integral_constant<int, 0>{});
      break;
  }
}

// The elements of each node (CSR, ascending element order) with the node's position in each.
struct Incidences {
  std::vector<int> start;                  // n_nodes + 1
  std::unique_ptr<int[]> elements, local;  // n_incidences each; local null unless asked for
  size_t bound = 0;                        // sum m_e^2: at least nnz and the number of slots
};

template <class NodesOf>
Incidences incidences(int n_nodes, int n_elements, NodesOf& nodes_of, bool with_local) {
  Incidences in;
  in.start.assign(size_t(n_nodes) + 1, 0);
  for (int e = 0; e < n_elements; ++e) {
    const auto& nodes = nodes_of(e);
    const int* p = std::data(nodes);
    const size_t m = std::size(nodes);
    for (size_t a = 0; a < m; ++a) ++in.start[size_t(p[a]) + 1];
    in.bound += m * m;
  }
  for (int v = 0; v < n_nodes; ++v) in.start[size_t(v) + 1] += in.start[size_t(v)];
  const size_t n_incidences = size_t(in.start[size_t(n_nodes)]);
  std::vector<int> next(in.start.begin(), in.start.end() - 1);
  in.elements = uninitialized_on_huge_pages<int>(n_incidences);  // every entry written below
  in.local = uninitialized_on_huge_pages<int>(with_local ? n_incidences : 0);
  for (int e = 0; e < n_elements; ++e) {
    const auto& nodes = nodes_of(e);
    const int* p = std::data(nodes);
    const int m = int(std::size(nodes));
    for (int b = 0; b < m; ++b) {
      const int k = next[size_t(p[b])]++;
      in.elements[size_t(k)] = e;
      if (with_local) in.local[size_t(k)] = b;
    }
  }
  return in;
}

// Calls row(u) for the nodes u of node v's elements, each once, in first-seen order: mark[u] ==
// tag marks u as seen (a tag not used before in mark for this column).
template <class NodesOf, class Row>
inline void gather_column(const Incidences& in, int v, NodesOf& nodes_of, int* mark, int tag, Row&& row) {
  for (int k = in.start[size_t(v)]; k < in.start[size_t(v) + 1]; ++k) {
    const auto& nodes = nodes_of(in.elements[size_t(k)]);
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
}

// The slots of node v's elements in column v: each element e, v its node b, gets its slots
// (a, b) = entry (nodes[a], v) at out[offsets[e] + a m_e + b] = where[nodes[a]].
template <class Slot, class NodesOf>
inline void column_slots(const Incidences& in, int v, NodesOf& nodes_of, const long* offsets, const int* where,
                         Slot* out) {
  for (int k = in.start[size_t(v)]; k < in.start[size_t(v) + 1]; ++k) {
    const int e = in.elements[size_t(k)];
    const auto& nodes = nodes_of(e);
    const int* p = std::data(nodes);
    with_size(long(std::size(nodes)), [&](auto M) {
      const int m = M() > 0 ? M() : int(std::size(nodes));
      Slot* s = out + offsets[e] + in.local[size_t(k)];
      for (int a = 0; a < m; ++a) s[long(a) * m] = Slot(where[size_t(p[a])]);
    });
  }
}

// ep.offsets (the prefix sums of m_e^2) and ep's slot array of kind K (not yet written).
template <SlotKind K, class NodesOf>
void allocate_slots(ElementPattern& ep, int n_elements, NodesOf& nodes_of) {
  ep.offsets.resize(size_t(n_elements) + 1);
  ep.offsets[0] = 0;
  for (int e = 0; e < n_elements; ++e) {
    const long m = long(std::size(nodes_of(e)));
    ep.offsets[size_t(e) + 1] = ep.offsets[size_t(e)] + m * m;
  }
  const size_t n_slots = size_t(ep.offsets[size_t(n_elements)]);
  if constexpr (K == SlotKind::absolute) {
    ep.slots.reserve(n_slots);
    advise_huge_pages(ep.slots.data(), sizeof(int) * n_slots);
    ep.slots.resize(n_slots);
  } else if constexpr (K == SlotKind::column_relative) {
    ep.relative_slots = uninitialized_on_huge_pages<std::uint16_t>(n_slots);  // the caller writes all
  }
}

}  // namespace element_pattern_impl

// The pattern of n_nodes x n_nodes entries (u, v) such that u and v are nodes of one element, and
// the elements' slots of kind K. nodes_of(e) gives element e's nodes as a contiguous range
// (std::data, std::size) of ids in [0, n_nodes), distinct within the element, in any order.
// Rows are collected per column in first-seen order and ordered as O says; the large buffers are
// advised for huge pages and the scratch ones left uninitialized.
template <SlotKind K, ColumnOrder O = ColumnOrder::transpose, class NodesOf>
ElementPattern element_pattern(int n_nodes, int n_elements, NodesOf&& nodes_of) {
  using element_pattern_impl::sort_column;
  constexpr bool with_slots = K != SlotKind::none;
  const element_pattern_impl::Incidences in =
      element_pattern_impl::incidences(n_nodes, n_elements, nodes_of, with_slots);
  const size_t bound = in.bound;
  // Column v: the nodes of v's elements, each once (marked with v), in first-seen order, written
  // to a buffer of the bound sum m_e^2 (the pages never written are never touched): the pattern's
  // own index array when sorting in place (trimmed afterwards without copying), else scratch.
  ElementPattern ep;
  Eigen::SparseMatrix<double>& pattern = ep.pattern;
  std::vector<int> outer(size_t(n_nodes) + 1, 0), mark(size_t(n_nodes), -1);
  std::unique_ptr<int[]> unsorted;
  int* rows;
  if constexpr (O == ColumnOrder::sort) {
    pattern.resize(n_nodes, n_nodes);
    pattern.resizeNonZeros(long(bound));
    advise_huge_pages(pattern.innerIndexPtr(), sizeof(int) * bound);
    advise_huge_pages(pattern.valuePtr(), sizeof(double) * bound);
    rows = pattern.innerIndexPtr();
  } else {
    unsorted = uninitialized_on_huge_pages<int>(bound);
    rows = unsorted.get();
  }
  int nnz = 0, longest = 0;
  for (int v = 0; v < n_nodes; ++v) {
    element_pattern_impl::gather_column(in, v, nodes_of, mark.data(), v, [&](int u) { rows[nnz++] = u; });
    if constexpr (O == ColumnOrder::sort) sort_column(rows + outer[size_t(v)], rows + nnz);
    outer[size_t(v) + 1] = nnz;
    longest = std::max(longest, nnz - outer[size_t(v)]);
  }
  int* inner;
  if constexpr (O == ColumnOrder::sort) {
    pattern.data().resize(nnz);  // within the capacity: no copy
    inner = pattern.innerIndexPtr();
    std::copy(outer.begin(), outer.end(), pattern.outerIndexPtr());
  } else {
    // Sorted by transposition (the pattern is symmetric): visiting the columns v in order and
    // appending v to column u for each row u of column v leaves every column's rows ascending.
    pattern.resize(n_nodes, n_nodes);
    pattern.resizeNonZeros(nnz);
    advise_huge_pages(pattern.innerIndexPtr(), sizeof(int) * size_t(nnz));
    advise_huge_pages(pattern.valuePtr(), sizeof(double) * size_t(nnz));
    std::copy(outer.begin(), outer.end(), pattern.outerIndexPtr());
    inner = pattern.innerIndexPtr();
    std::vector<int> next(outer.begin(), outer.end() - 1);
    for (int v = 0; v < n_nodes; ++v)
      for (int k = outer[size_t(v)]; k < outer[size_t(v) + 1]; ++k) inner[next[size_t(unsorted[size_t(k)])]++] = v;
    unsorted.reset();
  }
  std::fill(pattern.valuePtr(), pattern.valuePtr() + nnz, 0.0);
  if constexpr (!with_slots) {
    return ep;
  } else {
    if (K == SlotKind::column_relative && longest > 65535) return ep;
    element_pattern_impl::allocate_slots<K>(ep, n_elements, nodes_of);
    // Column v: where[u] is the slot of row u (absolute or past the column's start); each element
    // of v, v its node b, gets its slots (a, b) = entry (nodes[a], v).
    auto fill_slots = [&](auto* out, auto relative) {
      using Slot = std::remove_pointer_t<decltype(out)>;
      std::vector<int>& where = mark;
      for (int v = 0; v < n_nodes; ++v) {
        const int col = outer[size_t(v)];
        for (int k = col; k < outer[size_t(v) + 1]; ++k) where[size_t(inner[k])] = relative() ? k - col : k;
        element_pattern_impl::column_slots<Slot>(in, v, nodes_of, ep.offsets.data(), where.data(), out);
      }
    };
    if constexpr (K == SlotKind::absolute)
      fill_slots(ep.slots.data(), std::false_type{});
    else
      fill_slots(ep.relative_slots.get(), std::true_type{});
    return ep;
  }
}

}  // namespace polydec::detail
