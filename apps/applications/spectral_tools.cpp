// apps/applications/spectral_tools.cpp — HKS, WKS, biharmonic and diffusion distances, low-pass filter.
#include "polydec/apps/applications/spectral_tools.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace polydec {
namespace spectral_tools_detail {
namespace {

// Index of the first eigenvalue above the zero threshold (1e-8 lambda_max).
int first_nonzero(const Spectrum& sp) {
  const Eigen::Index n = sp.eigenvalues.size();
  if (n == 0) throw std::invalid_argument("spectral tools: empty spectrum");
  const double zero = 1e-8 * std::abs(sp.eigenvalues[n - 1]);
  int i = 0;
  while (i < n && sp.eigenvalues[i] <= zero) ++i;
  if (i == n) throw std::invalid_argument("spectral tools: the spectrum has no nonzero eigenvalue");
  return i;
}

int check_k(const Spectrum& sp, int k) {
  const int n = int(sp.eigenvalues.size());
  if (k == 0) return n;
  if (k < 1 || k > n)
    throw std::invalid_argument(fmt::format("spectral tools: k = {} must lie in [1, {}]", k, n));
  return k;
}

void check_source(const Spectrum& sp, int source) {
  if (source < 0 || source >= sp.eigenvectors.rows())
    throw std::invalid_argument(
        fmt::format("spectral tools: vertex {} out of range [0, {})", source, sp.eigenvectors.rows()));
}

}  // namespace
}  // namespace spectral_tools_detail

Eigen::VectorXd log_spaced(double lo, double hi, int n) {
  if (n < 1 || !(lo > 0) || !(hi > 0))
    throw std::invalid_argument("log_spaced: n >= 1 and positive bounds required");
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i)
    v[i] = n == 1 ? lo : std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * i / (n - 1));
  return v;
}

Eigen::VectorXd hks_times(const Spectrum& sp, int n) {
  const int i1 = spectral_tools_detail::first_nonzero(sp);
  const double lmax = sp.eigenvalues[sp.eigenvalues.size() - 1], l1 = sp.eigenvalues[i1];
  return log_spaced(4 * std::log(10.0) / lmax, 4 * std::log(10.0) / l1, n);
}

Eigen::MatrixXd heat_kernel_signature(const Spectrum& sp, const Eigen::VectorXd& times) {
  const Eigen::MatrixXd P2 = sp.eigenvectors.cwiseAbs2();
  Eigen::MatrixXd E(sp.eigenvalues.size(), times.size());
  for (Eigen::Index j = 0; j < times.size(); ++j)
    E.col(j) = (-sp.eigenvalues.array().max(0.0) * times[j]).exp().matrix();
  return P2 * E;
}

WksSamples wks_samples(const Spectrum& sp, int n) {
  const int i1 = spectral_tools_detail::first_nonzero(sp);
  const double lo = std::log(sp.eigenvalues[i1]), hi = std::log(sp.eigenvalues[sp.eigenvalues.size() - 1]);
  if (n < 1) throw std::invalid_argument("wks_samples: n >= 1 required");
  WksSamples w;
  w.sigma = 7 * (hi - lo) / n;
  if (!(w.sigma > 0))
    throw std::invalid_argument("wks_samples: the spectrum needs two distinct nonzero eigenvalues");
  const double a = lo + 2 * w.sigma, b = hi - 2 * w.sigma;
  w.energies.resize(n);
  for (int i = 0; i < n; ++i) w.energies[i] = n == 1 ? 0.5 * (a + b) : a + (b - a) * i / (n - 1);
  return w;
}

Eigen::MatrixXd wave_kernel_signature(const Spectrum& sp, const Eigen::VectorXd& energies, double sigma) {
  const int i1 = spectral_tools_detail::first_nonzero(sp);
  const int m = int(sp.eigenvalues.size()) - i1;
  const Eigen::ArrayXd loglam = sp.eigenvalues.tail(m).array().log();
  Eigen::MatrixXd G(m, energies.size());
  for (Eigen::Index j = 0; j < energies.size(); ++j) {
    const Eigen::ArrayXd g = (-(energies[j] - loglam).square() / (2 * sigma * sigma)).exp();
    const double sum = g.sum();
    G.col(j) = sum > 0 ? Eigen::VectorXd(g / sum) : Eigen::VectorXd::Zero(m);
  }
  return sp.eigenvectors.rightCols(m).cwiseAbs2() * G;
}

namespace spectral_tools_detail {
namespace {
// sqrt(sum_{i1 <= i < k} w_i (phi_i(x) - phi_i(source))^2) for every x.
Eigen::VectorXd weighted_distance(const Spectrum& sp, int source, int k, const Eigen::VectorXd& weights) {
  const int i1 = first_nonzero(sp);
  Eigen::VectorXd d2 = Eigen::VectorXd::Zero(sp.eigenvectors.rows());
  for (int i = i1; i < k; ++i) {
    const Eigen::ArrayXd diff = sp.eigenvectors.col(i).array() - sp.eigenvectors(source, i);
    d2.array() += weights[i] * diff.square();
  }
  return d2.cwiseSqrt();
}
}  // namespace
}  // namespace spectral_tools_detail

Eigen::VectorXd biharmonic_distance(const Spectrum& sp, int source, int k) {
  using namespace spectral_tools_detail;
  check_source(sp, source);
  k = check_k(sp, k);
  return weighted_distance(sp, source, k, sp.eigenvalues.cwiseAbs2().cwiseInverse());
}

Eigen::VectorXd diffusion_distance(const Spectrum& sp, double t, int source, int k) {
  using namespace spectral_tools_detail;
  check_source(sp, source);
  k = check_k(sp, k);
  if (!(t > 0)) throw std::invalid_argument("diffusion_distance: t must be positive");
  return weighted_distance(sp, source, k, (-2 * t * sp.eigenvalues.array()).exp().matrix());
}

Eigen::MatrixX3d lowpass_filter(const Spectrum& sp, const Eigen::VectorXd& lumped_mass,
                                const Eigen::MatrixX3d& X, int k) {
  k = spectral_tools_detail::check_k(sp, k);
  if (lumped_mass.size() != X.rows() || X.rows() != sp.eigenvectors.rows())
    throw std::invalid_argument("lowpass_filter: mass, positions and eigenvectors must have |V| rows");
  const Eigen::MatrixXd U = sp.eigenvectors.leftCols(k);
  const Eigen::MatrixXd coeff = U.transpose() * (lumped_mass.asDiagonal() * X);
  return U * coeff;
}

}  // namespace polydec
