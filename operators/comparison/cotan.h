// operators/comparison/cotan.h — the plain cotangent Laplacian of a triangle mesh (paper eq. 2-3) as the
// triangulation-based comparison Laplacians ("triangulated-*", "refined", "intrinsic-delaunay") use it:
// the operators themselves (cotan_operators, TriangleOperators, LengthTriangles,
// triangle_area_from_lengths) are declared in operators/surface/cotan_operators.h, included here;
// this header adds edge lengths of triangles, mixed Voronoi vertex areas and the mean edge length.
#pragma once

#include <vector>

#include "polydec/operators/surface/cotan_operators.h"

namespace polydec {

// The edge lengths of triangles over positions (|V| x 3), for the length-based cotan_operators and
// voronoi_areas.
LengthTriangles length_triangles(const Eigen::MatrixX3d& positions, const std::vector<Eigen::Vector3i>& triangles);

// Mixed Voronoi vertex areas (Meyer et al. 2003) of triangles given by lengths: per corner the
// circumcentric dual area in non-obtuse triangles; in an obtuse triangle half its area to the
// obtuse corner and a quarter to each other one. Sums to the total area. This is libigl's
// default (Voronoi) lumped mass and pmp-library's voronoi_area, which the paper's [BS07] and
// [Lie03] numbers were computed with (Tables 2, 3: see docs/paper.md).
Eigen::VectorXd voronoi_areas(const LengthTriangles& triangles);

// Mean length of the undirected edges of `triangles` over `positions` (each edge once).
double mean_edge_length(const Eigen::MatrixX3d& positions, const std::vector<Eigen::Vector3i>& triangles);

}  // namespace polydec
