// dec/volume/refinement.h — the virtual refinement of a polyhedral mesh (the 3D analogue
// of paper section 4.1): one virtual point per face (the surface rule, eq. 10 and 16) and one per
// cell, splitting every cell into the tetrahedra (x_i, x_{i+1}, x_f, x_c), one per face edge (i, i+1)
// of each of its faces f. Computed once and shared by every volume operator; the refined
// tetrahedral mesh is never built in the fast path.
//
// Refined vertices: 0..|V|-1 (the mesh's), |V| + f (face point of face f), |V| + |F| + c (cell
// point of cell c).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec {

// How the cell point's weights are chosen (the point itself is the same for both).
enum class CellPointRule {
  // x_c minimizes sum_{f, i} vol(x_f, x_i, x_{i+1}, x)^2 over the cell's faces f and face edges
  // (i, i+1); weights: the least-norm affine weights of the cell's vertices reproducing x_c.
  SquaredVolume,
  // The same point, written as polyLaplace does: an affine combination of the cell's face points
  // (half-face order) followed by its vertices (ascending), the first k-1 weights the minimum-norm
  // solution of sum_j lambda_j (q_j - q_k) = x_c - q_k, the last weight 1 minus their sum; the
  // face-point weights are then expanded through the face weights into vertex weights.
  PolyLaplace,
};

// Parses "squared-volume" or "polylaplace"; throws std::invalid_argument otherwise.
CellPointRule parse_cell_point_rule(const std::string& name);
std::string to_string(CellPointRule rule);

struct VolumeRefinementOptions {
  CellPointRule cell_rule = CellPointRule::SquaredVolume;
  // A sub-tetrahedron is degenerate when 6 |vol| is at most this tolerance times the cube of its
  // longest edge (relative to its own size: independent of the mesh's scale and position).
  // Degenerate sub-tetrahedra add no stiffness and no Whitney 1-, 2-, 3-form mass.
  double degenerate_tolerance = 1e-8;
  // Planarity of nearly planar faces for the face points' least-norm weights, as on surfaces
  // (RefinementOptions::planarity_tolerance): 0 decides from the mesh's coordinate precision
  // (VolumeMesh::precision(): what the file's digits resolve, double round-off for generated
  // meshes); > 0 overrides it and the mesh's own planarity_tolerance.
  double planarity_tolerance = 0.0;
  // Threads for the face and cell loops (0: all hardware threads); results do not depend on it.
  int threads = 1;
};

// Sub-tetrahedron quality.
enum class SubTet : std::uint8_t {
  Valid = 0,
  Degenerate = 1,  // zero volume up to the relative tolerance
  Inverted = 2,    // the cell point lies on the outer side of the face triangle (x_i, x_{i+1}, x_f)
};

struct SubTetQuality {
  int n_degenerate = 0;
  int n_inverted = 0;
  int n_cells_affected = 0;  // cells with at least one degenerate or inverted sub-tetrahedron
  bool ok() const { return n_degenerate == 0 && n_inverted == 0; }
};

struct VolumeRefinement {
  VolumeRefinementOptions options;
  std::vector<double> face_weights;         // aligned with VolumeMesh::face_indices(); each face sums to 1
  Eigen::MatrixX3d face_points;             // |F| x 3
  std::vector<int> cell_weight_offsets{0};  // |C| + 1, aligned with VolumeMesh::cell_vertices(c)
  std::vector<double> cell_weights;         // weights of the cell's vertices (ascending); each cell sums to 1
  Eigen::MatrixX3d cell_points;             // |C| x 3
  // Sub-tetrahedra of cell c: tet_offsets[c] .. tet_offsets[c+1], enumerated over the cell's
  // half-faces in order and, within a half-face, over its edges (i, i+1) in the half-face's
  // (outward) vertex order. Tetrahedron (x_i, x_{i+1}, x_f, x_c).
  std::vector<int> tet_offsets{0};
  std::vector<SubTet> tets;
  SubTetQuality quality;

  std::span<const double> weights_of_cell(int c) const {
    return {cell_weights.data() + cell_weight_offsets[c],
            size_t(cell_weight_offsets[c + 1] - cell_weight_offsets[c])};
  }
  std::span<const double> weights_of_face(const VolumeMesh& mesh, int f) const {
    return {face_weights.data() + mesh.face_offsets()[f], size_t(mesh.face_size(f))};
  }
};

VolumeRefinement refine_volume(const VolumeMesh& mesh, const VolumeRefinementOptions& options = {});

// One refined tetrahedron: refined vertex indices (i, j, |V| + f, |V| + |F| + c), with (i, j) the
// half-face's edge in outward order, and its quality.
struct RefinedTet {
  int v[4];
  SubTet quality;
};
// All sub-tetrahedra of the refinement, cell by cell (the order of VolumeRefinement::tets).
std::vector<RefinedTet> refined_tets(const VolumeMesh& mesh, const VolumeRefinement& refinement);

// Position of refined vertex r (mesh vertex, face point or cell point).
Eigen::Vector3d refined_position(const VolumeMesh& mesh, const VolumeRefinement& refinement, int r);

// Throws std::invalid_argument, naming `caller` and the first mismatch, unless `refinement` has the
// sizes of a refinement of `mesh`: |F| face points, one face weight per face corner, |C| cell points,
// and per cell as many weights as vertices and as many sub-tetrahedra as face corners (offsets from 0
// to the arrays' sizes). Every function taking a volume mesh with its refinement calls it first, so
// that a refinement of another mesh (or a default-constructed or truncated one) is refused instead of
// read out of bounds. O(|F| + |C|) integer compares, no allocation.
void check_refinement(const VolumeMesh& mesh, const VolumeRefinement& refinement, const char* caller);
// The same for what one cell c reads (c a cell of `mesh`; the arrays' sizes and cell c's weights and
// sub-tetrahedra), O(size of cell c): for per-cell functions.
void check_refinement_cell(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c,
                           const char* caller);
// The same for refined vertex r (in range, |F| face points, |C| cell points), O(1).
void check_refined_vertex(const VolumeMesh& mesh, const VolumeRefinement& refinement, int r,
                          const char* caller);

// Single-cell kernels (pure functions of positions).

// The point x minimizing sum_t vol(a_t, b_t, c_t, x)^2 over the triangles t (rows of A, B, C):
// a 3x3 least-squares problem in centred coordinates: a Cholesky solve of its normal matrix when
// that is well conditioned (smallest eigenvalue above 1e-6 of the largest), else through its
// eigen-decomposition (eigenvalues below 1e-12 of the largest dropped, least-norm offset from the
// centre). The minimizer is affine-equivariant (an affine map multiplies every volume by the same
// determinant).
Eigen::Vector3d squared_volume_minimizer(const Eigen::MatrixX3d& A, const Eigen::MatrixX3d& B,
                                         const Eigen::MatrixX3d& C);

// Least-norm affine weights w (sum 1) of the points X (m x 3) reproducing x: w = 1/m + Xc^+ (x - mean)
// with Xc the centred points (pseudo-inverse Xc (Xc^T Xc)^-1 through the 3x3 Gram matrix when it is
// well conditioned, else by complete orthogonal decomposition). Invariant under
// translations, rotations and uniform scalings of X and x together.
Eigen::VectorXd least_norm_affine_weights(const Eigen::MatrixX3d& X, const Eigen::Vector3d& x);

// polyLaplace's weights of x over the points Q (k x 3): the first k-1 weights the minimum-norm
// solution of sum_j w_j (q_j - q_{k-1}) = x - q_{k-1}, the last 1 minus their sum.
Eigen::VectorXd last_pinned_affine_weights(const Eigen::MatrixX3d& Q, const Eigen::Vector3d& x);

}  // namespace polydec
