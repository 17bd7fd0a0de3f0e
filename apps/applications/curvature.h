// apps/applications/curvature.h — mean curvature from the Laplacian of the coordinates (paper section 5.2,
// eq. 29, Table 2):
//   H_i = 1/2 || (L X)_i || * sign< -(L X)_i, n_i >,   L = M^-1 S (lumped M by default),
// with n_i the outward vertex normal. The Laplace-Beltrami operator of the coordinates is the
// mean-curvature normal, Delta X = -2 H n, so with an outward normal a sphere of radius r has
// H = 1/r > 0 (the sign convention of eq. 29 read for our negative semi-definite S).
#pragma once

#include "polydec/operators/registry/laplacians.h"

namespace polydec {

// Vertex normals (|V| x 3, unit length): the sum over the vertex's face corners of the corner
// normal (e_next x e_prev, normalized) weighted by the corner angle — the angle-weighted normal
// of pmp-library's vertex_normal, used by the authors' program. Oriented by the faces'
// orientation (outward for an outward-oriented closed mesh). Zero for vertices in no face or
// whose corner normals cancel.
Eigen::MatrixX3d vertex_normals(const Mesh& mesh);

// Volume enclosed by a closed mesh, positive when its faces are oriented outwards (for a mesh
// with boundary: the signed volume of the cone from the origin).
double signed_volume(const Mesh& mesh);

struct CurvatureOptions {
  bool lumped_mass = true;  // lumped (default, Table 2) or Galerkin mass in L = M^-1 S
};

// Mean curvature per vertex of the operator set's domain (eq. 29); 0 at vertices without mass.
// The normals are vertex_normals(), flipped when the mesh is closed and encloses a negative
// signed volume (faces oriented inwards), so convex closed surfaces get H > 0 either way.
// Throws SolverError when the Galerkin mass cannot be factored.
Eigen::VectorXd mean_curvature(const OperatorSet& operators, const CurvatureOptions& options = {});
// With the paper's operator ("ours").
Eigen::VectorXd mean_curvature(const Mesh& mesh, const CurvatureOptions& options = {});

// The Galerkin mass with 1 on the diagonal of vertices in no face (whose rows are empty), so
// that it can be factored; M^-1 S is unchanged at every other vertex and 0 at those.
SparseMatrix mass_with_unit_rows_for_unreferenced(const OperatorSet& operators);

// Root-mean-square deviation of H from the constant `expected` over all vertices (Table 2 uses
// expected = 1 on meshes projected to the unit sphere).
double curvature_rmse(const Eigen::VectorXd& H, double expected);

}  // namespace polydec
