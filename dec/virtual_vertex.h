// dec/virtual_vertex.h — per-polygon virtual-vertex weights (paper section 4.2, eq. 10, 15-16,
// Appendix A). Pure functions of the polygon's positions: unit-testable on a single polygon.
#pragma once

#include <Eigen/Core>
#include <string>

namespace polydec {

// Positions of one polygon's corners, n x 3, in face order.
using PolygonPositions = Eigen::Matrix<double, Eigen::Dynamic, 3>;

// How the virtual vertex of a face is placed.
enum class VirtualVertexRule {
  SquaredArea,  // minimizer of the sum of squared fan-triangle areas, least-norm affine weights (eq. 16)
  Centroid,     // uniform weights 1/n
};

// Parses "squared-area" / "centroid"; throws std::invalid_argument otherwise.
VirtualVertexRule parse_virtual_vertex_rule(const std::string& name);
std::string to_string(VirtualVertexRule rule);

// Least-norm affine weights w (sum 1) of the point minimizing sum_i area(x_i, x_{i+1}, x)^2
// (eq. 16 and 38). Computed in centred coordinates so that the result does not depend on where
// the polygon sits or how large it is: the minimizer solves a 3x3 system, and the least-norm
// weights reproducing it come from the pseudo-inverse of the centred positions, whose rank
// (2 for planar, 3 for non-planar polygons) is decided relative to the polygon's own extent.
Eigen::VectorXd squared_area_weights(const PolygonPositions& X);
// The same weights without allocating: x holds the n corners row by row (x[3k..3k+2]), the
// n weights are written to w; `work` needs 3n doubles of scratch. For per-face inner loops.
void squared_area_weights(const double* x, int n, double* w, double* work);

// Uniform weights 1/n.
Eigen::VectorXd centroid_weights(int n);

// Dispatch on the rule.
Eigen::VectorXd virtual_vertex_weights(const PolygonPositions& X, VirtualVertexRule rule);

}  // namespace polydec
