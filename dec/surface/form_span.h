// dec/surface/form_span.h — working with star1 and star2 on their span (docs/feec.md, "Rank").
//
// The coarsened Whitney k-forms (k = 1, 2) of a polygon mesh are linearly dependent as soon as
// faces have 5 (k = 1) or 4 (k = 2) corners: star_k = P_k^T star_k^f P_k is then singular, with
// null space ker P_k (cochains whose Whitney form is zero). A k-cochain x stands for the Whitney
// form P_k x; x and x + z, z in ker P_k, are the same form.
//
// The reduced basis: a subset of the coarse k-cells whose Whitney forms are linearly
// independent and span all Whitney k-forms. For k = 1 it holds every mesh edge and, per face,
// the polygon diagonals picked by column-pivoted QR of the face's spoke rows of P1; for k = 2
// the triples picked by column-pivoted QR of the face's rows of P2. Faces that share a
// diagonal (or triple) are treated together. A pivot counts when it exceeds `tolerance` times
// the largest pivot of its block (P_k entries are weights, dimensionless: the choice is
// independent of the mesh's scale). Rows of refined cells without mass (degenerate fan
// triangles, spokes between two of them) are left out, so the rank is that of star_k. With R
// the |C_k| x r selection matrix, R^T star_k R is symmetric positive definite and sparse (the
// one exception: a mesh edge whose fan triangles are all degenerate, then it is singular);
// operators/solvers/span_solver.h factors it.
#pragma once

#include <Eigen/Sparse>

#include "polydec/dec/surface/complex.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec {

struct FormSpan {
  int degree = 1;
  double tolerance = 1e-10;
  std::vector<int> cells;         // selected coarse k-cells, ascending
  Eigen::SparseMatrix<double> R;  // |C_k| x rank(), column c is the unit vector of cells[c]
  int rank() const { return int(cells.size()); }
};

// The reduced basis of the Whitney `degree`-forms (1 or 2; throws std::invalid_argument otherwise).
FormSpan form_span(const Mesh& mesh, const Refinement& refinement, const CoarseComplex& complex, int degree,
                   double tolerance = 1e-10);

}  // namespace polydec
