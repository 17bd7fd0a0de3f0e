// operators/volume/laplacian.h — the polyhedral Laplacian of volume meshes: stiffness S = P^T S^tet P,
// Galerkin mass M = P^T M^tet P and lumped mass, with P the composed prolongation (mesh vertices
// <- face points <- cell points) of dec/volume/refinement.h and S^tet, M^tet the linear finite
// elements of the sub-tetrahedra. Assembled cell by cell into the pattern of "vertices sharing a
// cell".
//
// Conventions as on surfaces (operators/surface/laplacian.h): S symmetric NEGATIVE semi-definite, S 1 = 0,
// L = M^-1 S; |V| x |V| column-major matrices in the mesh's vertex order; unreferenced vertices get
// empty rows and columns. Degenerate sub-tetrahedra add no stiffness.
#pragma once

#include <Eigen/Sparse>

#include "polydec/dec/volume/prolongation.h"
#include "polydec/dec/volume/refinement.h"

namespace polydec {

using SparseMatrix = Eigen::SparseMatrix<double>;

// The symbolic part: the pattern of vertex pairs sharing a cell (values zero).
SparseMatrix cell_pattern(const VolumeMesh& mesh);

// Coarsened local matrices of one cell, P_c^T S^tet P_c and P_c^T M^tet P_c, rows and columns
// in the order of VolumeMesh::cell_vertices(c). Either output may be null.
void cell_matrices(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c, Eigen::MatrixXd* S,
                   Eigen::MatrixXd* M);

struct VolumeLaplacian {
  SparseMatrix S;            // stiffness, negative semi-definite
  SparseMatrix M;            // Galerkin mass
  Eigen::VectorXd M_lumped;  // row sums of M
  SubTetQuality quality;     // of the refinement that was used
};

// One pass over the cells; `pattern` (from cell_pattern) may be passed to skip the symbolic step
// (each cell's entries are then found by searching its columns; the pattern built here also records
// where they sit, 2 bytes per local entry, freed on return).
// `threads` (0: all hardware threads) build the pattern by vertex ranges and take the cells in
// contiguous ranges, each thread adding its cells to the columns of the vertices all of whose cells
// it holds, then one pass the cells around the vertices on the seams (when the cell order is not
// spatially coherent, more than 1/8 of the cells on seams: blocks of cells computed in parallel and
// added by column ranges); results are bitwise identical for every thread count.
VolumeLaplacian assemble_volume_laplacian(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                          const SparseMatrix* pattern = nullptr, int threads = 1);

}  // namespace polydec
