// apps/applications/hodge_decomposition.h — Hodge decomposition of a coarse 1-cochain on a polygon mesh,
// omega = d0 alpha + delta beta + h (exact + co-exact + harmonic), orthogonal in the star1
// inner product of the coarsened Whitney 1-forms (paper section 4.6; docs/feec.md).
//
// The inner product <x, y> = x^T star1 y is only semi-definite (star1 is singular on faces with
// 5 or more corners): it is an inner product on Whitney forms, i.e. on 1-cochains modulo
// ker P1. The decomposition is one of Whitney forms; parts are returned as coarse 1-cochains,
// each determined up to ker P1 (norms and orthogonality do not depend on the choice).
//   exact:    d0 alpha, with -S alpha = d0^T star1 omega (S = -d0^T star1 d0, one vertex
//             pinned per connected component; alpha is 0 there);
//   harmonic: the star1-orthogonal projection onto H = span{g - d0 a_g}, g running over
//             closed, non-exact cellular cochains (tree-cotree generators of the first
//             cohomology, extended from mesh edges to diagonals by face potentials, so that
//             d1 g = 0 exactly); dim H = 2 genus (+ boundary loops - 1 per component with
//             boundary);
//   co-exact: the rest, omega - exact - harmonic, which is star1-orthogonal to every closed
//             form (ker d1 = exact + harmonic), hence in the range of delta = star1^+ d1^T star2.
// Assumes a manifold mesh in which no polygon diagonal is shared by two faces (then the coarse
// complex has the surface's cohomology).
// On the mesh complex (DecComplex::Mesh, dec/surface/mesh_complex.h) the 1-forms live on the mesh
// edges and star1 is positive definite: the same steps are ordinary solves, the parts are unique,
// and the harmonic generators are the tree-cotree cochains on the edges.
#pragma once

#include <Eigen/Sparse>
#include <memory>

#include "polydec/apps/applications/hodge_parts.h"
#include "polydec/dec/surface/complex.h"
#include "polydec/dec/surface/mesh_complex.h"
#include "polydec/dec/surface/refinement.h"
#include "polydec/operators/solvers/cholesky.h"

namespace polydec {

class HodgeDecomposer {
 public:
  // Builds the complex, d0, star1, factors d0^T star1 d0 (pinned) and the harmonic basis.
  explicit HodgeDecomposer(const Mesh& mesh, const RefinementOptions& options = {},
                           DecComplex complex = DecComplex::Complete);

  // omega: one value per coarse 1-cell (pair of the complete complex, or mesh edge); throws
  // std::invalid_argument on a size mismatch or non-finite values.
  HodgeParts decompose(const Eigen::VectorXd& omega) const;

  DecComplex dec_complex() const { return kind_; }
  const CoarseComplex& complex() const { return complex_; }  // empty on the mesh complex
  // The 1-cells' vertices (i, j), i < j: the complete complex's pairs, or the mesh edges.
  const Eigen::MatrixX2i& cells() const { return edges_; }
  const Eigen::SparseMatrix<double>& d0() const { return d0_; }
  const Eigen::SparseMatrix<double>& star1() const { return star1_; }
  // star1-orthonormal basis of the harmonic 1-forms, |C1| x dim.
  const Eigen::MatrixXd& harmonic_basis() const { return H_; }
  int harmonic_dimension() const { return int(H_.cols()); }

 private:
  Eigen::VectorXd exact_potential(const Eigen::VectorXd& rhs) const;

  DecComplex kind_ = DecComplex::Complete;
  CoarseComplex complex_;
  Eigen::MatrixX2i edges_;
  Eigen::SparseMatrix<double> d0_, star1_;
  std::vector<unsigned char> pinned_;
  std::unique_ptr<SparseCholesky> poisson_;
  Eigen::MatrixXd H_;
};

// Closed, non-exact 1-cochains on the coarse complex generating its first cohomology (tree-cotree
// on the polygon mesh, one per edge left over by a primal spanning forest and a dual spanning
// forest whose roots are one exterior node per bordered component), |C1| x b1. Integer-valued;
// d1 g = 0 exactly.
Eigen::MatrixXd cohomology_generators(const Mesh& mesh, const CoarseComplex& complex);
// The same generators on the mesh edges (the mesh complex), |E| x b1.
Eigen::MatrixXd cohomology_generators(const Mesh& mesh);

// One-shot: HodgeDecomposer(mesh).decompose(omega).
HodgeParts hodge_decomposition(const Mesh& mesh, const Eigen::VectorXd& omega);

}  // namespace polydec
