// dec/surface/virtual_vertex.h — per-polygon virtual-vertex weights (paper section 4.2, eq. 10, 15-16,
// Appendix A; the variants of section 5.7; the trace minimizer of Bunge et al., "Polygon
// Laplacian Made Robust", EG 2024). Pure functions of the polygon's positions: unit-testable on
// a single polygon.
#pragma once

#include "polydec/dec/mesh/eigen_abi.h"
#include <Eigen/Core>
#include <string>

namespace polydec {

// Positions of one polygon's corners, n x 3, in face order.
using PolygonPositions = Eigen::Matrix<double, Eigen::Dynamic, 3>;

// How the virtual vertex of a face is placed.
enum class VirtualVertexRule {
  SquaredArea,  // minimizer of the sum of squared fan-triangle areas, least-norm affine weights (eq. 16)
  Centroid,     // uniform weights 1/n
  AbsArea,   // minimizer of the sum of absolute fan-triangle areas (section 4.2), least-norm affine weights
  Convex,    // squared-area minimizer over convex weights (w >= 0, sum 1; section 4.2)
  TraceMin,  // minimizer of the fan's stiffness trace, harmonic weights (Bunge et al. 2024)
};

// How the rank of a polygon's centred corners (2: planar, 3: non-planar) is decided for the
// least-norm weights (eq. 16): the paper's definition (exact arithmetic) wherever the data can
// tell. A polygon counts as planar when its smallest singular value is within what the corners'
// uncertainty allows (sqrt(3n) noise, plus a few n eps of the largest singular value for the
// round-off of the computation); with `relative` > 0, when it is at most `relative` times the
// largest (the fixed cut of earlier versions: 1e-5).
struct PlanarityCut {
  double noise =
      -1.0;  // absolute uncertainty of each corner coordinate; < 0: double round-off of the corners
  double relative = 0.0;  // > 0: overrides `noise`
};

// The planarity decision of a mesh's polygon with the n corners x (row by row): `tolerance` when
// > 0 (a user's or the mesh's planarity tolerance), else the mesh's absolute coordinate noise
// (CoordinatePrecision::noise times the mesh's rms radius) or the corners' own double round-off,
// whichever is larger. Shared by the surface and volume refinements.
PlanarityCut planarity_cut(double tolerance, double noise, const double* x, int n);

// Parses "squared-area" (or "affine"), "centroid", "abs-area", "convex", "trace-min"; throws
// std::invalid_argument otherwise.
VirtualVertexRule parse_virtual_vertex_rule(const std::string& name);
std::string to_string(VirtualVertexRule rule);

// Least-norm affine weights w (sum 1) of the point minimizing sum_i area(x_i, x_{i+1}, x)^2
// (eq. 16 and 38). Computed in centred coordinates (two-pass mean) so that the result does not
// depend on where the polygon sits or how large it is: the minimizer solves a 3x3 system (LDL^T,
// or an eigen-decomposition when it is ill-conditioned), and the least-norm weights reproducing
// it come from the pseudo-inverse of the centred positions (Householder QR, then R^-T or the SVD
// of R; for a polygon planar to round-off, the 2x2 Gram matrix in its plane), whose rank (2 for
// planar, 3 for non-planar polygons) `planarity` decides (default: the corners are exact doubles,
// so only round-off counts as planar). No allocation in the pointer version below.
Eigen::VectorXd squared_area_weights(const PolygonPositions& X, const PlanarityCut& planarity = {});
// The same weights without allocating: x holds the n corners row by row (x[3k..3k+2]), the
// n weights are written to w; `work` needs 3n doubles of scratch. For per-face inner loops.
void squared_area_weights(const double* x, int n, double* w, double* work,
                          const PlanarityCut& planarity = {});

// Uniform weights 1/n.
Eigen::VectorXd centroid_weights(int n);

// Least-norm affine weights of the point minimizing the sum of absolute fan areas
// sum_i area(x_i, x_{i+1}, x) (areas measured in 3D). The objective is convex but not strictly:
// for a convex planar polygon every interior point is a minimizer, for a star-shaped one every
// point of its kernel. Iteratively reweighted least squares on sum_i sqrt(|c_i|^2 + eps^2) (c_i
// twice the area vector of fan triangle i), eps decreasing from 1e-2 to 1e-7 of the polygon's
// squared size, starting at the centroid; the centroid is kept unless a point improves the true
// objective by more than 1e-12 of it (so convex polygons keep their centroid).
Eigen::VectorXd abs_area_weights(const PolygonPositions& X, const PlanarityCut& planarity = {});

// Convex weights (w >= 0, sum w = 1) minimizing the sum of squared fan areas of x = X^T w, with
// ties (the objective has rank <= 3 in w) broken towards the least-norm w by a Tikhonov term
// 1e-9 * mean(diag H) * |w|^2 on the n x n Hessian H. Solved exactly by a primal active-set
// method on the simplex (finite; at most 10 n iterations), each step a Tikhonov least-squares
// problem on the 3 x n factor of H (by SVD: the normal equations' condition number 1e9 would cost
// seven digits). Equals squared_area_weights() when those are non-negative, up to the Tikhonov term.
Eigen::VectorXd convex_weights(const PolygonPositions& X);

// The virtual vertex of Bunge et al. 2024: in the plane orthogonal to the polygon's vector area,
// the point p minimizing the trace of the refined fan stiffness, sum_i cot-sum of fan triangle i
// = sum_i (|x_i - p|^2 + |x_{i+1} - p|^2 + |x_{i+1} - x_i|^2) / (4 area_i(p)), a convex barrier
// function on the polygon's kernel, by damped Newton from the squared-area point (or from the
// kernel's centroid when that point is outside the kernel). Weights are the harmonic (cotangent)
// weights of p in its fan, which reproduce p for planar polygons. Falls back to
// squared_area_weights() when the projected polygon has no kernel (not star-shaped) or when the
// fallback's coarsened stiffness has the smaller trace.
Eigen::VectorXd trace_min_weights(const PolygonPositions& X, const PlanarityCut& planarity = {});

// Trace of the positive semi-definite coarsened fan stiffness -P_f^T S^f P_f of polygon X with
// virtual-vertex weights w (eq. 12), fan triangles (x_i, x_{i+1}, x_f) with x_f = X^T w; +infinity
// when a fan triangle has zero area.
double coarse_stiffness_trace(const PolygonPositions& X, const Eigen::VectorXd& w);

// Dispatch on the rule.
Eigen::VectorXd virtual_vertex_weights(const PolygonPositions& X, VirtualVertexRule rule,
                                       const PlanarityCut& planarity = {});

}  // namespace polydec
