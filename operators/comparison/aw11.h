// operators/comparison/aw11.h — the polygon Laplacian of Alexa & Wardetzky, "Discrete Laplacians on general
// polygonal meshes" (SIGGRAPH 2011), parameter lambda >= 0.
//
// Variant implemented (the one of the comparison code of Bunge et al., which the paper's authors
// distribute with their later work): per face with corners X (n x 3), cyclic difference d
// ((d u)_i = u_{i+1} - u_i), edge vectors E = d X, edge midpoints B, vector area a (|a| = A):
//   M_f = B B^T / A + lambda * K,   S_f = -d^T M_f d,
// where K is the orthogonal projector onto ker(E_flat^T), E_flat the edges projected to the plane
// orthogonal to a (the plane of largest projected area, which is how AW11 treats non-planar
// faces); B is not projected. The first term reproduces the Dirichlet energy A |grad u|^2 of
// linear u on planar faces; the second, of rank n - 2, vanishes on triangles, so on triangle
// meshes S is the cotangent Laplacian. The lumped mass is A / n per face corner (AW11 define no
// Galerkin mass). Gradient (following Crane et al. 2013, section 3.2.2, for AW11): on face f the
// n-vector G_f u = R_f d u / sqrt(A) with R_f^T R_f = M_f, so |G_f u| = |grad u| for linear u on
// planar faces (on non-planar ones, for lambda = 0, |grad u projected to the vector area's plane|);
// D = -G^T W with W = A per face; S = D G exactly. The heat method normalizes each face's n-vector
// as one block (OperatorSet::G_blocks). Conventions as in operators/surface/laplacian.h.
#pragma once

#include "polydec/operators/registry/laplacians.h"

namespace polydec {

// Cyclic difference of an n-gon's corners (n x n): row i = e_{i+1} - e_i, i.e. (d u)_i = u_{i+1} - u_i,
// the face's d0 restricted to its boundary cycle (used by AW11 and de Goes et al. 2020).
Eigen::MatrixXd cyclic_difference(int n);

// Local AW11 stiffness S_f (n x n, symmetric negative semi-definite) of one polygon.
Eigen::MatrixXd aw11_local_stiffness(const PolygonPositions& X, double lambda);

// Local inner product M_f (n x n, positive definite for lambda > 0) on the face's edge 1-forms.
Eigen::MatrixXd aw11_inner_product(const PolygonPositions& X, double lambda);

// S, lumped M, G (sum_f n_f rows), D and the G blocks on `mesh`. Throws InvalidMeshError for a
// face of zero vector area.
OperatorSet aw11_operators(const Mesh& mesh, double lambda, bool with_gradient = true);

}  // namespace polydec
