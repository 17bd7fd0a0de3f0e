// dec/surface/hodge_star.h — discrete Hodge stars of the coarsened Whitney forms (paper eq. 20-22, 27).
//
// Refined stars, from the Whitney forms of the fan triangulation (dec/surface/whitney.h):
//   star0^f: Galerkin mass of the hat functions, (|V|+|F|) x (|V|+|F|);
//   star1^f: Whitney 1-form mass, (|E|+|H|) x (|E|+|H|), summed over the fan triangles;
//   star2^f: diag(1 / area), |H| x |H| (1/area for either orientation of a triangle).
// Coarse stars star_k = P_k^T star_k^f P_k (eq. 27), assembled face by face without building
// P_k or star_k^f: star0 (|V| x |V|, equals the Galerkin mass M of operators/surface/laplacian.h), its
// lumped version (row sums), star1 (|C1| x |C1|) and star2 (|C2| x |C2|). Rows and columns in
// the CoarseComplex numbering.
//
// All stars are symmetric positive SEMI-definite. star1 and star2 are singular in general: the
// coarsened Whitney 1-forms of an n-gon span 2n-1 dimensions (n>=5), its 2-forms n dimensions
// (n>=4), fewer than the face's n(n-1)/2 pairs and n(n-1)(n-2)/6 triples (docs/feec.md). Use
// dec/surface/form_span.h to solve with them. Fan triangles flagged degenerate (RefinementOptions)
// contribute nothing to star1^f and star2^f, exactly as they add no stiffness to S, so that
// S = -d0^T star1 d0 holds on every mesh.
//
// Cost: a face of valence n has n(n-1)/2 pairs and n(n-1)(n-2)/6 triples; its local star1 has
// O(n^4) and its local star2 O(n^6) entries (a 12-gon: 66^2 and 220^2). Fine for quads and
// hexagons; callers should warn on very high valence (see kHighValence).
#pragma once

#include <Eigen/Sparse>
#include <span>
#include <vector>

#include "polydec/dec/surface/complex.h"
#include "polydec/dec/surface/mesh_complex.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Above this face valence the per-face 2-cells (and star2) grow large enough to warn about.
inline constexpr int kHighValence = 12;

// Refined stars on the fan triangulation (numbering of dec/surface/complex.h).
SparseMatrix refined_star0(const Mesh& mesh, const Refinement& refinement);
SparseMatrix refined_star1(const Mesh& mesh, const Refinement& refinement);
SparseMatrix refined_star2(const Mesh& mesh, const Refinement& refinement);

// Face-local kernels, P_f^T star^f_f P_f of one polygon: corners X (n x 3, face order), weights
// w, virtual point xf, fan-triangle flags (n, fan triangle k = (x_k, x_{k+1}, xf)), and `order`,
// the corners sorted by vertex index (CoarseComplex::sorted_corners). Rows and columns are the
// face's pairs (triples) in local lexicographic order of corner ranks, i.e. in the order of
// CoarseComplex::face_pairs (face_triples).
Eigen::MatrixXd polygon_star1(const PolygonPositions& X, const Eigen::VectorXd& w, const Eigen::Vector3d& xf,
                              const FanTriangle* fan, std::span<const int> order);
Eigen::MatrixXd polygon_star2(const PolygonPositions& X, const Eigen::VectorXd& w, const Eigen::Vector3d& xf,
                              const FanTriangle* fan, std::span<const int> order);

// What hodge_stars computes.
struct HodgeStarParts {
  bool star0 = true;
  bool star0_lumped = true;
  bool star1 = true;
  bool star2 = true;
};

struct HodgeStars {
  SparseMatrix star0;            // |V| x |V|, Galerkin (eq. 20, 27)
  Eigen::VectorXd star0_lumped;  // row sums of star0
  SparseMatrix star1;            // |C1| x |C1| (eq. 21, 27)
  SparseMatrix star2;            // |C2| x |C2| (eq. 22, 27)
};

// The symbolic part of the assembly: for each star the column-major pattern of "cells sharing
// a face" (values zero) and, per face, the slots of its local block (row-major) in the value
// array. Depends on the connectivity only: build once, reuse for any number of re-assemblies
// on moved vertices.
struct StarPattern {
  SparseMatrix pattern;
  std::vector<long> offsets;  // |F| + 1: face f's slots are slots[offsets[f] ..], m_f^2 of them
  std::vector<int> slots;     // index into pattern.valuePtr()
};
struct StarPatterns {
  StarPattern star0, star1, star2;  // empty for parts not requested
};
StarPatterns star_patterns(const Mesh& mesh, const CoarseComplex& complex, HodgeStarParts parts = {});

// One pass over the faces computing the requested coarse stars. `patterns` (from
// star_patterns with at least these parts) skips the symbolic step; std::invalid_argument if
// it does not match. The stars store no exact zeros: the entries of the patterns that no fan
// triangle fills (most of star2's: triples of a face that share no polygon edge) are dropped.
HodgeStars hodge_stars(const Mesh& mesh, const Refinement& refinement, const CoarseComplex& complex,
                       HodgeStarParts parts = {}, const StarPatterns* patterns = nullptr);

// Shorthands.
SparseMatrix star1(const Mesh& mesh, const Refinement& refinement, const CoarseComplex& complex);
SparseMatrix star2(const Mesh& mesh, const Refinement& refinement, const CoarseComplex& complex);

// Everything of DEC on a polygon mesh, computed once: the fields of VolumeDec
// (dec/volume/hodge_star.h) for surfaces, so that d[k], P[k] and star[k] read alike on both, on
// either complex. Built from the functions above and those of dec/surface/complex.h,
// dec/surface/prolongation.h and dec/surface/mesh_complex.h, which remain the building blocks.
struct SurfaceDec {
  DecComplex complex = DecComplex::Complete;
  int max_degree = 2;    // d_k for k < max_degree, P_k and star_k for k <= max_degree
  CoarseComplex coarse;  // the complete complex's cells (dec/surface/complex.h); empty for the mesh complex,
                         // whose cells are the mesh's vertices, edges (Mesh::edges()) and faces
  SparseMatrix d[2];     // coarse d0 (|C1| x |V|), d1 (|C2| x |C1|); empty beyond max_degree
  SparseMatrix P[3];     // P0 = prolongation, P1, P2 (dec/surface/prolongation.h, mesh_complex.h)
  SparseMatrix star[3];  // coarse star0 (the Galerkin mass M), star1, star2 (diagonal on the mesh complex)
};

struct SurfaceDecOptions {
  int max_degree = 2;                          // 0..2
  DecComplex complex = DecComplex::Complete;  // the paper's cells, or the mesh's own
  SpokeRule spoke_rule = SpokeRule::AreaConsistent;  // the mesh complex's P1 (dec/surface/mesh_complex.h)
};

// Builds the complex, d_k, P_k and star_k up to degree max_degree (0..2, std::invalid_argument
// otherwise). On the complete complex star2 costs O(n^6) per n-gon (max_degree = 1 skips it); on
// the mesh complex every degree costs O(n^2) per n-gon. Defined in dec/surface/surface_dec.cpp.
SurfaceDec surface_dec(const Mesh& mesh, const Refinement& refinement, const SurfaceDecOptions& options);
// The complete complex up to max_degree.
SurfaceDec surface_dec(const Mesh& mesh, const Refinement& refinement, int max_degree = 2);

}  // namespace polydec
