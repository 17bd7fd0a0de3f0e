// dec/surface/virtual_lift.h — virtual vertices off the affine point (beyond the paper; its section 6
// asks for them): the weights w_f of eq. 10 keep defining the prolongation P (eq. 11), while the fan
// triangles (x_i, x_{i+1}, x_f) use another position x_f, given per face or computed by a lift of the
// affine point sum_i w_fi x_i. S = P^T S^f P and M = P^T M^f P stay symmetric with S 1 = 0 (the weights
// still sum to 1); linear precision on planar meshes holds only for lifts that stay in the plane.
#pragma once

#include <Eigen/Core>
#include <string>

#include "polydec/dec/mesh/mesh.h"

namespace polydec {

// Where the virtual vertex of each face is placed.
enum class VirtualLiftKind {
  None,       // the affine point sum_i w_fi x_i (the paper's operator)
  Positions,  // VirtualLift::positions, one row per face
  Sphere,     // the closest point on a sphere: c + r (a - c) / |a - c| for the affine point a
  Quadric,    // a + h(0, 0) n: the height over the face's best-fit plane of a local quadric fit
};

// The lift of RefinementOptions::lift.
//
// Sphere: `radius` > 0 gives the sphere (center, radius); radius 0 (the default) fits one to the mesh's
// vertices (best_fit_sphere), so that a polygonized sphere of any center and radius is lifted onto itself.
//
// Quadric: per face, in the orthonormal frame (t1, t2, n) at the affine point a with n the unit vector
// area of the face, the heights z = <x - a, n> of the face's vertices and their edge neighbours are
// fitted by z = c0 + c1 u + c2 v + c3 u^2 + c4 u v + c5 v^2 in least squares (u, v the tangent
// coordinates over the points' largest distance from a; minimum-norm solution when fewer than six points
// or a degenerate configuration leave it underdetermined), and x_f = a + c0 n. Exact on quadric
// surfaces z(u, v); on a planar mesh every height is zero up to round-off, so x_f = a.
struct VirtualLift {
  VirtualLiftKind kind = VirtualLiftKind::None;
  Eigen::MatrixX3d positions;                          // Positions: |F| x 3, finite
  Eigen::Vector3d center = Eigen::Vector3d::Zero();    // Sphere
  double radius = 0.0;                                 // Sphere: > 0, or 0 for the best-fit sphere
};

// A sphere (center, radius).
struct Sphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 1.0;
};

// The algebraic least-squares sphere through the points (rows): minimizes sum_i (|x_i|^2 - 2 <c, x_i> - d)^2
// over c and d = r^2 - |c|^2, in centred coordinates scaled by their rms radius. Exact for points on a
// sphere. Throws std::invalid_argument when fewer than 4 points or when they are (nearly) coplanar (no
// finite sphere), relative to their spread.
Sphere best_fit_sphere(const Eigen::MatrixX3d& points);

// Parses "none", "sphere" (best-fit sphere), "sphere:cx,cy,cz,r" (r > 0) and "quadric"; throws
// std::invalid_argument otherwise. Positions are given as a matrix, not by name.
VirtualLift parse_virtual_lift(const std::string& spec);
// "none", "positions", "sphere", "sphere:cx,cy,cz,r", "quadric".
std::string to_string(const VirtualLift& lift);

// The virtual points of `mesh` under `lift`, from its affine points (|F| x 3, eq. 10). Throws std::invalid_argument when the lift's
// positions are not |F| x 3 or not finite, when a sphere lift's affine point sits at the sphere's center,
// or when a given sphere has a non-positive or non-finite radius. Faces with a zero vector area keep their
// affine point under the quadric lift.
Eigen::MatrixX3d lifted_virtual_points(const Mesh& mesh, const Eigen::MatrixX3d& affine_points,
                                       const VirtualLift& lift);

}  // namespace polydec
