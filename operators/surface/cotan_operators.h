// operators/surface/cotan_operators.h — the cotangent operators of explicit triangles (paper eq. 2-3):
// stiffness S, Galerkin mass M, lumped mass (row sums of M, i.e. area/3 per corner), and the
// per-triangle gradient G with divergence D = -G^T W, so that S = D G. The kernel of the split
// operators (operators/surface/split_laplacian.h) and of the triangulation-based comparison
// Laplacians (operators/comparison/cotan.h, which includes this header).
//
// Conventions as in operators/surface/laplacian.h: S symmetric NEGATIVE semi-definite, S 1 = 0,
// |V| x |V|; G is 3|T| x |V| (rows 3t..3t+2: the gradient on triangle t), W the diagonal of
// triangle areas repeated three times. A triangle is degenerate when twice its area is at most
// `degenerate_tolerance` times its longest squared edge (scale-free); degenerate triangles add
// no stiffness and get zero gradient rows.
#pragma once

#include <vector>

#include "polydec/operators/surface/laplacian.h"

namespace polydec {

struct TriangleOperators {
  SparseMatrix S, M;
  Eigen::VectorXd M_lumped;
  SparseMatrix G, D;     // empty unless asked for
  int n_degenerate = 0;  // triangles treated as degenerate
};

// Triangles given only by their edge lengths (an intrinsic triangulation): triangle t has corners
// triangles[t] and lengths[t][k] = length of the edge from corner k to corner k+1.
struct LengthTriangles {
  int n_vertices = 0;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<Eigen::Vector3d> lengths;
};

// Cotangent operators of a triangle mesh (throws std::invalid_argument for a non-triangle face).
// G holds world-space gradients.
TriangleOperators cotan_operators(const Mesh& triangles, bool with_gradient = true,
                                  double degenerate_tolerance = 1e-10);

// The same for triangles over `positions` (|V| x 3) that need not form a valid mesh (e.g. a
// triangulation whose triangles fold over a neighbour). Throws std::out_of_range for a bad index.
TriangleOperators cotan_operators(const Eigen::MatrixX3d& positions,
                                  const std::vector<Eigen::Vector3i>& triangles, bool with_gradient = true,
                                  double degenerate_tolerance = 1e-10);

// Cotangent operators from edge lengths only. G holds each triangle's gradient in its own
// orthonormal 2D frame (corner 0 at the origin, corner 1 on the x axis; z component 0): norms and
// D = -G^T W, hence S = D G and the heat method, do not depend on the frame.
TriangleOperators cotan_operators(const LengthTriangles& triangles, bool with_gradient = true,
                                  double degenerate_tolerance = 1e-10);

// Area of a triangle with side lengths a, b, c (Kahan's stable Heron formula; 0 if the lengths
// violate the triangle inequality).
double triangle_area_from_lengths(double a, double b, double c);

}  // namespace polydec
