// apps/applications/harmonics.cpp — spherical-harmonics reproduction error (eq. 30).
#include "polydec/apps/applications/harmonics.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "polydec/apps/applications/curvature.h"
#include "polydec/operators/solvers/cholesky.h"

namespace polydec {

double associated_legendre(int l, int m, double x) {
  if (m < 0 || m > l) throw std::invalid_argument("associated_legendre: need 0 <= m <= l");
  // P_m^m = (-1)^m (2m-1)!! (1-x^2)^(m/2), then the three-term recurrence in l.
  const double s = std::sqrt(std::max(0.0, (1.0 - x) * (1.0 + x)));
  double pmm = 1.0;
  for (int i = 1; i <= m; ++i) pmm *= -(2.0 * i - 1.0) * s;
  if (l == m) return pmm;
  double pm1 = x * (2.0 * m + 1.0) * pmm;
  for (int ll = m + 2; ll <= l; ++ll) {
    const double p = ((2.0 * ll - 1.0) * x * pm1 - (ll + m - 1.0) * pmm) / (ll - m);
    pmm = pm1;
    pm1 = p;
  }
  return pm1;
}

double spherical_harmonic(const Eigen::Vector3d& p, int l, int m) {
  const double r = p.norm();
  const double cos_theta = std::clamp(p.y() / r, -1.0, 1.0);
  const double phi = std::atan2(p.x(), p.z()) + std::numbers::pi;
  const int am = std::abs(m);
  // K(l, m) = sqrt((2l+1)/(4 pi) * (l-m)!/(l+m)!)
  double ratio = 1.0;
  for (int i = l - am + 1; i <= l + am; ++i) ratio /= i;
  const double K = std::sqrt((2.0 * l + 1.0) / (4.0 * std::numbers::pi) * ratio);
  const double P = associated_legendre(l, am, cos_theta);
  if (m == 0) return K * P;
  if (m > 0) return std::sqrt(2.0) * K * std::cos(m * phi) * P;
  return std::sqrt(2.0) * K * std::sin(am * phi) * P;
}

double HarmonicsError::sum(int max_l) const {
  if (max_l < 0 || max_l > int(band_error.size()))
    throw std::out_of_range("HarmonicsError::sum: band not evaluated");
  double s = 0;
  for (int l = 1; l <= max_l; ++l) s += band_error[l - 1];
  return s;
}

HarmonicsError spherical_harmonics_error(const OperatorSet& ops, const HarmonicsOptions& options) {
  if (options.max_band < 1) throw std::invalid_argument("spherical harmonics: max_band must be >= 1");
  if (!options.lumped_mass && ops.M.size() == 0)
    throw std::invalid_argument("spherical harmonics: Laplacian '" + ops.name + "' defines no unlumped mass");
  const Mesh& mesh = ops.domain;
  const int nv = mesh.n_vertices();
  std::unique_ptr<SparseCholesky> Minv;
  if (!options.lumped_mass)
    Minv = std::make_unique<SparseCholesky>(mass_with_unit_rows_for_unreferenced(ops), "mass matrix M");
  for (int v = 0; v < nv; ++v)
    if (ops.M_lumped[v] > 0 && !(mesh.position(v).norm() > 0))
      throw std::invalid_argument(
          fmt::format("spherical harmonics: vertex {} lies at the origin (no direction)", v));
  // L y = M^-1 S y; vertices without mass (no face) have no Laplacian: their entries are 0.
  auto apply_L = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
    const Eigen::VectorXd Sy = ops.S * y;
    if (Minv) return Minv->solve(Sy);
    Eigen::VectorXd Ly = Eigen::VectorXd::Zero(nv);
    for (int v = 0; v < nv; ++v)
      if (ops.M_lumped[v] > 0) Ly[v] = Sy[v] / ops.M_lumped[v];
    return Ly;
  };
  auto M_times = [&](const Eigen::VectorXd& r) -> Eigen::VectorXd {
    return Minv ? Eigen::VectorXd(ops.M * r) : Eigen::VectorXd(ops.M_lumped.cwiseProduct(r));
  };

  HarmonicsError err;
  err.vertex_error = Eigen::VectorXd::Zero(nv);
  Eigen::VectorXd y(nv);
  for (int l = 1; l <= options.max_band; ++l) {
    double band = 0;
    const double eig = -double(l) * (l + 1);
    for (int m = -l; m <= l; ++m) {
      for (int v = 0; v < nv; ++v) y[v] = spherical_harmonic(mesh.position(v), l, m);
      y.normalize();
      const Eigen::VectorXd r = y - apply_L(y) / eig;
      const Eigen::VectorXd share = r.cwiseProduct(M_times(r));
      err.vertex_error += share;
      band += share.sum();
    }
    err.band_error.push_back(band);
  }
  return err;
}

HarmonicsError spherical_harmonics_error(const Mesh& mesh, const HarmonicsOptions& options) {
  return spherical_harmonics_error(build_operators(mesh, parse_laplacian("ours"), false), options);
}

}  // namespace polydec
