// apps/applications/volume/hodge_decomposition.h — Hodge decomposition of a coarse 1-cochain on a
// polyhedral mesh, omega = d0 alpha + co-exact + harmonic, orthogonal in the star1 inner product of
// the coarsened Whitney 1-forms (the volume counterpart of apps/applications/hodge_decomposition.h).
//
//   exact:    d0 alpha, with d0^T star1 d0 alpha = d0^T star1 omega (one vertex pinned per
//             connected component);
//   harmonic: the star1-orthogonal projection onto H = closed forms modulo exact ones: the
//             Whitney-closed forms (star2-null d1, i.e. P2 d1 x = 0) of the reduced basis
//             (volume_form_span), minus their exact parts, star1-orthonormalised; dim H is the
//             first Betti number of the mesh (0 on a ball, 1 on a solid torus);
//   co-exact: the rest, star1-orthogonal to every closed form.
// On the complete complex the closed forms are found by a dense eigen-decomposition on the span
// of the 1-forms, so the constructor is meant for meshes of up to a few thousand coarse pairs (it
// throws std::invalid_argument above volume_form_span's limit); it builds DEC up to degree 2 (no
// 3-forms), so cells of up to max_dec_cell_vertices(2) = 16 vertices. On the mesh complex
// (DecComplex::Mesh, dec/volume/mesh_complex.h) the 1-forms live on the mesh edges, star1 and
// star2 are positive definite, cells of any size are allowed, and the closed forms come from
// closed_edge_generators (sparse: memory and time linear in the mesh for a fixed Betti number).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>

#include "polydec/apps/applications/hodge_parts.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/operators/solvers/cholesky.h"

namespace polydec {

// Closed 1-cochains on the edges (|E| x k, k = the first Betti number) that with the exact ones
// span ker d1, from the coboundaries d0 (|E| x |V|) and d1 (|F| x |E|) of any 2-complex: the
// cochains vanish on a spanning forest of the edges; faces with exactly one edge not yet fixed fix
// it (peeling); each edge left free starts one cochain, propagated through the peel, and the closed
// combinations of those (a dense null space of size free edges) are returned. Not orthonormal,
// not free of exact parts.
Eigen::MatrixXd closed_edge_generators(const SparseMatrix& d0, const SparseMatrix& d1);

class VolumeHodgeDecomposer {
 public:
  explicit VolumeHodgeDecomposer(const VolumeMesh& mesh, const VolumeRefinementOptions& options = {},
                                 DecComplex complex = DecComplex::Complete);
  // The same on a refinement of `mesh` the caller already holds (std::invalid_argument when it
  // belongs to another mesh); the results are those of refining again with its options.
  static VolumeHodgeDecomposer on_refinement(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                             DecComplex complex = DecComplex::Complete);

  // omega: one value per coarse pair, or per mesh edge on the mesh complex (std::invalid_argument
  // on a size mismatch or non-finite values).
  HodgeParts decompose(const Eigen::VectorXd& omega) const;

  const VolumeDec& dec() const { return dec_; }
  // The 1-cells' vertices (i, j), i < j: the complete complex's pairs, or the mesh edges.
  const Eigen::MatrixX2i& cells() const { return edges_; }
  const Eigen::MatrixXd& harmonic_basis() const { return H_; }  // star1-orthonormal, |C1| x dim
  int harmonic_dimension() const { return int(H_.cols()); }

 private:
  struct OnRefinement {};
  VolumeHodgeDecomposer(OnRefinement, const VolumeMesh& mesh, const VolumeRefinement& refinement, DecComplex complex);
  Eigen::VectorXd exact_potential(const Eigen::VectorXd& rhs) const;

  VolumeDec dec_;
  Eigen::MatrixX2i edges_;
  std::vector<unsigned char> pinned_;
  std::unique_ptr<SparseCholesky> poisson_;
  Eigen::MatrixXd H_;
};

}  // namespace polydec
