// dec/surface/quadratic.h — quadratic (P2) elements on the virtual refinement, beyond the paper
// (its section 6 asks for higher-order bases; docs/extensions.md): coarse degrees of freedom at
// the vertices and edge midpoints, quadratic Lagrange elements on the fan triangles, and the
// prolongation that reproduces every quadratic polynomial of a face's plane.
//
// Numbering. Coarse dofs: vertex v is dof v, edge e (Mesh::edges() order) is dof |V| + e.
// Refined nodes: the |V| + |E| coarse dofs (each maps to itself), then the virtual vertex of
// face f at |V| + |E| + f, then the spoke midpoint (x_h + x_f) / 2 of halfedge h (corner h of
// its face) at |V| + |E| + |F| + h.
#pragma once

#include <Eigen/Sparse>

#include "polydec/dec/surface/refinement.h"

namespace polydec {

// The quadratic Lagrange triangle with corners p0, p1, p2 (3-D): nodes 0..2 the corners, 3, 4, 5
// the midpoints of edges (0,1), (1,2), (2,0); basis l_i (2 l_i - 1) and 4 l_i l_j in barycentric
// coordinates l. Stiffness K_ab = int grad phi_a . grad phi_b (positive semi-definite, exact by
// the three-edge-midpoint rule, the integrand being quadratic); mass M_ab = int phi_a phi_b
// (the closed form area/180 [6 -1 -1 0 -4 0; ... 32 16 16], exact). A zero-area triangle gives
// a zero stiffness.
using Matrix6d = Eigen::Matrix<double, 6, 6>;
Matrix6d p2_triangle_stiffness(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                               const Eigen::Vector3d& p2);
Matrix6d p2_triangle_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2);

// The six P2 basis values at barycentric point l (node order as above).
Eigen::Matrix<double, 6, 1> p2_basis(const Eigen::Vector3d& l);
// Their gradients (rows, 3-D, in the triangle's plane) at barycentric point l of the triangle
// p0, p1, p2; zero for a zero-area triangle.
Eigen::Matrix<double, 6, 3> p2_basis_gradients(const Eigen::Vector3d& l, const Eigen::Vector3d& p0,
                                               const Eigen::Vector3d& p1, const Eigen::Vector3d& p2);

// The per-face weights of the quadratic prolongation: (n + 1) x 2n, row 0 the virtual vertex
// x_f, row 1 + k the spoke midpoint (x_k + x_f) / 2; columns 0..n-1 the corners, n + k the
// midpoint of edge (k, k+1). Among all weights with sum_j c_j q(y_j) = q(z) for every quadratic
// polynomial q of the face's best-fit plane (least-squares plane of the corners; nodes y_j and
// targets z projected onto it), the minimum-norm ones (the pseudo-inverse of the 6 x 2n
// Vandermonde matrix of 1, u, v, u^2, uv, v^2; rank 6 whenever the edges span three or more
// lines). Invariant under affine maps of the plane (they preserve quadratics), so under the
// polygon's position, size and the frame chosen. For a triangle they are the P2 basis values.
// `xf` is the virtual vertex (Refinement::virtual_points), used in 3-D for the elements. A polygon
// whose corners coincide gets uniform weights 1 / (2n).
Eigen::MatrixXd quadratic_face_weights(const PolygonPositions& X, const Eigen::Vector3d& xf);

// Positions of the coarse dofs, (|V| + |E|) x 3: the vertices, then the edge midpoints.
Eigen::MatrixX3d quadratic_dof_positions(const Mesh& mesh);

// Positions of the refined nodes, (|V| + |E| + |F| + |H|) x 3, numbered as above.
Eigen::MatrixX3d quadratic_refined_positions(const Mesh& mesh, const Refinement& refinement);

// The quadratic prolongation P: (|V| + |E| + |F| + |H|) x (|V| + |E|), identity on the coarse
// dofs, rows of the virtual vertices and spoke midpoints from quadratic_face_weights.
Eigen::SparseMatrix<double> quadratic_prolongation(const Mesh& mesh, const Refinement& refinement);

}  // namespace polydec
