// apps/applications/quadratic.h — applications of the quadratic polygon Laplacian
// (operators/surface/quadratic.h; beyond the paper, docs/extensions.md): its operator set for the
// solvers that read S, M and the lumped M only (Dirichlet Poisson, spectra), the Franke Poisson
// problem with L2 and H1 errors of the whole quadratic function, and the convergence study of
// Figure 9 with order 2 elements.
#pragma once

#include <string>
#include <vector>

#include "polydec/apps/applications/spectrum.h"
#include "polydec/operators/surface/quadratic.h"

namespace polydec {

// The quadratic S, M, HRZ-lumped M, and G, D (quadratic_gradient: per fan triangle at its
// centroid) as an OperatorSet named "quadratic" (domain: `mesh`; n_input_vertices = |V|, the first
// |V| dofs being the vertices). Its matrices act on the |V| + |E| dofs, so only applications that
// read these matrices alone take it: solve_dirichlet_poisson (apps/applications/poisson.h) and
// laplacian_spectrum (heat geodesics with G and D measure far worse than order 1: docs/extensions.md).
OperatorSet quadratic_operator_set(const Mesh& mesh, const Refinement& refinement);
OperatorSet quadratic_operator_set(const Mesh& mesh, const RefinementOptions& options = {});

// Eigenpairs of -S x = lambda M x with the quadratic operators (eigenvectors: one row per dof).
Spectrum quadratic_spectrum(const Mesh& mesh, const SpectrumOptions& options = {});

struct QuadraticPoissonError {
  double h = 0;         // mean edge length
  double l2_error = 0;  // || u - u_h ||_L2 over the fan triangles (7-point degree-5 rule per triangle)
  double h1_error = 0;  // || grad u - grad u_h ||_L2, the same way
  int n_dofs = 0;       // |V| + |E|
};

// The Franke problem (apps/applications/poisson.h) on a planar mesh of the unit square with the
// quadratic operators: S u = M b at the free dofs (Galerkin mass, b = Laplace(f) at the dofs),
// u = f at the boundary vertices and boundary-edge midpoints; the errors compare the prolonged
// piecewise quadratic function with f and its gradient on every fan triangle.
QuadraticPoissonError franke_poisson_quadratic(const Mesh& mesh);

struct QuadraticConvergenceSeries {
  std::string family;  // "triangles", "quads", "hexagons", "non-convex"
  std::vector<int> resolutions;
  std::vector<QuadraticPoissonError> errors;
  double l2_slope = 0, h1_slope = 0;  // least-squares slopes against h (loglog_slope)
};

// The study of Figure 9 with quadratic elements on triangle_grid, quad_grid, hex_grid and
// chevron_grid (non-convex hexagons) with n x n cells for every n in `resolutions` (two or more).
std::vector<QuadraticConvergenceSeries> franke_convergence_quadratic(const std::vector<int>& resolutions);

}  // namespace polydec
