// operators/comparison/triangulation.h — triangulating polygons without new vertices by dynamic programming
// over diagonals (Liepa 2003), O(n^3) per polygon: the triangulation with the minimum sum of
// squared triangle areas, or the one maximizing the minimum triangle angle. Both are defined for
// non-planar polygons (areas and angles measured in 3D). Neither checks for fold-overs: on
// non-convex polygons the max-min-angle triangulation can pick triangles outside the polygon
// (paper section 5), and so, more rarely, can the min-area one.
#pragma once

#include <string>
#include <vector>

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/virtual_vertex.h"

namespace polydec {

enum class TriangulationRule {
  MinSquaredArea,  // minimize sum of area(t)^2 (Liepa 2003)
  MaxMinAngle,     // maximize the smallest angle over all triangles
};

// Triangles of one polygon, as corner indices (a, b, c) with a < b < c, oriented like the polygon.
using PolygonTriangulation = std::vector<Eigen::Vector3i>;

// The optimal triangulation of the polygon X (n x 3, n >= 3); ties (costs within 1e-12 of each
// other, relative) go to the smallest apex index, so that round-off, which changes with the
// polygon's position and scale, does not pick among equal triangulations.
PolygonTriangulation triangulate_polygon(const PolygonPositions& X, TriangulationRule rule);

// The objective of a triangulation: sum of squared areas (MinSquaredArea) or the smallest angle
// in radians (MaxMinAngle).
double triangulation_cost(const PolygonPositions& X, const PolygonTriangulation& T, TriangulationRule rule);

// The triangles (global vertex indices) of every face triangulated by `rule`: n - 2 per n-gon,
// contiguous and in face order. Not validated as a mesh: a max-min-angle triangle that folds out
// of a non-convex polygon can overlap a neighbouring face and share an edge with it.
std::vector<Eigen::Vector3i> triangulate(const Mesh& mesh, TriangulationRule rule);

}  // namespace polydec
