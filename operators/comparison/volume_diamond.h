// operators/comparison/volume_diamond.h — the Diamond Laplacian of [BBA21] on polyhedral volume meshes.
//
// Diamonds per face, split by the face's fan (dec/volume/refinement.h's face point x_f): for every
// face edge (x_p, x_q) the sub-diamond is the double pyramid over the triangle (x_p, x_q, x_f) with
// tips the two adjacent cells' points (a boundary face has one cell: the sub-diamond is the single
// tetrahedron (x_p, x_q, x_f, x_c)). The union of a face's sub-diamonds is the face's diamond, the
// convex hull of the face and the two cell points when that is convex. Values at face and cell
// points are interpolated by the refinement's affine weights (P of operators/volume/laplacian.h).
// Gradient per sub-diamond by the discrete Gauss formula over its closed triangulated boundary,
//   g = (1/V) sum_t a_t (u_a + u_b + u_c) / 3,   V = (1/3) sum_t a_t . (centroid_t - o),
// a_t the outward area vectors (exact for linear u); W = diag(|V|), S = -G^T W G = D G. Mass (as the
// authors' code): a quarter of V to each tip and a sixth to each of x_p, x_q, x_f (on boundary faces
// the missing tip's quarter goes to x_f), coarsened M = P^T M^fine P, M_lumped its row sums.
// Conventions as operators/volume/laplacian.h (S negative semi-definite, S 1 = 0). docs/volumes.md.
#pragma once

#include "polydec/dec/volume/refinement.h"
#include "polydec/operators/comparison/diamond.h"
#include "polydec/operators/registry/volume_laplacians.h"
#include "polydec/operators/volume/laplacian.h"

namespace polydec {

// The fine sub-diamonds (face by face, within a face one per face edge) on the refined points.
FineDiamonds volume_diamonds(const VolumeMesh& mesh, const VolumeRefinement& refinement);

// S, M, M_lumped of the volume Diamond Laplacian for a refinement (quality: the refinement's).
VolumeLaplacian assemble_volume_diamond(const VolumeMesh& mesh, const VolumeRefinement& refinement);

// The same with the default refinement (or options.refinement) as an OperatorSet (name "diamond (volume)", no surface
// domain, n_input_vertices = |V|, mean_edge_length of the volume mesh, sub_tet_quality the
// refinement's sub-tetrahedron counts); options.with_gradient adds G (3 rows per sub-diamond) and D,
// options.keep_refinement the refinement (volume_refinement); options.threads is not used.
// n_degenerate_triangles / n_folded_triangles count degenerate and folded (negative Gauss volume)
// sub-diamonds. Method "diamond" of operators/registry/volume_laplacians.h.
OperatorSet volume_diamond_operators(const VolumeMesh& mesh, const VolumeOperatorOptions& options = {});

}  // namespace polydec
