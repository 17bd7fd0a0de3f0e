// apps/applications/volume/spectrum.h — eigenvalues of the volume Laplacian (-S x = lambda M x) and the
// analytic spectrum of the unit ball: spherical Bessel functions j_l, their zeros and the zeros of
// their derivatives.
//
// Unit ball, -Delta u = lambda u: separation u = j_l(sqrt(lambda) r) Y_lm gives
//   Dirichlet (u = 0 on the sphere): lambda = j_{l,n}^2, j_{l,n} the n-th positive zero of j_l;
//   Neumann (du/dr = 0):             lambda = j'_{l,n}^2, j'_{l,n} the n-th positive zero of j_l',
//                                    plus lambda = 0 (the constants);
// each with multiplicity 2l + 1 (m = -l..l).
// Also the Hodge Laplacian spectra of 1-, 2- and 3-forms of a polyhedral mesh (volume_form_spectrum).
#pragma once

#include <vector>

#include "polydec/apps/applications/form_spectrum.h"
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

// The options.k smallest eigenpairs of the Hodge Laplacian on Whitney k-forms of a polyhedral mesh,
// k = options.degree (1, 2 or 3), from its DEC bundle (volume_dec, dec/volume/hodge_star.h):
//   K x = lambda star_k x,  K = star_k d_{k-1} M^-1 d_{k-1}^T star_k + d_k^T star_{k+1} d_k
// (no second term for k = 3), M = star_{k-1}, for k = 1 the lumped star0 (row sums; the default,
// options.lumped_mass) or star0 itself. Natural boundary conditions (no cochain is constrained):
// the zero eigenvalues count the Betti number b_k (b_1 = 0 on a ball, 1 on a solid torus;
// b_2 = b_3 = 0 for both), and d_{k-1} maps the eigenforms of degree k - 1 with lambda != 0 to
// eigenforms of degree k with the same lambda (with the lumped or Galerkin mass, the 0-form
// spectrum -S u = lambda M u of operators/volume/laplacian.h).
// options.complex: the mesh's own edges, faces and cells (dec/volume/mesh_complex.h; positive
// definite stars, cells of any size) or the complete complex (on the reduced bases of
// volume_form_span, dense: small meshes; degree k needs DEC up to min(k + 1, 3), which
// volume_dec refuses for large cells). Solved as form_spectrum (the same mixed shift-invert
// system, apps/applications/form_spectrum.h) with sigma = -shift_factor / V^(2/3), V the volume.
// Eigenvectors: star_k-orthonormal cochains on the k-cells (the mesh's, or the complete complex's
// pairs, triples, quadruples). Hodge parts (options.decompose): for lambda != 0 the exact part
// d_{k-1} M^-1 d_{k-1}^T star_k x / lambda, the co-exact part star_k^-1 d_k^T star_{k+1} d_k x /
// lambda and the harmonic part the rest (round-off); for lambda below 1e-8 / V^(2/3) the whole
// form is harmonic. options.refinement (a surface option) is not used; quality stays empty.
// std::invalid_argument for a degree outside 1..3 or k outside [1, rank); SolverError as
// form_spectrum; InvalidMeshError for a mesh without cells.
FormSpectrum volume_form_spectrum(const VolumeMesh& mesh, const FormSpectrumOptions& options = {});

}  // namespace polydec
