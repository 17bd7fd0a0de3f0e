// apps/pictures/volume_cut.h — a planar cut through a polyhedral volume mesh, for pictures:
// the section of the mesh by a plane, and the solid behind the plane (its boundary surface clipped,
// closed by the section) as a surface Mesh carrying a scalar, ready for render() (render.h).
//
// The plane {x : n . (x - p) = 0} (n need not be unit) splits space into the front half n . (x - p) > 0,
// which is removed, and the kept half n . (x - p) <= 0. The section is computed on the sub-tetrahedra
// of the virtual refinement (dec/volume/refinement.h): each one crossed by the plane gives a triangle
// or a quadrilateral (a sub-tetrahedron face lying in the plane is counted once, from the kept side).
// Vertex values u are extended to face and cell points by the prolongation P (operators/volume/laplacian.h)
// and interpolated linearly along the refined edges, so a field that is linear on every sub-tetrahedron
// (e.g. a linear function of the position) is reproduced exactly on the cut. Section vertices are
// shared between neighbouring pieces (keyed by the refined edge they lie on, or the refined vertex),
// and oriented with normal +n (facing the viewer looking along -n).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "polydec/apps/pictures/render.h"
#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/mesh/volume_mesh.h"
#include "polydec/dec/volume/refinement.h"

namespace polydec {

struct CutPlane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // non-zero; points into the removed half
};

// Polygons in the plane: polygon k has the vertex indices indices[offsets[k] .. offsets[k+1]).
struct VolumeCut {
  Eigen::MatrixX3d positions;
  Eigen::VectorXd values;  // the interpolated scalar at positions (empty without one)
  std::vector<int> offsets{0}, indices;
  int n_polygons() const { return int(offsets.size()) - 1; }
  bool empty() const { return n_polygons() == 0; }
  double area() const;  // sum of the polygons' areas
};

// The section of `mesh` by `plane`; `vertex_values` has |V| values, or is empty. Pieces that
// collapse to a point or a segment (the plane touching a sub-tetrahedron at a vertex or an edge) are
// dropped. Empty when the plane misses the mesh. Throws std::invalid_argument for a zero or
// non-finite normal, a scalar of the wrong size, or a refinement whose sizes are not those of a
// refinement of `mesh` (faces, cells, weights per face and cell, sub-tetrahedra per cell).
VolumeCut cut_volume(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                     const Eigen::VectorXd& vertex_values, const CutPlane& plane);

// The solid behind the plane as a surface: the boundary faces of `mesh` clipped to the kept half
// (faces lying in the plane dropped: the section replaces them), plus the section's polygons, with
// the scalar in *values (if given). Throws std::invalid_argument, with the range of the vertices'
// signed distances from the plane, when the plane misses the mesh (no section) or keeps nothing.
Mesh cut_solid(const VolumeMesh& mesh, const VolumeRefinement& refinement,
               const Eigen::VectorXd& vertex_values, const CutPlane& plane,
               Eigen::VectorXd* values = nullptr);

// The plane through the centre of the mesh's bounding box with normal `normal`.
CutPlane centre_plane(const VolumeMesh& mesh, const Eigen::Vector3d& normal);

// A view direction for pictures of a cut: from the removed half, looking along -n, tilted so that the
// kept boundary shows too (-n - 0.5 u - 0.35 w with u the component of `up` orthogonal to n, w = n x u).
Eigen::Vector3d cut_view_direction(const CutPlane& plane,
                                   const Eigen::Vector3d& up = Eigen::Vector3d::UnitY());

// cut_solid rendered to a PNG (render_png) with the scalar colour-mapped (empty: plain grey); a zero
// options.view_direction is replaced by cut_view_direction. Pass the refinement the field's operators
// were built on (build_volume_operators), so that the picture interpolates as they do.
void render_volume_cut_png(const std::string& path, const VolumeMesh& mesh,
                           const VolumeRefinement& refinement, const Eigen::VectorXd& vertex_values,
                           const CutPlane& plane, RenderOptions options);

// The same on the default refinement, refine_volume(mesh).
void render_volume_cut_png(const std::string& path, const VolumeMesh& mesh,
                           const Eigen::VectorXd& vertex_values, const CutPlane& plane,
                           RenderOptions options);

}  // namespace polydec
