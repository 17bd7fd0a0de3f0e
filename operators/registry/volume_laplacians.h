// operators/registry/volume_laplacians.h — the Laplacians polydec offers on polyhedral volume meshes, behind
// the OperatorSet interface of operators/registry/laplacians.h, selectable by name
// (`--laplacian NAME` of the volume commands):
//   ours          S, M of operators/volume/laplacian.h with the least-norm cell-point weights
//                 (CellPointRule::SquaredVolume, the default)
//   polylaplace   the same with polyLaplace's cell-point weights (CellPointRule::PolyLaplace)
//   diamond       the Diamond Laplacian of Bunge, Botsch & Alexa 2021 (operators/comparison/volume_diamond.h;
//                 its G has 3 rows per sub-diamond, not per sub-tetrahedron)
// Both come with a gradient and divergence (below), so the heat method applies.
//
// Gradient: vector fields live on the sub-tetrahedra of the refinement (dec/volume/refinement.h,
// order of refined_tets). G = G^tet P is (3T) x |V|: rows 3t..3t+2 the constant gradient of the
// linear element of sub-tetrahedron t applied to the prolongated values P u; degenerate
// sub-tetrahedra get zero rows. D = -G^T W with W the sub-tetrahedron volumes (0 for degenerate
// ones), each repeated three times, so that S = D G (the 3D eq. 17-18).
//
// The returned OperatorSet has no surface `domain` (an empty Mesh); n_input_vertices = |V|,
// mean_edge_length that of the volume mesh, `quality` unused (sub-tetrahedron counts are in
// `sub_tet_quality`, the refinement in `volume_refinement` when asked for). Conventions as on
// surfaces: S symmetric negative semi-definite.
#pragma once

#include <string>
#include <vector>

#include "polydec/dec/volume/refinement.h"
#include "polydec/operators/registry/laplacians.h"
#include "polydec/operators/volume/laplacian.h"

namespace polydec {

// Names of the volume methods, for help texts.
std::vector<std::string> volume_laplacian_names();

// Parses a volume method name (no parameters are defined); throws std::invalid_argument naming
// the known methods.
LaplacianChoice parse_volume_laplacian(const std::string& spec);

// What build_volume_operators builds besides S, M and the lumped M, and how (the fields shared with
// OperatorOptions mean the same).
struct VolumeOperatorOptions {
  bool with_gradient = true;     // G and D too
  int threads = 1;               // refinement and assembly threads of "ours" and "polylaplace" (0: all
                                 // hardware threads); the results do not depend on it
  bool keep_refinement = false;  // OperatorSet::volume_refinement receives the refinement used
  // A refinement of the mesh (refine_volume) to use instead of building one, e.g. a caller's cached
  // one; its cell-point rule must be the method's (ours and diamond: squared-volume, polylaplace:
  // polylaplace) and its tolerances the defaults, else std::invalid_argument, as for a refinement of
  // another mesh (check_refinement).
  // The operators equal those built from a fresh refinement with the same rule, bit for bit.
  const VolumeRefinement* refinement = nullptr;
};

// Builds the operator set of `choice` on `mesh`, e.g.
//   build_volume_operators(mesh, parse_volume_laplacian("ours"), {.with_gradient = false, .threads = 0});
// OperatorSet::sub_tet_quality holds the refinement's sub-tetrahedron counts. Throws
// std::invalid_argument for a method that is not a volume method.
OperatorSet build_volume_operators(const VolumeMesh& mesh, const LaplacianChoice& choice,
                                   const VolumeOperatorOptions& options = {});

// Gradient G = G^tet P, (3T) x |V| (T = number of sub-tetrahedra), see above; with `volumes`, also
// the sub-tetrahedra's volumes from the same pass (as sub_tet_volumes).
SparseMatrix volume_gradient(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                             Eigen::VectorXd* volumes = nullptr);

// Volumes of the sub-tetrahedra (absolute; 0 for degenerate ones), order of refined_tets.
Eigen::VectorXd sub_tet_volumes(const VolumeMesh& mesh, const VolumeRefinement& refinement);

// Divergence D = -G^T W, |V| x (3T).
SparseMatrix volume_divergence(const SparseMatrix& G, const Eigen::VectorXd& sub_tet_volumes);

}  // namespace polydec
