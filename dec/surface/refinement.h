// dec/surface/refinement.h — the virtual refinement of a polygon mesh (paper section 4.1): one virtual
// vertex per face (eq. 10) splitting the face into a fan of triangles, one per halfedge.
// Computed once and shared by every operator; the refined mesh itself is never built in the
// fast path (refined_mesh() builds it explicitly, for tests and for the "refined" comparison).
#pragma once

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/virtual_lift.h"
#include "polydec/dec/surface/virtual_vertex.h"

#include <cstdint>
#include <vector>

namespace polydec {

struct RefinementOptions {
  VirtualVertexRule rule = VirtualVertexRule::SquaredArea;
  // A fan triangle (x_i, x_j, x_f) is degenerate when twice its area is at most this
  // tolerance times the square of its longest edge (i.e. its height is below tolerance times
  // its length). Degenerate fan triangles get zero stiffness and zero gradient: relative to
  // the triangle's own size, so independent of the mesh's scale and position.
  double degenerate_tolerance = 1e-8;
  // Planarity of nearly planar faces for the least-norm weights (eq. 16, dec/surface/virtual_vertex.h):
  // 0 decides from the mesh's coordinate precision (Mesh::precision(): what the file's digits
  // resolve, double round-off for generated meshes); > 0 overrides it and the mesh's own
  // planarity_tolerance: a face whose out-of-plane extent is at most this fraction of its size
  // counts as planar.
  double planarity_tolerance = 0.0;
  // Threads for the per-face work (0: all hardware threads). Results do not depend on it.
  int threads = 1;
  // Where the virtual vertices sit (dec/surface/virtual_lift.h): the affine points of the weights
  // (default, the paper's operator) or given or lifted positions; the weights define P either way.
  VirtualLift lift = {};
};

// Fan-triangle quality, per halfedge.
enum class FanTriangle : std::uint8_t {
  Valid = 0,
  Degenerate = 1,  // zero area up to the relative tolerance (virtual vertex on the edge's line)
  Inverted = 2,    // oriented against the polygon's vector-area normal (the virtual vertex does not see the edge)
};

struct FanQuality {
  int n_degenerate = 0;
  int n_inverted = 0;
  int n_faces_affected = 0;  // faces with at least one degenerate or inverted fan triangle
  bool ok() const { return n_degenerate == 0 && n_inverted == 0; }
};

struct Refinement {
  RefinementOptions options;
  std::vector<double> weights;         // one per corner, aligned with Mesh::face_indices(); each face sums to 1
  Eigen::MatrixX3d virtual_points;     // |F| x 3, x_f = sum_i w_fi x_i (eq. 10), or its lift (options.lift)
  std::vector<FanTriangle> fan;        // one per halfedge: the quality of fan triangle (x_h, x_next(h), x_f)
  FanQuality quality;
};

// Computes the virtual vertices of all faces and classifies every fan triangle. Throws
// std::invalid_argument for a lift that does not fit the mesh (lifted_virtual_points).
Refinement refine(const Mesh& mesh, const RefinementOptions& options = {});

// Recomputes the virtual points and the fan classification for moved vertex positions,
// keeping the options (weights are recomputed too: they depend on the geometry; given virtual
// positions, VirtualLiftKind::Positions, stay where they were given).
Refinement refine(const Mesh& mesh, const Refinement& previous);

// The explicit refined triangle mesh: vertices 0..|V|-1 are the mesh's, vertex |V|+f is the
// virtual vertex of face f; triangle h (one per halfedge) is (source(h), target(h), |V|+f).
Mesh refined_mesh(const Mesh& mesh, const Refinement& refinement);

// Throws std::invalid_argument, naming `caller`, unless `refinement` has the sizes of a refinement
// of `mesh` (|F| virtual points, one weight and one fan triangle per halfedge): every function
// taking a mesh with its refinement calls it first, so that a refinement of another mesh (or a
// default-constructed one) is refused instead of read out of bounds. O(1), no allocation.
void check_refinement(const Mesh& mesh, const Refinement& refinement, const char* caller);

// Gathers the positions of face f's corners (n x 3).
PolygonPositions face_positions(const Mesh& mesh, int f);

}  // namespace polydec
