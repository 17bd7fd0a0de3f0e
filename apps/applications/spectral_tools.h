// apps/applications/spectral_tools.h — the everyday spectral shape tools on 0-forms, from k
// eigenpairs (lambda_i, phi_i) of -S x = lambda M x (apps/applications/spectrum.h; M-orthonormal
// phi_i, lambda_0 = 0 with constant phi_0 on a connected mesh):
//   heat kernel signature (Sun, Ovsjanikov, Guibas 2009)
//     HKS(x, t) = sum_i exp(-lambda_i t) phi_i(x)^2,
//     times log-spaced from 4 ln 10 / lambda_max to 4 ln 10 / lambda_1;
//   wave kernel signature (Aubry, Schlickewei, Cremers 2011)
//     WKS(x, e) = sum_i phi_i(x)^2 exp(-(e - ln lambda_i)^2 / (2 s^2)) / sum_i exp(-(e - ln lambda_i)^2 / (2
//     s^2)), i >= 1, energies e log-spaced from ln lambda_1 + 2 s to ln lambda_max - 2 s, s = 7 (ln
//     lambda_max - ln lambda_1) / N;
//   biharmonic distance (Lipman, Rustamov, Funkhouser 2010)
//     d_B(x, y)^2 = sum_{i >= 1} (phi_i(x) - phi_i(y))^2 / lambda_i^2;
//   diffusion distance (Coifman, Lafon 2006) at time t
//     d_t(x, y)^2 = sum_{i >= 1} exp(-2 lambda_i t) (phi_i(x) - phi_i(y))^2;
//   manifold-harmonics low-pass filter (Vallet, Levy 2008): X' = sum_{i < K} phi_i phi_i^T M X.
// The kernel sums are those of the heat kernel with respect to the mass M: with all |V|
// eigenpairs, HKS(x, t) is exactly u_x(t) for the heat flow M u' = S u from u(0) = e_x / M_xx.
// Eigenvalues below 1e-8 lambda_max count as zero (one per connected component) and are left
// out of the sums over i >= 1.
#pragma once

#include <Eigen/Dense>

#include "polydec/apps/applications/spectrum.h"

namespace polydec {

// Log-spaced sample points: n values from lo to hi (n = 1: lo).
Eigen::VectorXd log_spaced(double lo, double hi, int n);

// The standard HKS times for this spectrum: n log-spaced in [4 ln 10 / lambda_max, 4 ln 10 / lambda_1].
Eigen::VectorXd hks_times(const Spectrum& spectrum, int n = 100);
// HKS at the given times, |V| x |times|.
Eigen::MatrixXd heat_kernel_signature(const Spectrum& spectrum, const Eigen::VectorXd& times);

// The WKS energies (log scale) and the Gaussian's width s for n samples.
struct WksSamples {
  Eigen::VectorXd energies;
  double sigma = 0;
};
WksSamples wks_samples(const Spectrum& spectrum, int n = 100);
// WKS at the given log energies with width sigma, |V| x |energies|.
Eigen::MatrixXd wave_kernel_signature(const Spectrum& spectrum, const Eigen::VectorXd& energies,
                                      double sigma);

// Biharmonic distance from vertex `source` to every vertex, with the first `k` eigenpairs
// (k <= spectrum size; 0: all).
Eigen::VectorXd biharmonic_distance(const Spectrum& spectrum, int source, int k = 0);
// Diffusion distance at time t from vertex `source` to every vertex, with the first k eigenpairs.
Eigen::VectorXd diffusion_distance(const Spectrum& spectrum, double t, int source, int k = 0);

// Positions X (|V| x 3) projected onto the first `k` eigenvectors in the M inner product:
// sum_{i<k} phi_i phi_i^T M X, M the mass the spectrum was computed with (its diagonal, lumped).
Eigen::MatrixX3d lowpass_filter(const Spectrum& spectrum, const Eigen::VectorXd& lumped_mass,
                                const Eigen::MatrixX3d& X, int k);

}  // namespace polydec
