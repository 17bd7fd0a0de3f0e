// operators/surface/face_to_vertex.h — per-face values to per-vertex values by averaging over the
// faces around each vertex (unweighted), e.g. to draw a face quantity with a vertex colormap.
#pragma once

#include <Eigen/Core>

#include "polydec/dec/mesh/mesh.h"

namespace polydec {

// Vertex i gets the mean of face_values over the faces that contain it (0 at a vertex in no face).
// std::invalid_argument when face_values does not have one value per face.
Eigen::VectorXd face_to_vertex(const Mesh& mesh, const Eigen::VectorXd& face_values);

}  // namespace polydec
