// apps/applications/hodge_parts.cpp — the parts and norms of a Hodge decomposition.
#include "polydec/apps/applications/hodge_parts.h"

#include <algorithm>
#include <cmath>

namespace polydec {

HodgeParts hodge_parts(const Eigen::VectorXd& omega, Eigen::VectorXd potential,
                       const Eigen::SparseMatrix<double>& d0, const Eigen::SparseMatrix<double>& star1,
                       const Eigen::MatrixXd& H) {
  HodgeParts p;
  p.potential = std::move(potential);
  p.exact = d0 * p.potential;
  // H^T star1 d0 = 0, so projecting omega or omega - exact onto H is the same.
  p.harmonic = H * (H.transpose() * (star1 * omega));
  p.coexact = omega - p.exact - p.harmonic;
  auto norm = [&](const Eigen::VectorXd& x) { return std::sqrt(std::max(0.0, x.dot(star1 * x))); };
  p.norm = norm(omega);
  p.norm_exact = norm(p.exact);
  p.norm_coexact = norm(p.coexact);
  p.norm_harmonic = norm(p.harmonic);
  return p;
}

}  // namespace polydec
