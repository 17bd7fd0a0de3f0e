// dec/detail/union_find.h — root lookup with path halving for the union-finds of the library: over
// vertices (mesh validation, diagnostics, repairs) and over faces (form_span's spanning forest).
#pragma once

#include <vector>

namespace polydec {

// Root of x in the forest `parent` (parent[r] == r for a root), halving the path on the way.
inline int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

}  // namespace polydec
