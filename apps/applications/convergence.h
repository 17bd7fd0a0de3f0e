// apps/applications/convergence.h — the order of convergence of a refinement study: the
// least-squares slope of log(error) against log(h).
#pragma once

#include <vector>

namespace polydec {

// Least-squares slope of log(y) against log(x) over the points with x, y > 0 (the convergence
// order when x is the mesh size); NaN with fewer than two such points or no spread in x.
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace polydec
