// operators/comparison/degoes20.h — the polygon operators of de Goes, Butts & Desbrun, "Discrete
// differential operators on polygonal meshes" (SIGGRAPH 2020), parameter lambda >= 0 (they
// recommend 1).
//
// Per face with corners X (n x 3), centroid c, vector area a (|a| = A, unit normal n), cyclic
// difference d, edge vectors E = d X, edge midpoints B:
//   gradient  G_f = (1/A) [n]_x (B - c)^T d  (3 x n; equals -(1/2A) n x (x_{i+1} - x_{i-1}) per corner),
//   sharp     U_f = (1/A) [n]_x (B - c)^T,  flat V_f = E (I - n n^T),  projection P_f = I - V_f U_f,
//   1-form inner product M_f = A U_f^T U_f + lambda P_f^T P_f,   S_f = -d^T M_f d.
// The lumped mass is A / n per face corner (the paper's vertex areas; no Galerkin mass is
// defined). D = -G^T W with W = A per face, so D G is the consistency part of S only: S = D G
// - lambda sum_f d^T P_f^T P_f d (P_f d vanishes on linear functions of planar faces and on every
// triangle, where S is the cotangent Laplacian). Conventions as in operators/surface/laplacian.h.
#pragma once

#include "polydec/operators/registry/laplacians.h"

namespace polydec {

// Local gradient G_f (3 x n) of one polygon.
Eigen::MatrixXd degoes20_local_gradient(const PolygonPositions& X);

// Local stiffness S_f (n x n, symmetric negative semi-definite) of one polygon.
Eigen::MatrixXd degoes20_local_stiffness(const PolygonPositions& X, double lambda);

// S, lumped M, G (3|F| x |V|), D on `mesh`. Throws InvalidMeshError for a face of zero vector area.
OperatorSet degoes20_operators(const Mesh& mesh, double lambda, bool with_gradient = true);

}  // namespace polydec
