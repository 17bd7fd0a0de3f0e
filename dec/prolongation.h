// dec/prolongation.h — prolongations from the coarse polygon mesh to its refined fan
// triangulation (paper eq. 11 and 24). Row-major or column-major as stated per function.
#pragma once

#include "dec/refinement.h"

#include <Eigen/Sparse>

namespace polydec {

// P0 = P (eq. 11, 24): (|V| + |F|) x |V|, identity on the original vertices, row |V| + f holds
// the virtual-vertex weights of face f. Column-major.
Eigen::SparseMatrix<double> prolongation(const Mesh& mesh, const Refinement& refinement);

}  // namespace polydec
