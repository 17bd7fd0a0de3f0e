// apps/applications/poisson.h — Poisson problems with Dirichlet boundary values, and the convergence study of
// the paper's section 5.8 (Figure 9): Delta f = b on the unit square for the Franke test
// function, on regular triangle, quad and hexagon meshes of increasing resolution.
//
// Discretization: L f = b with L = M^-1 S, i.e. S f = M b at the interior vertices, f = f* at
// the boundary vertices. The error is the L2 error in the M-norm, sqrt((f - f*)^T M (f - f*)),
// with f* the exact solution sampled at the vertices; the mesh size h is the mean edge length.
#pragma once

#include <string>
#include <vector>

#include "polydec/operators/registry/laplacians.h"

namespace polydec {

// Franke's test function (Franke 1979) and its exact Laplacian f_xx + f_yy.
double franke(double x, double y);
double franke_laplacian(double x, double y);
// Its gradient (f_x, f_y), for H1 errors.
Eigen::Vector2d franke_gradient(double x, double y);

// The Dirichlet Poisson system: A = -S restricted to the free vertices (not in `fixed`, with
// positive lumped mass; symmetric positive definite when some vertex is fixed on every
// component), and each vertex's row in it (-1 for the others). Throws std::out_of_range for a
// fixed index outside the mesh.
struct PoissonBlock {
  SparseMatrix A;
  std::vector<int> index;
};
PoissonBlock poisson_free_block(const OperatorSet& operators, const std::vector<int>& fixed);

// Solves S f = M b at the vertices that are not fixed, with f = values at the fixed vertices
// (`fixed` lists vertex indices of the operator set's domain, `values` has one entry per vertex
// and is read at the fixed ones). `b` holds the right-hand side per vertex. Every connected
// component needs a fixed vertex (SolverError otherwise).
Eigen::VectorXd solve_dirichlet_poisson(const OperatorSet& operators, const Eigen::VectorXd& b,
                                        const std::vector<int>& fixed, const Eigen::VectorXd& values,
                                        bool lumped_mass = true);

struct PoissonError {
  double h = 0;         // mean edge length
  double l2_error = 0;  // M-norm of f - f*
  int n_vertices = 0;
  Eigen::VectorXd solution, exact;
};

// The Franke problem on a planar mesh of the unit square (positions' x, y used): Dirichlet
// values at the mesh's boundary vertices.
PoissonError franke_poisson(const OperatorSet& operators, bool lumped_mass = true);
PoissonError franke_poisson(const Mesh& mesh, bool lumped_mass = true);

struct ConvergenceSeries {
  std::string family;  // "triangles", "quads", "hexagons"
  std::vector<int> resolutions;
  std::vector<PoissonError> errors;  // solution vectors dropped (sizes only)
  double slope = 0;                  // least-squares slope of log(error) against log(h) (apps/pictures/plot.h)
};

struct ConvergenceOptions {
  std::vector<int> resolutions{8, 16, 32, 64};  // n x n cells of dec/mesh/generators.h's grids
  bool lumped_mass = true;
  LaplacianChoice laplacian = parse_laplacian("ours");
  // Grids of the study: "triangles", "quads", "hexagons" (the paper's) or "sawtooth"
  // (dec/mesh/sawtooth_grid.h: non-convex cells without a valid single fan).
  std::vector<std::string> families{"triangles", "quads", "hexagons"};
};

// The study of Figure 9 on triangle_grid, quad_grid and hex_grid (dec/mesh/generators.h), all on
// [0,1]^2 with the square as boundary (options.families); std::invalid_argument for an unknown family.
std::vector<ConvergenceSeries> franke_convergence(const ConvergenceOptions& options = {});

}  // namespace polydec
