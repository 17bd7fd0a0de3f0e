// dec/volume/hodge_star.h — prolongations P0..P3 and Hodge stars star0..star3 of the coarsened
// Whitney forms on a polyhedral mesh (paper eq. 23-27 in 3D).
//
// With the coarse hats phi_i = sum_r P_ri phi^tet_r (P = P0, dec/volume/prolongation.h), the
// coarse Whitney k-form of a sorted coarse simplex (i_0 < .. < i_k) is, by multilinearity,
//   phi_{i_0..i_k} = sum over sorted refined k-simplices (r_0 < .. < r_k) of
//                    det[P_{r_a, i_b}]_{a,b = 0..k} phi^tet_{r_0..r_k},
// the 3D form of eq. 25-26 (docs/feec.md): P_k holds these determinants. A refined simplex has at
// most one face point and one cell point (the other rows of P are unit rows), so each of its rows
// has at most C(m, 2) entries for a cell of m vertices.
//
// Refined stars: Galerkin inner products of the Whitney forms of the sub-tetrahedra
// (dec/volume/whitney.h); degenerate sub-tetrahedra add nothing to star1..star3 (as they add no
// stiffness, so that S = -d0^T star1 d0 holds exactly). Coarse stars star_k = P_k^T star_k^tet P_k
// (eq. 27), symmetric positive semi-definite, storing no exact zeros; star0 equals the Galerkin
// mass M. Rows and columns in the numbering of dec/volume/complex.h.
#pragma once

#include <Eigen/Sparse>

#include "polydec/dec/surface/form_span.h"
#include "polydec/dec/surface/mesh_complex.h"
#include "polydec/dec/volume/complex.h"

namespace polydec {

using SparseMatrix = Eigen::SparseMatrix<double>;

// P_k: refined.n_simplices(k) x coarse.n_simplices(k), k = 0..3.
Eigen::SparseMatrix<double> volume_prolongation_k(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                                  const SimplexComplex3& coarse,
                                                  const SimplexComplex3& refined, int k);

// star_k^tet on the refined complex, k = 0..3.
Eigen::SparseMatrix<double> volume_refined_star(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                                const SimplexComplex3& refined, int k);

// Everything of DEC on a volume mesh, computed once.
struct VolumeDec {
  DecComplex complex = DecComplex::Complete;
  int max_degree = 3;                   // d_k for k < max_degree, P_k and star_k for k <= max_degree
  SimplexComplex3 coarse;               // the complete complex's simplices; empty for the mesh complex,
                                        // whose cells are the mesh's (dec/volume/mesh_complex.h)
  SimplexComplex3 refined;
  Eigen::SparseMatrix<double> d[3];     // coarse d0, d1, d2 (empty beyond max_degree)
  Eigen::SparseMatrix<double> P[4];     // P0..P3
  Eigen::SparseMatrix<double> star[4];  // coarse star0..star3
};

struct VolumeDecOptions {
  int max_degree = 3;                                // 0..3
  DecComplex complex = DecComplex::Complete;         // the paper's cells, or the mesh's own
  SpokeRule spoke_rule = SpokeRule::AreaConsistent;  // the mesh complex's face kernel
};

// Builds the complexes, d_k, P_k and star_k up to degree max_degree (0..3). On the complete
// complex std::invalid_argument when a cell has more than max_dec_cell_vertices(max_degree)
// vertices (volume_dec_max_degree tells the largest degree a mesh allows); on the mesh complex
// every degree works for cells of any size.
VolumeDec volume_dec(const VolumeMesh& mesh, const VolumeRefinement& refinement, const VolumeDecOptions& options);
// The complete complex up to max_degree.
VolumeDec volume_dec(const VolumeMesh& mesh, const VolumeRefinement& refinement, int max_degree = 3);

// The reduced basis of the coarse Whitney k-forms (k = 1, 2, 3; docs/volumes.md): the coarse
// k-simplices picked by column-pivoted QR of P_k restricted to the refined simplices with mass (a
// pivot counts above `tolerance` times the largest; P_k entries are dimensionless), so that
// R^T star_k R is positive definite. Dense: std::invalid_argument when P_k has more than
// `max_entries` dense entries (rows with mass times coarse simplices).
FormSpan volume_form_span(const VolumeDec& dec, const VolumeMesh& mesh, const VolumeRefinement& refinement,
                          int degree, double tolerance = 1e-10, long max_entries = 40'000'000);

}  // namespace polydec
