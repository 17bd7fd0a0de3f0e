// dec/detail/scale.h — power-of-two normalization of an element's coordinates, so that kernels
// forming high powers of lengths (squared volumes, cubes of 3x3 Gram determinants) hold at every
// scale double precision represents. Scaling by 2^-e is exact, so a kernel run on scaled
// coordinates returns the unscaled result times a power of 2^e, bit for bit.
#pragma once

#include <algorithm>
#include <cmath>

namespace polydec::detail {

// Extents within 2^-64 .. 2^64 are ordinary: the kernels' twelfth powers of lengths stay within
// 2^+-768, far from overflow and from subnormal numbers, so they run unscaled.
inline constexpr double kOrdinaryHigh = 0x1p64, kOrdinaryLow = 0x1p-64;

// The exponent e that brings an element of this extent (a length) to [1, 2) by 2^-e, or 0 when
// the extent is ordinary (or zero, or not finite: then nothing is gained by scaling). |e| <= 1022,
// so that 2^e and 2^-e are normal doubles.
inline int normalizing_exponent(double extent) {
  if (extent < kOrdinaryHigh && extent > kOrdinaryLow) return 0;
  if (!(extent > 0) || !std::isfinite(extent)) return 0;
  return std::clamp(std::ilogb(extent), -1022, 1022);
}

// The largest magnitude of n doubles.
inline double max_abs(const double* x, int n) {
  double m = 0;
  for (int k = 0; k < n; ++k) m = std::fmax(m, std::fabs(x[k]));
  return m;
}

}  // namespace polydec::detail
