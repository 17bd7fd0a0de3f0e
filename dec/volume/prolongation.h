// dec/volume/prolongation.h — the prolongation of vertex values to the polyhedral refinement's
// points (the 3D analogue of paper eq. 11): mesh vertices <- face points <- cell points, composed.
#pragma once

#include <Eigen/Sparse>

#include "polydec/dec/volume/refinement.h"

namespace polydec {

// P: (|V| + |F| + |C|) x |V|; identity on the mesh vertices, row |V| + f the face weights, row
// |V| + |F| + c the cell weights (already expressed in vertices). Throws std::invalid_argument when
// the refinement is not the mesh's.
Eigen::SparseMatrix<double> volume_prolongation(const VolumeMesh& mesh, const VolumeRefinement& refinement);

}  // namespace polydec
