// dec/surface/whitney.h — Whitney forms on one triangle (paper section 4.6): hat gradients, the Galerkin
// inner products of Whitney 0-, 1- and 2-forms in closed form, and pointwise evaluation of a
// Whitney 1-form. Pure functions of the triangle's corners; no mesh needed.
//
// Conventions: the triangle is (p0, p1, p2) in the order given; its local edges are (0,1),
// (0,2), (1,2), each oriented from the lower to the higher local index (the order used for the
// refined complex, where corners are sorted by vertex index). The Whitney 1-form of edge (a,b)
// is lambda_a d lambda_b - lambda_b d lambda_a; that of the triangle (0,1,2) is
// 2 (lambda_0 dl_1^dl_2 - lambda_1 dl_0^dl_2 + lambda_2 dl_0^dl_1) = +-(1/area) dA.
#pragma once

#include "polydec/dec/mesh/eigen_abi.h"
#include <Eigen/Core>

namespace polydec {

// Gradients of the three barycentric coordinates, as the columns of a 3x3 matrix (they lie in
// the triangle's plane). The triangle must not be degenerate.
Eigen::Matrix3d hat_gradients(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                              const Eigen::Vector3d& p2);

// Galerkin mass of the hats (eq. 20 on one triangle): area/12 * (1 + delta_ab).
Eigen::Matrix3d whitney0_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                              const Eigen::Vector3d& p2);

// Mass matrix of the three Whitney 1-forms (eq. 21 on one triangle), rows and columns in the
// local edge order (0,1), (0,2), (1,2). Closed form: with G_ab = grad lambda_a . grad lambda_b
// and int lambda_a lambda_c = area (1 + delta_ac) / 12,
//   M_(ab)(cd) = area/12 [(1+d_ac) G_bd - (1+d_ad) G_bc - (1+d_bc) G_ad + (1+d_bd) G_ac].
// Symmetric positive definite for a non-degenerate triangle.
Eigen::Matrix3d whitney1_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                              const Eigen::Vector3d& p2);

// Inner product of the Whitney 2-form with itself (eq. 22 on one triangle): 1 / area, whatever
// the orientation.
double whitney2_mass(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2);

// The vector field (in the triangle's plane) of the Whitney 1-form with edge values
// c = (c_01, c_02, c_12) at the point with barycentric coordinates `bary`.
Eigen::Vector3d whitney1_value(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                               const Eigen::Vector3d& p2, const Eigen::Vector3d& c,
                               const Eigen::Vector3d& bary);

}  // namespace polydec
