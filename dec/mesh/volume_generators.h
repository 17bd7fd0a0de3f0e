// dec/mesh/volume_generators.h — polyhedral test meshes of the unit cube [0, 1]^3 (hexahedra,
// tetrahedra, pyramids, clipped truncated octahedra), a hexahedral solid torus and a
// hexahedral ball, each with an optional seeded jitter of the interior vertices.
#pragma once

#include <cstdint>

#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec {

// Jitter of interior vertices: each moves by a uniformly random vector in the ball of radius
// `amplitude` times its shortest incident edge (so 0 < amplitude < 0.5 keeps cells valid on
// these meshes); boundary vertices stay. Deterministic for a given seed.
struct VolumeJitter {
  double amplitude = 0.0;
  std::uint64_t seed = 1;
};

// Moves the interior vertices of `mesh` as VolumeJitter describes.
VolumeMesh jitter_interior(const VolumeMesh& mesh, const VolumeJitter& jitter);

// nx x ny x nz hexahedra filling [0, 1]^3; vertex (i, j, k) has index i + (nx+1)(j + (ny+1) k).
VolumeMesh hex_grid_volume(int nx, int ny, int nz, const VolumeJitter& jitter = {});

// The same grid with every cube split into 6 tetrahedra around its diagonal from (i, j, k) to
// (i+1, j+1, k+1) (Kuhn subdivision: conforming, every cube split the same way).
VolumeMesh tet_grid_volume(int nx, int ny, int nz, const VolumeJitter& jitter = {});

// The same grid with every cube split into 6 pyramids (its faces as bases) around a new vertex
// at its centre; the centres are numbered after the grid vertices.
VolumeMesh pyramid_grid_volume(int nx, int ny, int nz, const VolumeJitter& jitter = {});

// The bitruncated cubic honeycomb clipped to [0, 1]^3: the Voronoi cells of the body-centred
// cubic lattice with n cubes per side (sites at the cube corners and centres), each
// intersected with the box. Interior cells are truncated octahedra (6 squares, 8 hexagons);
// clipped cells are convex polyhedra with planar faces. n^3 + (n+1)^3 cells.
VolumeMesh truncated_octahedra_volume(int n, const VolumeJitter& jitter = {});

// The cube family of polyLaplace's cube_truncated_L.ovm files (n = 2^(L-1) reproduces level L):
// each of the n^3 cubes of [0, 1]^3 split into the cuboctahedron on its 12 edge midpoints (6
// squares, 8 triangles; 5/6 of the cube) and its 8 corner tetrahedra (1/48 each). Grid corners
// lie in tetrahedra only. 9 n^3 cells, all faces planar.
VolumeMesh cuboctahedra_volume(int n, const VolumeJitter& jitter = {});

// A hexahedral solid torus: an n_cross x n_cross grid of squares (side 2 r, centred at radius
// R from the z axis) swept around the z axis in n_around steps. First Betti number 1,
// V - E + F - C = 0. All faces planar.
VolumeMesh hex_torus_volume(int n_around, int n_cross, double R = 1.0, double r = 0.4,
                            const VolumeJitter& jitter = {});

// A hexahedral unit ball: the n x n x n grid of [-1, 1]^3 mapped along rays by
// x -> x ((1 - t) + t |x|_inf / |x|_2), t = |x|_inf, so the centre stays nearly a cube grid
// and the boundary lands on the unit sphere (boundary vertices exactly on it).
VolumeMesh hex_ball_volume(int n, const VolumeJitter& jitter = {});

}  // namespace polydec
