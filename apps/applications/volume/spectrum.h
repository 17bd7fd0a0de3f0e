// apps/applications/volume/spectrum.h — eigenvalues of the volume Laplacian (-S x = lambda M x) and the
// analytic spectrum of the unit ball: spherical Bessel functions j_l, their zeros and the zeros of
// their derivatives.
//
// Unit ball, -Delta u = lambda u: separation u = j_l(sqrt(lambda) r) Y_lm gives
//   Dirichlet (u = 0 on the sphere): lambda = j_{l,n}^2, j_{l,n} the n-th positive zero of j_l;
//   Neumann (du/dr = 0):             lambda = j'_{l,n}^2, j'_{l,n} the n-th positive zero of j_l',
//                                    plus lambda = 0 (the constants);
// each with multiplicity 2l + 1 (m = -l..l).
#pragma once

#include <vector>

#include "polydec/apps/applications/spectrum.h"
#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec {

// j_l(x) for l >= 0, x > 0, by Miller's downward recurrence j_{l-1} = (2l+1)/x j_l - j_{l+1},
// normalized by j_0 = sin x / x or j_1 = sin x / x^2 - cos x / x (whichever is larger).
double spherical_bessel_j(int l, double x);
// j_l'(x) = j_{l-1}(x) - (l+1)/x j_l(x) (l >= 1), j_0' = -j_1.
double spherical_bessel_j_derivative(int l, double x);

// The first `count` positive zeros of j_l (derivative = false) or of j_l' (derivative = true),
// ascending, by a scan for sign changes (step 0.05, far below the zeros' spacing of about pi)
// and bisection to machine precision.
std::vector<double> spherical_bessel_zeros(int l, int count, bool derivative = false);

struct BallEigenvalue {
  double lambda = 0;
  int l = 0, n = 0;  // j_{l,n} (n from 1); Neumann's 0 has l = 0, n = 0
};
// The `count` smallest eigenvalues of -Delta on the unit ball, each repeated 2l + 1 times, ascending.
std::vector<BallEigenvalue> ball_eigenvalues(int count, bool dirichlet);

// The k smallest eigenpairs of -S x = lambda M x of the volume Laplacian: Neumann (every vertex)
// or Dirichlet (the boundary vertices removed; their rows in the eigenvectors are 0), through
// laplacian_spectrum (apps/applications/spectrum.h).
Spectrum volume_laplacian_spectrum(const VolumeMesh& mesh, bool dirichlet,
                                   const SpectrumOptions& options = {});
// The same with any volume operator set of `mesh` (operators/registry/volume_laplacians.h).
Spectrum volume_laplacian_spectrum(const OperatorSet& operators, const VolumeMesh& mesh, bool dirichlet,
                                   const SpectrumOptions& options = {});

struct BallSpectrum {
  int n = 0;  // hex_ball_volume(n)
  bool dirichlet = false;
  int n_vertices = 0, n_cells = 0;
  double h = 0;                          // mean edge length
  std::vector<double> eigenvalues;       // discrete, ascending
  std::vector<BallEigenvalue> analytic;  // the analytic ones, same order
  std::vector<double> relative_error;    // |lambda_h - lambda| / lambda (absolute for lambda = 0)
  std::string method;
};

// The k smallest eigenvalues on hex_ball_volume(n) against the unit ball's (2k + 10 pairs are
// computed and the k smallest kept, so that no copy of a repeated eigenvalue is missed).
BallSpectrum ball_spectrum(int n, int k, bool dirichlet, bool lumped_mass = false);

}  // namespace polydec
