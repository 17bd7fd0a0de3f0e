// operators/surface/gradient.h — gradient G = G^f P and divergence D = -G^T W (paper eq. 4, 17-18), so
// that the stiffness factors as S = D G.
//
// Vector fields live on the refined fan triangles, one per halfedge (face corner) h: the
// triangle (source(h), target(h), virtual vertex of face(h)). G is (3|H|) x |V|: rows 3h, 3h+1,
// 3h+2 are the x, y, z components of the constant gradient on fan triangle h. W is the
// diagonal of fan-triangle areas, each repeated three times. Degenerate fan triangles (see
// RefinementOptions) get zero gradient rows. Column-major sparse matrices.
#pragma once

#include "polydec/operators/surface/laplacian.h"

namespace polydec {

// Gradient, (3|H|) x |V|.
SparseMatrix gradient(const Mesh& mesh, const Refinement& refinement);

// Divergence D = -G^T W, |V| x (3|H|).
SparseMatrix divergence(const Mesh& mesh, const Refinement& refinement);

// Areas of the fan triangles, one per halfedge (0 for degenerate ones).
Eigen::VectorXd fan_areas(const Mesh& mesh, const Refinement& refinement);

}  // namespace polydec
