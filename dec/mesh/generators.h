// dec/mesh/generators.h — the library's own sample meshes and mesh transformations: planar grids
// (triangle, quad, hexagon), spheres (UV quad sphere, cube sphere, hexagon-dominant sphere), a
// quad torus, a genus-2 quad surface, Catmull-Clark subdivision, the dual mesh, projection to
// the unit sphere and deterministic noise. Every generator returns a validated Mesh with
// counter-clockwise (outward) faces; it throws std::invalid_argument for bad sizes and, before
// building anything, for meshes of more than 1e8 vertices.
#pragma once

#include "polydec/dec/mesh/mesh.h"

#include <cstdint>

namespace polydec {

// Planar grids on [0,1]^2 (z = 0), nx by ny cells.
Mesh quad_grid(int nx, int ny);
// Each cell split into two triangles along the same diagonal (from (i,j) to (i+1,j+1)).
Mesh triangle_grid(int nx, int ny);
// Hexagon-dominant tiling of [0,1]^2: the boundary-aware dual of triangle_grid(nx, ny); interior
// faces are hexagons, boundary faces are the halves cut by the square's sides.
Mesh hex_grid(int nx, int ny);
// Non-convex tiling of [0,1]^2: the cells of quad_grid(nx, ny) with each interior horizontal edge
// bent upwards at its midpoint by `dent` (fraction of a cell's height, in (0, 1/2)); each cell is a
// hexagon (corner, bottom midpoint, corner, corner, top midpoint, corner) whose bottom midpoint is
// a reflex corner, except in the bottom row (straight bottom side: convex).
Mesh chevron_grid(int nx, int ny, double dent = 0.3);

// UV sphere of radius 1 with n_lat latitude bands and n_lon longitude segments: quads, and
// triangles around the two poles. The polar axis is z.
Mesh uv_sphere(int n_lat, int n_lon);
// Quad-only sphere: a cube with n x n quads per side, projected to the unit sphere (6 n^2 faces).
Mesh cube_sphere(int n);
// Hexagon-dominant sphere (12 pentagons): dual of an icosahedron subdivided `level` times
// (1-to-4, projected), dual vertices at face centroids, projected to the unit sphere.
Mesh hex_sphere(int level);

// Quad torus with n_major x n_minor faces, radii R > r > 0, around the z axis.
Mesh torus(int n_major, int n_minor, double R = 1.0, double r = 0.4);
// Its soup (no validation or topology: the compact form the distributed engine generates).
PolygonSoup torus_soup(int n_major, int n_minor, double R = 1.0, double r = 0.4);
// A closed genus-2 quad surface: the boundary of a 5 x 3 x 1 block of unit cubes with two
// cubes removed (two holes), optionally smoothed by `subdivisions` Catmull-Clark steps.
Mesh genus2(int subdivisions = 1);

// One Catmull-Clark step with the rules of the paper authors' program (see docs/operators.md):
// face point = average of the face's vertices; interior edge point = average of the endpoints
// and the two face points; boundary edge point = midpoint; interior vertex of valence k =
// (sum of neighbours + sum of adjacent face points) / k^2 + (k - 2) / k * old position;
// boundary vertex = (6 old + its two boundary neighbours) / 8. New vertex order: old vertices
// (same indices), then edge points (edge order of Mesh::edges()), then face points.
Mesh catmull_clark(const Mesh& mesh);

// Dual mesh: one vertex per face (the centroid of its vertices), one face per vertex. With
// boundary, a boundary vertex's dual face also uses the midpoints of its two boundary edges and
// the vertex itself, so the dual covers the same domain. Vertex order: face centroids (face
// order), then boundary edge midpoints, then boundary vertices. Throws InvalidMeshError at a
// non-manifold vertex.
Mesh dual(const Mesh& mesh);

// Every vertex moved to p / |p| (throws InvalidMeshError for a vertex at the origin).
Mesh project_to_unit_sphere(const Mesh& mesh);

// Every vertex moved by a uniform random vector of length up to amplitude * mean edge length
// (deterministic for a given seed).
Mesh add_noise(const Mesh& mesh, double amplitude, std::uint64_t seed = 1);

}  // namespace polydec
