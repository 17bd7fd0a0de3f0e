// tests/dec/detail/test_element_pattern.cpp — the shared element pattern: its pattern against one
// built from triplets, every slot at entry (nodes[a], nodes[b]), absolute and column-relative
// slots and both column orders agreeing, unsorted elements, unused nodes, the uint16 fallback.
#include <catch2/catch.hpp>
#include <numeric>
#include <random>
#include <vector>

#include "polydec/dec/detail/element_pattern.h"

using namespace polydec;
using polydec::detail::element_pattern;
using polydec::detail::ElementPattern;
using polydec::detail::ColumnOrder;
using polydec::detail::SlotKind;

namespace test_element_pattern {
namespace {

using Elements = std::vector<std::vector<int>>;

// The pattern of all node pairs of each element, from triplets (values zero).
Eigen::SparseMatrix<double> triplet_pattern(int n_nodes, const Elements& elements) {
  std::vector<Eigen::Triplet<double>> t;
  for (const auto& e : elements)
    for (int u : e)
      for (int v : e) t.emplace_back(u, v, 1.0);
  Eigen::SparseMatrix<double> A(n_nodes, n_nodes);
  A.setFromTriplets(t.begin(), t.end());
  A.coeffs().setZero();
  return A;
}

bool same_structure(const Eigen::SparseMatrix<double>& A, const Eigen::SparseMatrix<double>& B) {
  return A.rows() == B.rows() && A.cols() == B.cols() && A.nonZeros() == B.nonZeros() && A.isCompressed() &&
         B.isCompressed() && std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1, B.outerIndexPtr()) &&
         std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), B.innerIndexPtr());
}

template <SlotKind K, ColumnOrder O = ColumnOrder::transpose>
ElementPattern build(int n_nodes, const Elements& elements) {
  return element_pattern<K, O>(n_nodes, int(elements.size()),
                               [&](int e) -> const std::vector<int>& { return elements[size_t(e)]; });
}

// Checks everything the header promises for one input, for both column orders.
template <ColumnOrder O>
void check_order(int n_nodes, const Elements& elements) {
  const auto ref = triplet_pattern(n_nodes, elements);
  const ElementPattern none = build<SlotKind::none, O>(n_nodes, elements);
  const ElementPattern abs = build<SlotKind::absolute, O>(n_nodes, elements);
  const ElementPattern rel = build<SlotKind::column_relative, O>(n_nodes, elements);
  for (const ElementPattern* p : {&none, &abs, &rel}) {
    REQUIRE(same_structure(p->pattern, ref));
    REQUIRE(p->pattern.coeffs().isZero(0.0));
  }
  CHECK(none.offsets.empty());
  CHECK(none.slots.empty());
  CHECK(none.relative_slots == nullptr);
  CHECK(abs.relative_slots == nullptr);
  CHECK(rel.slots.empty());
  REQUIRE(rel.relative_slots != nullptr);
  REQUIRE(abs.offsets == rel.offsets);
  REQUIRE(abs.offsets.size() == elements.size() + 1);
  REQUIRE(abs.slots.size() == size_t(abs.offsets.back()));
  const int* outer = ref.outerIndexPtr();
  const int* inner = ref.innerIndexPtr();
  for (size_t e = 0; e < elements.size(); ++e) {
    const auto& nodes = elements[e];
    const long m = long(nodes.size());
    REQUIRE(abs.offsets[e + 1] - abs.offsets[e] == m * m);
    for (long a = 0; a < m; ++a)
      for (long b = 0; b < m; ++b) {
        const long i = abs.offsets[e] + a * m + b;
        const int s = abs.slots[size_t(i)];
        // Slot (a, b): row nodes[a] of column nodes[b].
        REQUIRE(s >= outer[nodes[size_t(b)]]);
        REQUIRE(s < outer[nodes[size_t(b)] + 1]);
        REQUIRE(inner[s] == nodes[size_t(a)]);
        REQUIRE(outer[nodes[size_t(b)]] + int(rel.relative_slots[size_t(i)]) == s);
      }
  }
}

void check(int n_nodes, const Elements& elements) {
  check_order<ColumnOrder::transpose>(n_nodes, elements);
  check_order<ColumnOrder::sort>(n_nodes, elements);
  // Both orders give the same slots.
  REQUIRE(build<SlotKind::absolute>(n_nodes, elements).slots ==
          build<SlotKind::absolute, ColumnOrder::sort>(n_nodes, elements).slots);
}

// Random elements of 0..max_size distinct nodes in random order; nodes >= n_used never occur.
Elements random_elements(std::mt19937& rng, int n_used, int n_elements, int max_size) {
  Elements elements(static_cast<size_t>(n_elements));
  std::vector<int> ids(static_cast<size_t>(n_used));
  std::iota(ids.begin(), ids.end(), 0);
  std::uniform_int_distribution<int> size(0, max_size);
  for (auto& e : elements) {
    std::shuffle(ids.begin(), ids.end(), rng);
    e.assign(ids.begin(), ids.begin() + std::min(n_used, size(rng)));
  }
  return elements;
}

}  // namespace

TEST_CASE("element_pattern: pattern and slots on small hand-made elements", "[element-pattern]") {
  // Unsorted nodes, a node (3) in no element, the last node (6) in no element, sizes 1 to 4.
  const Elements elements = {{5, 0, 2}, {2, 4, 1, 0}, {4}, {1, 5}};
  check(7, elements);
  const ElementPattern abs = build<SlotKind::absolute>(7, elements);
  const auto& P = abs.pattern;
  CHECK(P.col(3).nonZeros() == 0);
  CHECK(P.col(6).nonZeros() == 0);
  CHECK(P.nonZeros() == 23);  // columns 0..5: {0,1,2,4,5} three times, none, {0,1,2,4}, {0,1,2,5}
  // Element 0 = (5, 0, 2): slot (0, 1) is row 5 of column 0, the last of {0, 1, 2, 4, 5}.
  CHECK(abs.slots[1] == P.outerIndexPtr()[0] + 4);
}

TEST_CASE("element_pattern: random elements of every unrolled and general size", "[element-pattern]") {
  std::mt19937 rng(7);
  for (int max_size : {3, 4, 6, 8, 11, 30}) {  // 30: columns over 32 rows (std::sort)
    const int n_nodes = 40;
    check(n_nodes, random_elements(rng, 35, 60, max_size));  // nodes 35..39 unused
  }
  // Fixed sizes only (the unrolled paths alone).
  for (int m : {3, 4, 6, 8}) {
    Elements elements = random_elements(rng, 30, 50, 30);
    for (auto& e : elements) {
      std::vector<int> ids(30);
      std::iota(ids.begin(), ids.end(), 0);
      std::shuffle(ids.begin(), ids.end(), rng);
      e.assign(ids.begin(), ids.begin() + m);
    }
    check(30, elements);
  }
  check(0, {});
  check(5, {});
}

TEST_CASE("element_pattern: columns over 65535 entries fall back to no column-relative slots", "[element-pattern]") {
  // Node 0 shares an element with each of 70000 others: its column has 70001 entries.
  const int n = 70001;
  Elements elements;
  for (int i = 1; i < n; ++i) elements.push_back({i, 0});
  const ElementPattern rel = build<SlotKind::column_relative>(n, elements);
  CHECK(rel.relative_slots == nullptr);
  CHECK(rel.offsets.empty());
  const ElementPattern sorted = build<SlotKind::column_relative, ColumnOrder::sort>(n, elements);
  CHECK(sorted.relative_slots == nullptr);
  REQUIRE(same_structure(sorted.pattern, rel.pattern));
  CHECK(rel.pattern.col(0).nonZeros() == n);
  REQUIRE(same_structure(rel.pattern, triplet_pattern(n, elements)));
  const ElementPattern abs = build<SlotKind::absolute>(n, elements);  // absolute slots have no limit
  REQUIRE(abs.slots.size() == size_t(4 * (n - 1)));
  const int* inner = abs.pattern.innerIndexPtr();
  for (int e = 0; e < n - 1; ++e) {
    CHECK(inner[abs.slots[size_t(4 * e + 1)]] == e + 1);  // (a, b) = (0, 1): row e + 1 of column 0
    CHECK(abs.slots[size_t(4 * e + 1)] == e + 1);
  }
  // Just under the limit: 65535 entries in column 0 keep their relative slots.
  elements.resize(65534);
  const ElementPattern at_limit = build<SlotKind::column_relative>(65535, elements);
  CHECK(at_limit.pattern.col(0).nonZeros() == 65535);
  CHECK(at_limit.relative_slots != nullptr);
}

}  // namespace test_element_pattern
