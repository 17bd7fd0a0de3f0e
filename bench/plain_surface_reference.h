// bench/plain_surface_reference.h — a deliberately plain implementation of the polygon Laplacian of
// "Polygon Laplacian Made Simple" (Bunge et al. 2020) in the style of the authors' published code:
// per face a dense local system, S = P^T S^f P (eq. 12) and M = P^T M^f P (eq. 13-14) added through
// Eigen triplets. The timing baseline of polydec_bench's surface rows and an independent oracle for
// the [surface-bench-ref] test.
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <vector>

namespace polydec {
class Mesh;
}

namespace plain_surface_reference {

struct Mesh {
  std::vector<Eigen::Vector3d> V;
  std::vector<std::vector<int>> F;  // vertex cycles, counter-clockwise
};

// The reference's own copy of a polydec mesh (built outside any timed region).
Mesh from_mesh(const polydec::Mesh& mesh);

// Stiffness S (negative semi-definite, S 1 = 0) and Galerkin mass M, |V| x |V|: per face the virtual
// vertex minimizing the sum of squared fan-triangle areas (eq. 10) with least-norm affine weights,
// the fan triangles' cotangent stiffness and linear mass, coarsened by the face's prolongation
// P = [I; w^T]. Fan triangles with 2 area <= 1e-8 longest_edge^2 add no stiffness.
void build(const Mesh& mesh, Eigen::SparseMatrix<double>& S, Eigen::SparseMatrix<double>& M);

}  // namespace plain_surface_reference
