// dec/volume/mesh_complex.h — DEC on a polyhedral mesh's own cells: its vertices, edges, faces
// and cells, prolongations P1, P2, P3 onto the sub-tetrahedra that commute with d, and the Hodge
// stars star_k = P_k^T star_k^tet P_k (eq. 27), small and symmetric positive definite for cells
// of any size. The volume analogue of dec/surface/mesh_complex.h, whose per-polygon kernel it
// uses for every face; the paper's complete complex of all vertex subsets of a cell is
// dec/volume/complex.h.
//
// Cells and orientations (the "mesh complex"):
//   0-cells: the vertices; 1-cells: VolumeMesh::edges(), oriented i -> j (i < j); 2-cells: the
//   faces, oriented by VolumeMesh::face(f)'s vertex order; 3-cells: the cells, oriented
//   positively (outward half-face normals).
//   d0 (|E| x |V|): (d0 u)_e = u_j - u_i;  d1 (|F| x |E|): +-1 per side of face f, + where the
//   side (a -> b) runs along its edge (a < b);  d2 (|C| x |F|): +1 where cell c holds half-face
//   2f, -1 where it holds 2f+1. Integer-valued; d_{k+1} d_k = 0 exactly.
//
// Refined complex: volume_refined_complex (dec/volume/complex.h: refined vertices |V| + f face
// points, |V| + |F| + c cell points; simplices oriented by increasing index). P0 is
// volume_prolongation (dec/volume/prolongation.h). P_k (refined.n_simplices(k) x n coarse
// k-cells) is built by the dimension of the coarse cell holding a refined simplex inside, so that
// P_{k+1} d_k = d_k^tet P_k (to round-off):
//   - inside a mesh edge: the edge itself, a unit row;
//   - inside a face f (spokes (v, x_f), fan triangles (v_i, v_{i+1}, x_f)): polygon_cochain_maps
//     of the face (dec/surface/mesh_complex.h) with the face weights of the refinement and the fan
//     triangles' areas (negative when against the face's vector area), exactly as on surfaces;
//   - inside a cell c (edges (v, x_c), (x_f, x_c); triangles (v_i, v_j, x_c) over the cell's
//     edges and (v, x_f, x_c) over its face corners; the sub-tetrahedra): the row r of a refined
//     k-simplex rho over the coarse k-cells of the cell's closure solves r D_{k-1} = row rho of
//     d^tet_{k-1} P_{k-1}, D_{k-1} the cell's local incidence matrix. The closure is a ball, so
//     this is solvable (cells whose boundary is not a sphere are refused), up to y D_{k-1} = 0:
//       k = 1: minimum norm, r^T = D0 L^+ g^T (L the Laplacian of the cell's edge graph);
//       k = 2: minimum norm plus c_rho Z (Z = row c of d2, the cell's oriented boundary), the c_rho
//              of least norm such that every sub-tetrahedron tau gets the P3 row vol_tau / vol_c
//              (vol_tau signed along tau's refined orientation, vol_c = the sub-tetrahedra's total
//              volume, the cell's volume when its faces are planar);
//       k = 3: then unique, P3 = vol_tau / vol_c.
//     The rule depends neither on the order of a cell's faces nor on where a face's vertex list
//     starts (least-norm solutions are invariant under renumbering). The least-norm solves are
//     dense per cell, through the graph Laplacians D0^T D0, D1 D1^T and that of the
//     sub-tetrahedra's adjacency, each made definite by adding its one-dimensional kernel (no
//     rank threshold).
// Stars, cell by cell from the cell's sub-tetrahedra (dec/volume/whitney.h), memory and time
// linear in the mesh size: star0 the Galerkin mass M; star1 and star2 blocks over the edges and
// faces of each cell; star3 diagonal, sum |vol_tau| / vol_c^2, i.e. 1 / vol_c when no
// sub-tetrahedron is inverted. P1..P3 have full column rank, so star1..star3 are positive
// definite when no sub-tetrahedron is degenerate.
// Degenerate sub-tetrahedra (SubTet::Degenerate) add nothing to star1..star3, as in
// dec/volume/hodge_star.h, so -d0^T star1 d0 = S of operators/volume/laplacian.h exactly.
#pragma once

#include <Eigen/Sparse>
#include <array>
#include <vector>

#include "polydec/dec/surface/mesh_complex.h"
#include "polydec/dec/volume/complex.h"

namespace polydec {

// Signed incidence matrices of the mesh complex: k = 0 (|E| x |V|), 1 (|F| x |E|), 2 (|C| x |F|).
SparseMatrix volume_mesh_d(const VolumeMesh& mesh, int k);

// P_k (k = 0..3) of the mesh complex, rows in the numbering of `refined` (volume_refined_complex
// of the same mesh and refinement); P0 is volume_prolongation. std::invalid_argument for a cell
// whose boundary is not a sphere or whose sub-tetrahedra have no positive total volume.
SparseMatrix volume_mesh_prolongation(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                      const SimplexComplex3& refined, int k,
                                      SpokeRule rule = SpokeRule::AreaConsistent);
// The same, building the refined complex.
SparseMatrix volume_mesh_prolongation(const VolumeMesh& mesh, const VolumeRefinement& refinement, int k,
                                      SpokeRule rule = SpokeRule::AreaConsistent);

// star_0..star_max_degree of the mesh complex in one pass over the cells (higher ones empty):
// star0 |V| x |V|, star1 |E| x |E|, star2 |F| x |F|, star3 |C| x |C| (diagonal).
std::array<SparseMatrix, 4> volume_mesh_stars(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                              int max_degree = 3, SpokeRule rule = SpokeRule::AreaConsistent);

// d_k (k < max_degree), P_k and star_k (k <= max_degree) in one pass over the cells, each cell's
// local systems solved once (what volume_dec uses for DecComplex::Mesh). The stars are summed into
// their patterns (dec/detail/element_pattern.h, the pairs of coarse cells sharing a cell) and P_k
// is written into columns sized from the connectivity: no list of all local entries is held, and
// the peak memory stays near the size of the results.
struct VolumeMeshDec {
  SparseMatrix d[3], P[4], star[4];
};
// One cell's share of the bundle, as volume_mesh_dec adds it: the cell's vertices (ascending),
// edges (ascending) and faces (half-face order) as global indices; the dense blocks
// P_k^T star_k^tet P_k over them (k = 0..min(max_degree, 2)) and its star3 entry (max_degree 3);
// the rows of P_k (k = 1..max_degree) of every refined k-simplex of its sub-tetrahedra (rows[k]:
// their indices in `refined`; P[k]: dense over the local vertices, edges or faces, P[3] one column,
// the cell). A face's rows are in both of its cells' shares, equal. std::invalid_argument for c
// out of range and as volume_mesh_prolongation.
struct VolumeMeshCell {
  std::vector<int> vertices, edges, faces;
  Eigen::MatrixXd star[3];
  double star3 = 0;
  std::vector<int> rows[4];
  Eigen::MatrixXd P[4];
};
VolumeMeshCell volume_mesh_cell(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                const SimplexComplex3& refined, int c, int max_degree = 3,
                                SpokeRule rule = SpokeRule::AreaConsistent);

VolumeMeshDec volume_mesh_dec(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                              const SimplexComplex3& refined, int max_degree = 3,
                              SpokeRule rule = SpokeRule::AreaConsistent);

}  // namespace polydec
