// dec/surface/prolongation.cpp — P0 (eq. 11), P1 and P2 (antisymmetrised eq. 25-26).
#include "polydec/dec/surface/prolongation.h"

namespace polydec {

using Triplet = Eigen::Triplet<double>;

Eigen::SparseMatrix<double> prolongation(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "prolongation");
  const int nv = mesh.n_vertices(), nf = mesh.n_faces();
  std::vector<Triplet> t;
  t.reserve(nv + mesh.n_halfedges());
  for (int v = 0; v < nv; ++v) t.emplace_back(v, v, 1.0);
  for (int h = 0; h < mesh.n_halfedges(); ++h)
    t.emplace_back(nv + mesh.halfedge_face(h), mesh.halfedge_source(h), refinement.weights[h]);
  Eigen::SparseMatrix<double> P(nv + nf, nv);
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

Eigen::SparseMatrix<double> prolongation1(const Mesh& mesh, const Refinement& refinement,
                                          const CoarseComplex& complex) {
  check_refinement(mesh, refinement, "prolongation1");
  const int ne = mesh.n_edges();
  std::vector<Triplet> t;
  t.reserve(ne + size_t(mesh.n_halfedges()) * size_t(mesh.max_face_size()));
  for (int e = 0; e < ne; ++e)
    t.emplace_back(e, complex.pair_index(mesh.edges()(e, 0), mesh.edges()(e, 1)), 1.0);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const int h0 = mesh.face_offsets()[f];
    const auto face = mesh.face(f);
    for (size_t a = 0; a < face.size(); ++a)
      for (size_t b = 0; b < face.size(); ++b) {
        if (a == b) continue;
        // P_a,i P_v,j - P_v,i P_a,j for the pair {face[a], face[b]}.
        const double w = refinement.weights[h0 + b];
        t.emplace_back(ne + h0 + int(a), complex.pair_index(face[a], face[b]), face[b] > face[a] ? w : -w);
      }
  }
  Eigen::SparseMatrix<double> P1(ne + mesh.n_halfedges(), complex.n_pairs());
  P1.setFromTriplets(t.begin(), t.end());
  return P1;
}

Eigen::SparseMatrix<double> prolongation2(const Mesh& mesh, const Refinement& refinement,
                                          const CoarseComplex& complex) {
  check_refinement(mesh, refinement, "prolongation2");
  std::vector<Triplet> t;
  t.reserve(size_t(mesh.n_halfedges()) * size_t(mesh.max_face_size()));
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    const int f = mesh.halfedge_face(h), h0 = mesh.face_offsets()[f];
    const int s = mesh.halfedge_source(h), e = mesh.halfedge_target(h);
    const int a = std::min(s, e), b = std::max(s, e);
    const auto face = mesh.face(f);
    for (size_t k = 0; k < face.size(); ++k) {
      const int c = face[k];
      if (c == a || c == b) continue;
      // det [e_a; e_b; w] on the columns (i, j, k) of the sorted triple {a, b, c}.
      const double w = refinement.weights[h0 + k];
      t.emplace_back(h, complex.triple_index(a, b, c), (c > a && c < b) ? -w : w);
    }
  }
  Eigen::SparseMatrix<double> P2(mesh.n_halfedges(), complex.n_triples());
  P2.setFromTriplets(t.begin(), t.end());
  return P2;
}

}  // namespace polydec
