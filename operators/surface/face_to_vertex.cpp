// operators/surface/face_to_vertex.cpp — the unweighted face-to-vertex average.
#include "polydec/operators/surface/face_to_vertex.h"

#include <stdexcept>
#include <string>

namespace polydec {

Eigen::VectorXd face_to_vertex(const Mesh& mesh, const Eigen::VectorXd& face_values) {
  if (face_values.size() != mesh.n_faces())
    throw std::invalid_argument("face_to_vertex: " + std::to_string(face_values.size()) +
                                " values for a mesh of " + std::to_string(mesh.n_faces()) + " faces");
  Eigen::VectorXd v = Eigen::VectorXd::Zero(mesh.n_vertices()), count = v;
  for (int f = 0; f < mesh.n_faces(); ++f)
    for (int i : mesh.face(f)) v[i] += face_values[f], count[i] += 1;
  for (int i = 0; i < mesh.n_vertices(); ++i) v[i] = count[i] > 0 ? v[i] / count[i] : 0.0;
  return v;
}

}  // namespace polydec
