// operators/surface/laplacian.h — the polygon Laplacian of the paper: stiffness S = P^T S^f P (eq. 12),
// Galerkin mass M = P^T M^f P and lumped mass (eq. 13-14), assembled face by face straight
// into the sparse pattern of "vertices sharing a face".
//
// Conventions: S is symmetric NEGATIVE semi-definite (S 1 = 0), as in the paper; the Laplacian
// is L = M^-1 S. Matrices are |V| x |V|, column-major Eigen::SparseMatrix<double>, rows and
// columns in the mesh's vertex order. Unreferenced vertices get empty rows and columns (zero
// lumped mass). Degenerate fan triangles (see RefinementOptions) add no stiffness.
#pragma once

#include <Eigen/Sparse>

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec {

using SparseMatrix = Eigen::SparseMatrix<double>;

// The symbolic part: the column-major pattern of all vertex pairs sharing a face, and for
// every face the slots of its n x n local matrix in the value array. Build once per
// connectivity, reuse for any number of (re-)assemblies on moved vertices.
struct FacePattern {
  SparseMatrix pattern;  // |V| x |V|, values zero
  std::vector<long>
      local_offsets;       // |F| + 1: face f's slots are slots[local_offsets[f] ..], n*n, row-major (a, b)
  std::vector<int> slots;  // index into pattern.valuePtr()
  std::vector<int> face_rank;  // |F|: position of each face in a breadth-first order of the faces
                               // (ranges of it are connected patches: the threads' shares); empty
                               // (threads <= 1): the file's order
};
// The pattern; with threads > 1 (0: all cores) also face_rank, for threaded re-assembly: without
// it the threads split the faces in file order, which parallelizes poorly when that order is not
// spatially coherent (FINE SPHERE: values on 2 threads 1.0x in file order, 1.45x with patches).
// The breadth-first pass is serial and costs about as much as the pattern itself.
FacePattern face_pattern(const Mesh& mesh, int threads = 1);

// What assemble_laplacian computes. The lumped mass is M's column sums when M is asked for, else
// summed face by face from the local mass matrices' row sums, without an nnz-sized mass buffer (and
// without a pattern when S is not asked for either): then equal to M's row sums up to rounding, and
// bitwise the same for any thread count and pattern.
struct LaplacianParts {
  bool stiffness = true;
  bool mass = true;  // unlumped Galerkin mass
  bool lumped_mass = true;
};

struct Laplacian {
  SparseMatrix S;            // stiffness, negative semi-definite (eq. 12)
  SparseMatrix M;            // Galerkin mass, unlumped (eq. 13 before lumping)
  Eigen::VectorXd M_lumped;  // row sums of M (eq. 14)
  FanQuality quality;        // fan triangles of the refinement that was used
};

// How to assemble. Results are bitwise identical for any number of threads: every matrix
// entry receives its face contributions in ascending face order.
struct AssemblyOptions {
  int threads = 1;  // 0: all hardware threads
};

// One pass over the faces computing the requested parts. `pattern` may be passed to skip the
// symbolic step (re-assembly on moved vertices with the same connectivity).
Laplacian assemble_laplacian(const Mesh& mesh, const Refinement& refinement, LaplacianParts parts = {},
                             const FacePattern* pattern = nullptr, const AssemblyOptions& options = {});

// Re-assembly on moved vertices (same connectivity as `pattern`): overwrites the requested
// parts of L in place, reusing its storage (no allocation when L already holds them).
// Gives the same values as a fresh assemble_laplacian.
void reassemble_laplacian(const Mesh& mesh, const Refinement& refinement, const FacePattern& pattern,
                          LaplacianParts parts, Laplacian& L, const AssemblyOptions& options = {});

// Shorthands.
SparseMatrix stiffness(const Mesh& mesh, const Refinement& refinement);
SparseMatrix mass(const Mesh& mesh, const Refinement& refinement);
Eigen::VectorXd lumped_mass(const Mesh& mesh, const Refinement& refinement);

}  // namespace polydec
