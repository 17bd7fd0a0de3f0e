// operators/surface/quadratic.h — the quadratic polygon Laplacian (beyond the paper;
// docs/extensions.md): S = P^T S^f P and M = P^T M^f P with P the quadratic prolongation
// (dec/surface/quadratic.h) and S^f, M^f the quadratic Lagrange (P2) stiffness and mass of the
// fan triangles, assembled face by face.
//
// Conventions as in operators/surface/laplacian.h: S symmetric NEGATIVE semi-definite (S 1 = 0),
// L = M^-1 S. Matrices are (|V| + |E|) x (|V| + |E|): the vertices in file order, then one dof per
// edge (its midpoint) in Mesh::edges() order. Degenerate fan triangles (RefinementOptions) add
// nothing.
#pragma once

#include "polydec/dec/surface/quadratic.h"
#include "polydec/operators/surface/laplacian.h"

namespace polydec {

struct QuadraticLaplacian {
  SparseMatrix S;  // stiffness, negative semi-definite
  SparseMatrix M;  // Galerkin mass
  // Lumped mass by diagonal scaling (Hinton, Rock & Zienkiewicz 1976) per face: face f's share of
  // dof k is its local mass diagonal (P_f^T M^f_f P_f)_kk times area_f / trace. Positive at every
  // dof of a face with positive area (row sums are not: on a triangle they vanish at the corners),
  // and each face's shares sum to its fan area. On a triangle: area/19 per corner, 16 area/57 per
  // edge midpoint.
  Eigen::VectorXd M_lumped;
  Eigen::MatrixX3d dofs;  // positions, quadratic_dof_positions(mesh)
  FanQuality quality;     // fan triangles of the refinement that was used
};

// One pass over the faces: per face the local prolongation (identity on its n corners and n edge
// midpoints, quadratic_face_weights for x_f and the spoke midpoints), the fan's P2 matrices, and
// P_f^T K P_f scattered into the global matrices.
QuadraticLaplacian assemble_quadratic_laplacian(const Mesh& mesh, const Refinement& refinement);

// With the default refinement (squared-area virtual vertices).
QuadraticLaplacian quadratic_laplacian(const Mesh& mesh);

// The gradient of the quadratic elements at the centroid of each fan triangle, 3|H| x (|V| + |E|)
// (rows 3h..3h+2 for the fan triangle of halfedge h, zero when it is degenerate, as gradient()
// numbers the linear one), and D = -G^T W with W the fan triangles' areas. For a field g constant
// on each fan triangle, -(D g)_i is exactly the integral of grad phi_i . g (grad phi_i is linear on
// the triangle, so its mean is its value at the centroid): the heat method's divergence (eq. 33).
struct QuadraticGradient {
  SparseMatrix G, D;
};
QuadraticGradient quadratic_gradient(const Mesh& mesh, const Refinement& refinement);

// The refined P2 matrices on the fan triangles, numbered as quadratic_prolongation's rows (for
// the explicit route S = P^T S^f P): S^f negative semi-definite, M^f the mass.
struct QuadraticRefinedMatrices {
  SparseMatrix S, M;
};
QuadraticRefinedMatrices quadratic_refined_matrices(const Mesh& mesh, const Refinement& refinement);

}  // namespace polydec
