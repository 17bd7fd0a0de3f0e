// operators/surface/split_laplacian.h — the paper's operators with several virtual vertices in a face
// (dec/surface/split_refinement.h): S = P^T S^f P, M = P^T M^f P, G = G^f P, D = -G^T W = P^T D^f,
// with S^f, M^f, G^f, D^f the cotangent operators (operators/surface/cotan_operators.h) of the refined
// triangles of the pieces' fans. A mesh whose faces all stay one piece (every convex mesh) gets the
// paper's operators from its fast path, bit for bit.
//
// Conventions as in operators/surface/laplacian.h: S symmetric NEGATIVE semi-definite, S 1 = 0,
// |V| x |V|; lumped M = row sums of M; G is 3|T| x |V| (one 3-vector per refined triangle; with no
// face split: one per halfedge, as operators/surface/gradient.h).
#pragma once

#include "polydec/dec/surface/split_refinement.h"
#include "polydec/operators/surface/laplacian.h"

namespace polydec {

struct SplitLaplacian {
  SparseMatrix S, M;
  Eigen::VectorXd M_lumped;
  SparseMatrix G, D;  // empty unless asked for
  SparseMatrix P;     // (|V| + pieces) x |V|, split_prolongation
  SplitRefinement split;
};

// The operators of the split refinement of `mesh` (split_refine with `options`).
SplitLaplacian split_laplacian(const Mesh& mesh, bool with_gradient = true, const SplitOptions& options = {});

}  // namespace polydec
