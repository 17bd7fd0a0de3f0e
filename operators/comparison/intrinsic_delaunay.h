// operators/comparison/intrinsic_delaunay.h — the intrinsic Delaunay triangulation of a triangle mesh
// (Bobenko & Springborn 2007): intrinsic edge flips, computed on edge lengths only, until every
// interior edge is Delaunay (the two angles opposite it sum to at most pi). The cotangent
// Laplacian of the result has non-negative off-diagonal entries (S_ij >= 0 for i != j) and
// satisfies the maximum principle on closed surfaces; with boundary, a boundary edge (never
// flipped) has the weight cot/2 of its one opposite angle, negative where that angle is obtuse.
// The vertices and the intrinsic metric stay those of the input; only the connectivity
// changes, so a triangle may have two edges to the same vertex pair.
#pragma once

#include "polydec/operators/comparison/cotan.h"

namespace polydec {

struct IntrinsicDelaunayOptions {
  // An edge counts as Delaunay when cot(alpha) + cot(beta) >= -tolerance (cotangents are
  // scale-free, so this tolerance is too).
  double tolerance = 1e-12;
};

struct IntrinsicTriangulation {
  LengthTriangles triangles;  // the intrinsic triangles with their edge lengths
  std::vector<int> twin;      // halfedge 3t+k (corner k to k+1 of triangle t) -> its twin, -1 on the boundary
  int n_flips = 0;
  int n_edges_checked = 0;  // interior edges of the final triangulation
};

// Flips the triangles over `positions` (consistently oriented; every edge in at most two
// triangles, else std::invalid_argument naming the edge) to their intrinsic Delaunay
// triangulation. The edge lengths are taken from the positions once; flips use lengths only.
IntrinsicTriangulation intrinsic_delaunay(const Eigen::MatrixX3d& positions,
                                          const std::vector<Eigen::Vector3i>& triangles,
                                          const IntrinsicDelaunayOptions& options = {});

// Largest value of (alpha + beta - pi) over interior edges, alpha and beta the angles opposite the
// edge (<= 0 iff the triangulation is Delaunay); -pi for a triangulation without interior edges.
double max_delaunay_violation(const IntrinsicTriangulation& T);

}  // namespace polydec
