// bench/plain_volume_reference.h — a deliberately plain implementation of the polyhedral
// Laplacian of operators/volume/laplacian.h, written in the style of the surface
// baseline ../shared/bench/plain_reference.cpp: per-element loops over std::vector meshes, dense
// local matrices, S = P^T S^tet P and M = P^T M^tet P added through Eigen triplets. The timing
// baseline of polydec_bench's volume rows and an independent oracle for the [volume-bench-ref] test.
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <vector>

namespace polydec {
class VolumeMesh;
}

namespace plain_volume_reference {

struct Mesh {
  std::vector<Eigen::Vector3d> V;
  std::vector<std::vector<int>> F;  // vertex cycles
  std::vector<std::vector<int>> C;  // half-faces: 2f is face f as listed, 2f+1 reversed; normals point out of the cell
};

// The reference's own copy of a polydec mesh (built outside any timed region).
Mesh from_volume_mesh(const polydec::VolumeMesh& mesh);

// Stiffness S (negative semi-definite) and Galerkin mass M, |V| x |V|: face points and cell points
// by the squared-area and squared-volume minimizers with least-norm affine weights, each cell
// split into the tetrahedra (x_i, x_{i+1}, x_f, x_c), their linear FEM matrices coarsened by the
// cell's local prolongation. Sub-tetrahedra with 6 |vol| <= 1e-8 longest_edge^3 add no stiffness.
void build(const Mesh& mesh, Eigen::SparseMatrix<double>& S, Eigen::SparseMatrix<double>& M);

}  // namespace plain_volume_reference
