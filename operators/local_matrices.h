// operators/local_matrices.h — per-face kernels: the coarsened stiffness and mass of one
// polygon, P_f^T S^f P_f and P_f^T M^f P_f (eq. 12-13), from its positions, its virtual-vertex
// weights and its fan-triangle classification. Pure functions; no mesh needed.
#pragma once

#include <Eigen/Core>

#include "dec/refinement.h"

namespace polydec {

// Half cotangents of the angles of triangle (p0, p1, p2): c[a] = cot(angle at corner a) / 2.
// The cotangent stiffness of the triangle is S_ab = c[3 - a - b] for a != b (eq. 3).
Eigen::Vector3d triangle_half_cotangents(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                         const Eigen::Vector3d& p2);

// Coarsened local stiffness S_f (n x n, negative semi-definite) and Galerkin mass M_f (n x n)
// of a polygon with corners X (n x 3), weights w and virtual point xf. Fan triangle k is
// (x_k, x_{k+1}, xf); fan[k] says whether it is degenerate (then it adds no stiffness).
// Either output may be null.
void polygon_matrices(const PolygonPositions& X, const Eigen::VectorXd& w, const Eigen::Vector3d& xf,
                      const FanTriangle* fan, Eigen::MatrixXd* S, Eigen::MatrixXd* M);

}  // namespace polydec
