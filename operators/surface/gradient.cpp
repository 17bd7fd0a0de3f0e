// operators/surface/gradient.cpp — gradient and divergence on the refined fan triangles.
#include "polydec/operators/surface/gradient.h"

#include <algorithm>
#include <vector>

#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/surface/whitney.h"

namespace polydec {

Eigen::VectorXd fan_areas(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "fan_areas");
  Eigen::VectorXd a(mesh.n_halfedges());
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    if (refinement.fan[h] == FanTriangle::Degenerate) {
      a[h] = 0.0;
      continue;
    }
    const Eigen::Vector3d xf = refinement.virtual_points.row(mesh.halfedge_face(h)).transpose();
    a[h] = 0.5 * (mesh.position(mesh.halfedge_source(h)) - xf)
                     .cross(mesh.position(mesh.halfedge_target(h)) - xf)
                     .norm();
  }
  return a;
}

namespace {

void advise(SparseMatrix& A) {
  advise_huge_pages(A.valuePtr(), sizeof(double) * size_t(A.nonZeros()));
  advise_huge_pages(A.innerIndexPtr(), sizeof(int) * size_t(A.nonZeros()));
}

// G^T (|V| x 3|H|, column-major), i.e. G in compressed row storage: column 3h + c (component c
// of the gradient on fan triangle h) holds one entry per corner of face(h), in ascending vertex
// order; degenerate fan triangles have empty columns. Written directly into the matrix's storage
// (huge pages, no triplets): with triplet lists and setFromTriplets, gradient() and divergence()
// took 0.6 + 1.0 s on FINE SPHERE, mostly page faults.
SparseMatrix gradient_transposed(const Mesh& mesh, const Refinement& refinement) {
  const int nh = mesh.n_halfedges();
  SparseMatrix T(mesh.n_vertices(), 3 * nh);
  int* outer = T.outerIndexPtr();
  outer[0] = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const int n = mesh.face_size(f), h0 = mesh.face_offsets()[f];
    for (int h = h0; h < h0 + n; ++h)
      for (int c = 0; c < 3; ++c)
        outer[3 * h + c + 1] = outer[3 * h + c] + (refinement.fan[h] == FanTriangle::Degenerate ? 0 : n);
  }
  T.resizeNonZeros(outer[3 * nh]);
  advise(T);
  int* inner = T.innerIndexPtr();
  double* values = T.valuePtr();
  std::vector<int> order;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size()), h0 = mesh.face_offsets()[f];
    order.resize(size_t(n));
    for (int m = 0; m < n; ++m) order[size_t(m)] = m;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return face[a] < face[b]; });
    const Eigen::Vector3d xf = refinement.virtual_points.row(f).transpose();
    for (int k = 0; k < n; ++k) {
      const int h = h0 + k;
      if (refinement.fan[h] == FanTriangle::Degenerate) continue;
      const int i = face[k], j = face[(k + 1) % n];
      const Eigen::Matrix3d G = hat_gradients(mesh.position(i), mesh.position(j), xf);
      const Eigen::Vector3d g[3] = {G.col(0), G.col(1), G.col(2)};
      // Coarse vertex c contributes [c == i] g0 + [c == j] g1 + w_c g2.
      for (int e = 0; e < n; ++e) {
        const int m = order[size_t(e)];
        const Eigen::Vector3d gm = refinement.weights[h0 + m] * g[2] +
                                   (m == k ? g[0] : Eigen::Vector3d::Zero()) +
                                   (m == (k + 1) % n ? g[1] : Eigen::Vector3d::Zero());
        for (int c = 0; c < 3; ++c) {
          inner[outer[3 * h + c] + e] = face[m];
          values[outer[3 * h + c] + e] = gm[c];
        }
      }
    }
  }
  return T;
}

}  // namespace

SparseMatrix gradient(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "gradient");
  const SparseMatrix T = gradient_transposed(mesh, refinement);
  // Transpose by counting sort: rows ascending within each column, as setFromTriplets leaves them.
  SparseMatrix G(T.cols(), T.rows());
  int* outer = G.outerIndexPtr();
  for (Eigen::Index k = 0; k < T.nonZeros(); ++k) ++outer[T.innerIndexPtr()[k] + 1];
  for (Eigen::Index v = 0; v < G.cols(); ++v) outer[v + 1] += outer[v];
  G.resizeNonZeros(T.nonZeros());
  advise(G);
  std::vector<int> next(outer, outer + G.cols());
  for (Eigen::Index r = 0; r < T.cols(); ++r)
    for (int k = T.outerIndexPtr()[r]; k < T.outerIndexPtr()[r + 1]; ++k) {
      const int at = next[size_t(T.innerIndexPtr()[k])]++;
      G.innerIndexPtr()[at] = int(r);
      G.valuePtr()[at] = T.valuePtr()[k];
    }
  return G;
}

SparseMatrix divergence(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "divergence");
  // D = -G^T W: G^T with column 3h + c scaled by -area(h).
  SparseMatrix D = gradient_transposed(mesh, refinement);
  const Eigen::VectorXd a = fan_areas(mesh, refinement);
  for (Eigen::Index r = 0; r < D.cols(); ++r)
    for (int k = D.outerIndexPtr()[r]; k < D.outerIndexPtr()[r + 1]; ++k)
      D.valuePtr()[k] = -(a[r / 3] * D.valuePtr()[k]);
  return D;
}

}  // namespace polydec
