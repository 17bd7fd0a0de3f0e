// dec/detail/drop_zeros.h — removing the stored entries of a sparse matrix that are exactly zero,
// the others kept bit for bit.
#pragma once

#include <Eigen/Sparse>
#include <algorithm>

namespace polydec::detail {

// Drops every stored entry equal to 0 (either sign); the matrix ends compressed. A compressed
// matrix without zeros is only scanned (one vectorizable pass over the values, no rewrite).
template <class Sparse>
void drop_exact_zeros(Sparse& A) {
  using Scalar = typename Sparse::Scalar;
  if (A.isCompressed() &&
      std::none_of(A.valuePtr(), A.valuePtr() + A.nonZeros(), [](const Scalar& v) { return v == Scalar(0); }))
    return;
  A.prune([](Eigen::Index, Eigen::Index, const Scalar& v) { return v != Scalar(0); });
}

}  // namespace polydec::detail
