// dec/volume/prolongation.cpp — the composed vertex prolongation of a polyhedral refinement.
#include "polydec/dec/volume/prolongation.h"

#include <vector>

namespace polydec {

Eigen::SparseMatrix<double> volume_prolongation(const VolumeMesh& mesh, const VolumeRefinement& refinement) {
  check_refinement(mesh, refinement, "volume_prolongation");
  const int nV = mesh.n_vertices(), nF = mesh.n_faces(), nC = mesh.n_cells();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(size_t(nV) + mesh.face_indices().size() + refinement.cell_weights.size());
  for (int v = 0; v < nV; ++v) t.emplace_back(v, v, 1.0);
  for (int f = 0; f < nF; ++f) {
    const auto face = mesh.face(f);
    const auto w = refinement.weights_of_face(mesh, f);
    for (size_t k = 0; k < face.size(); ++k) t.emplace_back(nV + f, face[k], w[k]);
  }
  for (int c = 0; c < nC; ++c) {
    const auto verts = mesh.cell_vertices(c);
    const auto w = refinement.weights_of_cell(c);
    for (size_t k = 0; k < verts.size(); ++k) t.emplace_back(nV + nF + c, verts[k], w[k]);
  }
  Eigen::SparseMatrix<double> P(nV + nF + nC, nV);
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

}  // namespace polydec
