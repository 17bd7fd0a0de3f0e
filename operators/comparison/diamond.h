// operators/comparison/diamond.h — the Diamond Laplacian of Bunge, Botsch & Alexa, "The Diamond Laplace for
// Polygonal and Polyhedral Meshes" (SGP 2021, Computer Graphics Forum 40(5)) [BBA21], on polygon
// meshes (method "diamond" of operators/registry/laplacians.h); the volume version is in
// operators/comparison/volume_diamond.h. Definitions, the choices made and measurements: docs/laplacians.md.
//
// Per edge e = (i, j) with faces f (left of i -> j) and g (right), the diamond is the quadrilateral
// (x_i, x_g, x_j, x_f) spanned by the edge and the two faces' virtual points (dec/surface/refinement.h, the
// squared-area point); on a boundary edge the missing point is the edge midpoint, so the diamond is
// the fan triangle (x_i, x_j, x_f). Values at virtual points are interpolated by the refinement's
// affine weights (the prolongation P of dec/surface/prolongation.h). The diamond gradient is the discrete
// Green formula (1/|D|) sum over the diamond's sides of (mean of u) * outward side normal, which for
// a quadrilateral is the vector g in the plane of the two diagonals with
//   g . (x_j - x_i) = u_j - u_i,   g . (x_f - x_g) = u_f - u_g
// (the diagonals span the plane of the diamond's vector area a = (x_j - x_i) x (x_f - x_g) / 2, so a
// non-planar diamond is handled without choosing a projection). W = diag(|a|) per diamond,
// G = G^fine P, D = -G^T W, S = D G (negative semi-definite, S 1 = 0). Mass: the diamond area is
// lumped to the diamond's corners (a quarter each; a third each on boundary edges) and coarsened,
// M = P^T M^fine P (the mass of the authors' code), M_lumped its row sums.
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "polydec/dec/surface/refinement.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec {

// A diamond's height (2D: twice its area over its longest diagonal; 3D: six times its volume over
// the cube of its longest edge) at most this fraction of its size makes it degenerate: no gradient,
// no weight, no mass.
inline constexpr double kDiamondDegenerateTolerance = 1e-8;

// The diamond operators before coarsening, on the refined points (mesh vertices, then face points,
// then, for volumes, cell points).
struct FineDiamonds {
  int n_points = 0;                              // columns of the fine gradient
  std::vector<Eigen::Triplet<double>> gradient;  // rows 3k, 3k+1, 3k+2: the gradient on diamond k
  Eigen::VectorXd weight;                        // |D_k| (area or volume), zero where degenerate
  Eigen::VectorXd mass;                          // lumped mass per refined point
  int n_degenerate = 0;  // diamonds of zero size (relative to kDiamondDegenerateTolerance)
  int n_folded = 0;      // diamonds oriented against their faces (2D) or cells (3D)
};

// The coarse operators from the fine ones and the prolongation P (refined points x |V|):
// G = G^fine P, D = -G^T W, S = D G, M = P^T diag(mass) P, M_lumped = P^T mass (its row sums, as
// the rows of P sum to 1). G and D are only filled when `G` and `D` are non-null.
void coarsen_diamonds(const FineDiamonds& fine, const SparseMatrix& P, SparseMatrix& S, SparseMatrix& M,
                      Eigen::VectorXd& M_lumped, SparseMatrix* G, SparseMatrix* D);

// coarsen_diamonds into `ops` (S, M, M_lumped, G and D with_gradient), with the fine diamonds'
// degenerate and folded counts in ops.n_degenerate_triangles and ops.n_folded_triangles.
void fill_diamond_operators(const FineDiamonds& fine, const SparseMatrix& P, bool with_gradient,
                            OperatorSet& ops);

// The fine diamonds of a polygon mesh (one per edge, in the mesh's edge order) for a refinement.
FineDiamonds surface_diamonds(const Mesh& mesh, const Refinement& refinement);

// The Diamond Laplacian on `mesh` with the paper's virtual points (squared-area rule): S, M,
// M_lumped and, with_gradient, G (3 rows per edge) and D. n_degenerate_triangles and
// n_folded_triangles count degenerate and folded diamonds.
OperatorSet diamond_operators(const Mesh& mesh, bool with_gradient = true);

}  // namespace polydec
