// apps/applications/harmonics.h — how well the spherical harmonics are eigenfunctions of the discrete
// Laplacian (paper section 5.4, eq. 30, Table 3).
//
// For every band l and order m, Y_l^m is sampled at the mesh vertices (which should lie on the
// unit sphere), the sample vector y is normalized to unit Euclidean length, and the error
//   e_lm = || y + L y / (l (l + 1)) ||_M^2,   L = M^-1 S,
// is measured in the M-norm (the same M, lumped by default, in L and in the norm). The paper's
// Table 3 sums e_lm over l = 1..8 (as the authors' program runs it; the caption says 1..9).
#pragma once

#include <vector>

#include "polydec/operators/registry/laplacians.h"

namespace polydec {

// Real spherical harmonic Y_l^m at direction p (any length > 0), with the Condon-Shortley phase
// in P_l^m and the y axis as the polar axis: theta = acos(y/|p|), phi = atan2(x, z) + pi;
// m = 0: K(l,0) P_l^0(cos theta); m > 0: sqrt(2) K(l,m) cos(m phi) P_l^m(cos theta);
// m < 0: sqrt(2) K(l,|m|) sin(|m| phi) P_l^|m|(cos theta); K(l,m) = sqrt((2l+1)(l-m)!/(4 pi (l+m)!)).
double spherical_harmonic(const Eigen::Vector3d& p, int l, int m);

// Associated Legendre function P_l^m(x), 0 <= m <= l, with the Condon-Shortley phase (-1)^m.
double associated_legendre(int l, int m, double x);

struct HarmonicsOptions {
  int max_band = 9;         // bands l = 1..max_band are evaluated
  bool lumped_mass = true;  // lumped (default) or Galerkin mass, in L and in the norm
};

struct HarmonicsError {
  std::vector<double> band_error;  // band_error[l-1] = sum over m of e_lm
  // Where the error sits: vertex v's share r_v (M r)_v summed over all evaluated l, m (r the
  // residual of eq. 30), so that vertex_error.sum() == sum(max_band).
  Eigen::VectorXd vertex_error;
  // Sum of the band errors for l = 1..max_l (max_l <= the evaluated max_band).
  double sum(int max_l) const;
};

// Eq. (30) summed per band, on the operator set's domain. Throws SolverError when the Galerkin
// mass cannot be factored, std::invalid_argument for max_band < 1 or a missing mass.
HarmonicsError spherical_harmonics_error(const OperatorSet& operators, const HarmonicsOptions& options = {});
// With the paper's operator ("ours").
HarmonicsError spherical_harmonics_error(const Mesh& mesh, const HarmonicsOptions& options = {});

}  // namespace polydec
