// dec/prolongation.cpp — P0 (eq. 11).
#include "dec/prolongation.h"

namespace polydec {

Eigen::SparseMatrix<double> prolongation(const Mesh& mesh, const Refinement& refinement) {
  const int nv = mesh.n_vertices(), nf = mesh.n_faces();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(nv + mesh.n_halfedges());
  for (int v = 0; v < nv; ++v) t.emplace_back(v, v, 1.0);
  for (int h = 0; h < mesh.n_halfedges(); ++h)
    t.emplace_back(nv + mesh.halfedge_face(h), mesh.halfedge_source(h), refinement.weights[h]);
  Eigen::SparseMatrix<double> P(nv + nf, nv);
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

}  // namespace polydec
