// apps/pictures/vector_field.h — a tangent vector field drawn as arrows over the rendered surface:
// one flat arrow (shaft quad + head triangle) per base point, lying in the plane of its face,
// lifted slightly off the surface, drawn by render() (apps/pictures/render.h) together with the
// mesh as one scene.
#pragma once

#include <string>

#include "polydec/apps/pictures/render.h"

namespace polydec {

struct ArrowOptions {
  double length = 0.8;  // the longest arrow, times the mean edge length
  double width = 0.12;  // shaft width, times the longest arrow's length
  double lift = 0.02;   // offset along the face normal, times the mean edge length
  Color color{0.05, 0.05, 0.05};
};

// The mesh with the per-vertex scalar `vertex_scalar` (|V| values or empty), and one arrow per
// face f from points(f) along vectors(f) (|F| x 3 each; projected to the face's plane), lengths
// proportional to |vectors(f)|. Throws std::invalid_argument on sizes that do not match.
void render_vector_field_png(const std::string& path, const Mesh& mesh, const Eigen::VectorXd& vertex_scalar,
                             const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& vectors,
                             RenderOptions render_options, const ArrowOptions& arrows = {});

}  // namespace polydec
