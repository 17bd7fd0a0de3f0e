// apps/applications/convergence.cpp — least-squares slope in log-log coordinates.
#include "polydec/apps/applications/convergence.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace polydec {

double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    if (!(x[i] > 0 && y[i] > 0 && std::isfinite(x[i]) && std::isfinite(y[i]))) continue;
    const double a = std::log(x[i]), b = std::log(y[i]);
    n += 1;
    sx += a;
    sy += b;
    sxx += a * a;
    sxy += a * b;
  }
  const double den = n * sxx - sx * sx;
  if (n < 2 || !(den > 1e-12 * std::max(1.0, n * sxx))) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / den;
}

}  // namespace polydec
