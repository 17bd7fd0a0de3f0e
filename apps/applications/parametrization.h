// apps/applications/parametrization.h — spectral free-boundary conformal parametrization (Mullen, Tong,
// Alliez, Desbrun 2008; paper section 5.3, Figure 6, Table 1) on the polygon Laplacian.
//
// With U = (u, v) stacked (2|V|), the conformal energy is E_C(U) = E_D(U) - A(U) = 1/2 U^T L_C U:
// the Dirichlet energy E_D = 1/2 (u^T (-S) u + v^T (-S) v) minus the signed area of the image,
// A = 1/2 sum over boundary edges (i -> j, in the faces' orientation) of (u_i v_j - u_j v_i).
// E_C >= 0 vanishes exactly for orientation-preserving conformal maps. The parametrization is
// the first eigenvector of L_C U = lambda B U with B the boundary mass (1 at the u and v entries
// of boundary vertices, 0 elsewhere) that is B-orthogonal to the trivial ones, the translations.
// Since B vanishes at interior vertices, their rows read L_II U_I + L_IB U_B = 0, so the problem
// is solved exactly on the boundary with the Schur complement of L_C (a dense symmetric
// eigenproblem of size 2 |boundary vertices|), then U_I = -L_II^-1 L_IB U_B.
#pragma once

#include <string>

#include "polydec/dec/surface/refinement.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec {

struct ConformalParametrization {
  Eigen::MatrixX2d uv;    // |V| x 2 of the operator set's domain, scaled into [0,1]^2 (aspect kept)
  double eigenvalue = 0;  // lambda of the chosen eigenvector (its conformal energy, up to scale)
};

// Throws std::invalid_argument when a connected component has no boundary, SolverError when
// the interior block cannot be factored. Vertices in no face get uv = 0.
ConformalParametrization spectral_conformal_parametrization(const OperatorSet& operators);
// With the paper's operator ("ours").
ConformalParametrization spectral_conformal_parametrization(const Mesh& mesh);

// Conformal distortion: the area-weighted root-mean-square difference (radians) between the
// corner angles of the polygons in 3D and in the parametrization,
//   sqrt( sum_c w_c (alpha_c - beta_c)^2 / sum_c w_c ),
// over all face corners c; alpha_c, beta_c in [0, pi] are the angles between the corner's two
// edges in 3D and in uv, w_c = |vector area of c's face| / (valence of the face).
double conformal_distortion(const Mesh& mesh, const Eigen::MatrixX2d& uv);
// The same between a mesh and a deformed copy with the same connectivity (`deformed`: |V| x 3),
// e.g. the input against its conformalized curvature flow (Table 1). Throws std::invalid_argument
// for a wrong number of rows.
double conformal_distortion(const Mesh& mesh, const Eigen::MatrixX3d& deformed);

// Per vertex: the root-mean-square of alpha_c - beta_c over the vertex's corners, weighted
// as above (0 for vertices in no face) — where the distortion sits.
Eigen::VectorXd vertex_conformal_distortion(const Mesh& mesh, const Eigen::MatrixX2d& uv);

// Number of fan triangles (x_i, x_j, x_f) of the refinement whose image in uv — the virtual
// vertex mapped with the same affine weights, uv_f = sum_i w_i uv_i — has non-positive signed
// area (flipped or collapsed). Degenerate fan triangles of the 3D refinement are not counted.
int count_flipped_fan_triangles(const Mesh& mesh, const Refinement& refinement, const Eigen::MatrixX2d& uv);

// Writes an OBJ with "v" (3D positions), "vt" (uv) and faces "f i/i ..." (17 significant
// digits). Throws FileError when the file cannot be written.
void write_obj_with_uv(const std::string& path, const Mesh& mesh, const Eigen::MatrixX2d& uv);

}  // namespace polydec
