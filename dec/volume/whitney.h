// dec/volume/whitney.h — Whitney forms on one tetrahedron (DEC on polyhedral volume meshes): hat
// gradients, the linear stiffness and mass, and the Galerkin inner products of the Whitney 0-, 1-,
// 2- and 3-forms in closed form. Pure functions of the four corners; no mesh needed.
//
// Conventions: the tetrahedron is (p0, p1, p2, p3) in the order given; local edges are the pairs
// (0,1), (0,2), (0,3), (1,2), (1,3), (2,3) and local triangles (0,1,2), (0,1,3), (0,2,3), (1,2,3),
// each oriented by increasing local index (the order of the refined complex, whose simplices are
// sorted by vertex index). Whitney forms (vector proxies, lambda the barycentric coordinates):
//   phi_ab   = lambda_a grad lambda_b - lambda_b grad lambda_a,
//   phi_abc  = 2 (lambda_a gl_b x gl_c + lambda_b gl_c x gl_a + lambda_c gl_a x gl_b),
//   phi_0123 = +-1 / volume (a density),
// so that d (Whitney) = Whitney (d) with the combinatorial d of dec/volume/complex.h.
#pragma once

#include "polydec/dec/mesh/eigen_abi.h"
#include <Eigen/Core>

namespace polydec {

using Matrix34d = Eigen::Matrix<double, 3, 4>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Gradients of the four barycentric coordinates, as the columns of a 3x4 matrix, and the signed
// volume det[p1 - p0, p2 - p0, p3 - p0] / 6 in *signed_volume (optional). The tetrahedron must not
// be degenerate.
Matrix34d tet_hat_gradients(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                            const Eigen::Vector3d& p3, double* signed_volume = nullptr);

// Signed volume det[p1 - p0, p2 - p0, p3 - p0] / 6.
double tet_signed_volume(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                         const Eigen::Vector3d& p3);

// Linear (P1) stiffness, negative semi-definite: S_ab = -|vol| grad lambda_a . grad lambda_b
// (the 3D analogue of the cotangent matrix, eq. 3).
Eigen::Matrix4d tet_stiffness(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                              const Eigen::Vector3d& p3);

// Galerkin mass of the hats (Whitney 0-forms): |vol| / 20 * (1 + delta_ab).
Eigen::Matrix4d tet_whitney0_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                  const Eigen::Vector3d& p2, const Eigen::Vector3d& p3);

// Mass of the six Whitney 1-forms, local edge order above. With G_ab = gl_a . gl_b and
// int lambda_a lambda_c = |vol| (1 + delta_ac) / 20:
//   M_(ab)(cd) = |vol|/20 [(1+d_ac) G_bd - (1+d_ad) G_bc - (1+d_bc) G_ad + (1+d_bd) G_ac].
Matrix6d tet_whitney1_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                           const Eigen::Vector3d& p3);

// Mass of the four Whitney 2-forms, local triangle order above: with phi_abc = 2 sum_p lambda_p v_p,
//   M = 4 sum_{p, q} |vol| (1 + delta_pq) / 20 v_p . v'_q.
Eigen::Matrix4d tet_whitney2_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                  const Eigen::Vector3d& p2, const Eigen::Vector3d& p3);

// Inner product of the Whitney 3-form with itself: 1 / |vol|, whatever the orientation.
double tet_whitney3_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                         const Eigen::Vector3d& p3);

// Local edge (triangle) index of sorted local vertices, for the orders above.
inline int tet_local_edge(int a, int b) {
  static constexpr int table[4][4] = {{-1, 0, 1, 2}, {0, -1, 3, 4}, {1, 3, -1, 5}, {2, 4, 5, -1}};
  return table[a][b];
}
// The triangle without local vertex `missing`: (1,2,3) is 3, (0,2,3) is 2, (0,1,3) is 1, (0,1,2) is 0.
inline int tet_local_triangle_without(int missing) { return 3 - missing; }

}  // namespace polydec
