// dec/surface/mesh_complex.h — DEC on the mesh's own cells: the vertices, edges and faces of a
// polygon mesh, prolongations P1, P2 onto the fan triangulation that commute with d, and the
// Hodge stars star_k = P_k^T star_k^f P_k (eq. 27) on them, symmetric positive definite.
//
// Cells and orientations (the "mesh complex"; the paper's complete complex of all vertex pairs
// and triples of a face is dec/surface/complex.h):
//   0-cells: the vertices;
//   1-cells: the mesh edges in Mesh::edges() order, oriented i -> j with i < j;
//   2-cells: the faces in file order, oriented by their vertex order.
//   d0 (|E| x |V|): (d0 u)_e = u_j - u_i;  d1 (|F| x |E|): (d1 c)_f = sum over the face's sides
//   (a -> b) of sign(b - a) c_{ab}. Integer-valued; d1 d0 = 0 exactly.
//
// Prolongations onto the refined complex (numbering of dec/surface/complex.h), docs/feec.md:
//   P0 = prolongation (eq. 11): u(x_f) = sum_j w_j u_j.
//   P1 ((|E| + |H|) x |E|): a mesh edge keeps its value. The spoke (x_i, x_f) of face f must carry
//      u(x_f) - u_i = sum_j w_j (u_j - u_i) for exact forms (P1 d0 = d0^f P0), and u_j - u_i is
//      the sum of the face-oriented side values e_i + .. + e_{j-1}; this fixes the row up to a
//      multiple of the face's boundary cycle (e_0 + .. + e_{n-1}), one constant gamma_i a spoke.
//   P2 (|H| x |F|): fan triangle k of face f gets alpha_k times the face's value; commutation
//      (P2 d1 = d1^f P1) ties alpha_k = w_k + gamma_{k+1} - gamma_k, so choosing the alphas
//      chooses the gammas up to one constant per face, which is taken of least norm (sum over the
//      spokes of the squared coefficients).
//   SpokeRule::AreaConsistent (default): alpha_k = a_k / A_f, the fan triangles' share of the
//      face's area, signed: a_k is fan triangle k's area, negative when it is inverted (oriented
//      against the face's vector area), and A_f = sum_k a_k. P2 then carries the refined surface's
//      area form to itself (constant 2-forms are reproduced), and star2 is diagonal, 1 / A_f when
//      no fan triangle is inverted or degenerate.
//   SpokeRule::MinimumNorm: every spoke row of least norm on its own; then alpha_k = 1/n.
//   Both rules depend on the cyclic order of the face only, not on where its list starts.
// Since P_{k+1} d_k = d_k^f P_k, -d0^T star1 d0 = P0^T S^f P0 = S (eq. 14), the paper's
// stiffness, whichever rule; P1 and P2 have full column rank (unit rows on the mesh edges, one
// block per face), so star1 and star2 are positive definite when no fan triangle is degenerate
// (degenerate fan triangles add nothing, as in dec/surface/hodge_star.h).
#pragma once

#include <Eigen/Sparse>
#include <span>
#include <string>

#include "polydec/dec/surface/refinement.h"

namespace polydec {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Which cells carry the discrete forms: the paper's complete complex (all vertex pairs and
// triples of a face, dec/surface/complex.h) or the mesh's own edges and faces (this header).
enum class DecComplex { Complete, Mesh };
// "complete" or "mesh"; std::invalid_argument otherwise.
DecComplex parse_dec_complex(const std::string& name);
std::string to_string(DecComplex complex);

// How the spoke rows of P1 are fixed (see the header comment).
enum class SpokeRule { AreaConsistent, MinimumNorm };
// "area" or "minimum-norm"; std::invalid_argument otherwise.
SpokeRule parse_spoke_rule(const std::string& name);
std::string to_string(SpokeRule rule);

// The per-polygon kernel of P1 and P2 for one n-gon, in its face-oriented side basis (side k
// from corner k to corner k+1): spokes(i, k) is the coefficient of side k in the spoke
// (x_i, x_f); fractions(k) is fan triangle k's share alpha_k of the face value (sum 1).
// weights: the virtual vertex's affine weights (n, sum 1); fan_areas: the fan triangles' signed
// areas a_k (n; used by AreaConsistent only, which falls back to 1/n when their sum is not
// positive). Exactly, up to round-off: e_k + spokes.row(k+1) - spokes.row(k) = fractions(k) 1^T.
struct PolygonCochainMaps {
  Eigen::MatrixXd spokes;     // n x n
  Eigen::VectorXd fractions;  // n
};
PolygonCochainMaps polygon_cochain_maps(std::span<const double> weights, std::span<const double> fan_areas,
                                        SpokeRule rule = SpokeRule::AreaConsistent);

// Signed fan triangle areas a_k, one per halfedge: the area of (x_k, x_{k+1}, x_f), negative when
// its normal points against the face's vector area.
Eigen::VectorXd signed_fan_areas(const Mesh& mesh, const Refinement& refinement);

// Signed incidence matrices of the mesh complex: d0 |E| x |V|, d1 |F| x |E|.
SparseMatrix mesh_d0(const Mesh& mesh);
SparseMatrix mesh_d1(const Mesh& mesh);

// What mesh_complex_forms computes.
struct MeshComplexParts {
  bool P1 = false, P2 = false, star1 = false, star2 = false;
};
struct MeshComplexForms {
  SparseMatrix P1, P2, star1;  // empty unless asked for
  Eigen::VectorXd star2;       // the diagonal of star2
};
// The requested prolongations and stars (below) in one pass over the faces, each face's kernel
// computed once; the functions below are its shorthands.
MeshComplexForms mesh_complex_forms(const Mesh& mesh, const Refinement& refinement, SpokeRule rule,
                                    MeshComplexParts parts);

// P1: (|E| + |H|) x |E|; P2: |H| x |F| (refined numbering of dec/surface/complex.h).
SparseMatrix mesh_prolongation1(const Mesh& mesh, const Refinement& refinement,
                                SpokeRule rule = SpokeRule::AreaConsistent);
SparseMatrix mesh_prolongation2(const Mesh& mesh, const Refinement& refinement,
                                SpokeRule rule = SpokeRule::AreaConsistent);

// star1 = P1^T star1^f P1 (|E| x |E|, symmetric positive definite), assembled face by face
// (an n-gon adds an n x n block over its sides).
SparseMatrix mesh_star1(const Mesh& mesh, const Refinement& refinement, SpokeRule rule = SpokeRule::AreaConsistent);
// star2 = P2^T star2^f P2 (|F| x |F|), diagonal: sum_k alpha_k^2 / |area_k| over the fan
// triangles not flagged degenerate; 1 / A_f with AreaConsistent on a face without inverted or
// degenerate fan triangles.
Eigen::VectorXd mesh_star2_diagonal(const Mesh& mesh, const Refinement& refinement,
                                    SpokeRule rule = SpokeRule::AreaConsistent);

}  // namespace polydec
