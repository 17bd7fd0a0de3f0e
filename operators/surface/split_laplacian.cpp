// operators/surface/split_laplacian.cpp — S, M, G, D through the explicit refined triangles of the pieces.
#include "polydec/operators/surface/split_laplacian.h"

#include "polydec/operators/surface/cotan_operators.h"
#include "polydec/operators/surface/gradient.h"

namespace polydec {

SplitLaplacian split_laplacian(const Mesh& mesh, bool with_gradient, const SplitOptions& options) {
  SplitLaplacian L;
  L.split = split_refine(mesh, options);
  L.P = split_prolongation(mesh, L.split);
  if (L.split.n_faces_split == 0) {  // one piece per face: the paper's fast path
    RefinementOptions ro;
    ro.degenerate_tolerance = options.degenerate_tolerance;
    const Refinement r = refine(mesh, ro);
    Laplacian A = assemble_laplacian(mesh, r);
    L.S.swap(A.S);
    L.M.swap(A.M);
    L.M_lumped = std::move(A.M_lumped);
    if (with_gradient) {
      SparseMatrix G = gradient(mesh, r), D = divergence(mesh, r);
      L.G.swap(G);
      L.D.swap(D);
    }
    return L;
  }
  TriangleOperators T = cotan_operators(split_positions(mesh, L.split), split_triangles(mesh, L.split), with_gradient,
                                        options.degenerate_tolerance);
  const SparseMatrix Pt = L.P.transpose();
  const SparseMatrix S = Pt * T.S * L.P, M = Pt * T.M * L.P;
  // Symmetric to the last bit (the products round the two triangles of a pair differently).
  L.S = 0.5 * (S + SparseMatrix(S.transpose()));
  L.M = 0.5 * (M + SparseMatrix(M.transpose()));
  L.M_lumped = L.M * Eigen::VectorXd::Ones(mesh.n_vertices());
  if (with_gradient) {
    L.G = T.G * L.P;
    L.D = Pt * T.D;
  }
  return L;
}

}  // namespace polydec
