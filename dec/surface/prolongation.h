// dec/surface/prolongation.h — prolongations from the coarse polygon mesh to its refined fan
// triangulation (paper eq. 11, 24-26): P0 for 0-forms, P1 for 1-forms, P2 for 2-forms.
// Column-major sparse matrices. Cell numbering and orientation: dec/surface/complex.h.
//
// P1 and P2 are the antisymmetrised forms of eq. 25-26 (derivation in docs/feec.md): with the
// coarse hats phi_i = sum_k P_ki phi^f_k, the Whitney forms satisfy
//   phi_ij  = sum_{k<l}   (P_ki P_lj - P_li P_kj)      phi^f_kl,
//   phi_ijk = sum_{k<l<m} det[P_{(klm),(ijk)}]          phi^f_klm,
// for coarse cells i<j (i<j<k) and refined cells k<l (k<l<m), all oriented by increasing index.
#pragma once

#include <Eigen/Sparse>

#include "polydec/dec/surface/complex.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec {

// P0 = P (eq. 11, 24): (|V| + |F|) x |V|, identity on the original vertices, row |V| + f holds
// the virtual-vertex weights of face f.
Eigen::SparseMatrix<double> prolongation(const Mesh& mesh, const Refinement& refinement);

// P1: (|E| + |H|) x |C1|. A mesh-edge row is the unit row of its pair; the row of the spoke
// (a, v_f) holds sign(b - a) w_b in the column of pair {a, b}, for every other corner b of f.
Eigen::SparseMatrix<double> prolongation1(const Mesh& mesh, const Refinement& refinement,
                                          const CoarseComplex& complex);

// P2: |H| x |C2|. The row of refined triangle (a, b, v_f), a < b, holds +-w_c in the column of
// triple {a, b, c} for every other corner c of f: + when c < a or c > b, - when a < c < b.
Eigen::SparseMatrix<double> prolongation2(const Mesh& mesh, const Refinement& refinement,
                                          const CoarseComplex& complex);

}  // namespace polydec
