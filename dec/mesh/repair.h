// dec/mesh/repair.h — explicit, opt-in repair steps on a polygon soup, run before validation
// (Mesh's constructor never repairs anything). Every step reports what it changed: counts per
// reason and index maps from the old vertex/face numbering to the new one (-1 = removed).
#pragma once

#include <string>
#include <vector>

#include "polydec/dec/mesh/mesh.h"

namespace polydec {

// Result of remove_unreferenced_vertices.
struct VertexRemoval {
  int n_removed = 0;
  std::vector<int> vertex_map;  // old vertex -> new vertex, -1 if removed
};

// Removes vertices that no face refers to; the remaining vertices keep their relative order.
// Throws std::invalid_argument when a face index is out of range (drop invalid faces first).
VertexRemoval remove_unreferenced_vertices(PolygonSoup& soup);

// What drop_invalid_faces considers invalid, and how zero area is measured.
struct FaceDropOptions {
  // Consecutive repeats of a vertex (cyclically: 0 1 1 2, 0 1 2 0) are collapsed to one corner
  // before the other tests, as vertex merging produces them. Off: such faces are dropped.
  bool collapse_consecutive_repeats = true;
  // A face has zero area when its corners lie on one line (or point) up to this tolerance:
  // sigma_2 <= tolerance * sigma_1 for the singular values of its centred corner positions.
  // Relative to the face's own extent; the same scale as RefinementOptions::degenerate_tolerance.
  double zero_area_tolerance = 1e-10;
};

// Result of drop_invalid_faces, counted by the first reason that applies.
struct FaceDrop {
  int n_out_of_range = 0;       // an index outside [0, |V|)
  int n_too_few = 0;            // fewer than 3 distinct corners (after collapsing)
  int n_repeated_vertex = 0;    // a vertex occurring twice, not consecutively
  int n_zero_area = 0;          // all corners collinear up to the tolerance
  int n_collapsed_corners = 0;  // corners removed from kept or dropped faces by collapsing repeats
  std::vector<int> face_map;    // old face -> new face, -1 if dropped
  int n_dropped() const { return n_out_of_range + n_too_few + n_repeated_vertex + n_zero_area; }
};

FaceDrop drop_invalid_faces(PolygonSoup& soup, const FaceDropOptions& options = {});

// Result of merge_duplicate_vertices.
struct VertexMerge {
  double distance = 0;          // the absolute merge distance used (tolerance x bounding-box diagonal)
  int n_merged = 0;             // vertices that were merged into another one (and removed)
  std::vector<int> vertex_map;  // old vertex -> new vertex (merged vertices map to their representative)
};

// Merges vertices closer than relative_tolerance x (bounding-box diagonal) to each other
// (transitively: chains of close vertices become one). Each cluster keeps the position and the
// place of its lowest-numbered vertex; faces are renumbered. Faces may then repeat a vertex:
// run drop_invalid_faces afterwards. relative_tolerance = 0 merges exactly coincident vertices.
// Throws std::invalid_argument for a negative tolerance, non-finite positions or indices out
// of range.
VertexMerge merge_duplicate_vertices(PolygonSoup& soup, double relative_tolerance);

// Result of remove_duplicate_faces.
struct FaceDeduplication {
  int n_same_orientation = 0;      // same cyclic vertex sequence as an earlier face
  int n_opposite_orientation = 0;  // the reversed cyclic sequence of an earlier face
  std::vector<int> face_map;       // old face -> new face, -1 if removed
  int n_removed() const { return n_same_orientation + n_opposite_orientation; }
};

// Removes faces with the same vertices in the same cyclic order as an earlier face, in either
// direction; the first occurrence is kept.
FaceDeduplication remove_duplicate_faces(PolygonSoup& soup);

// Which steps repair() runs, in this order: merge vertices, drop invalid faces, remove
// duplicate faces, remove unreferenced vertices.
struct RepairOptions {
  bool merge_vertices = false;
  double merge_tolerance = 0.0;  // relative to the bounding-box diagonal
  bool drop_invalid_faces = true;
  FaceDropOptions face_drop;
  bool remove_duplicate_faces = true;
  bool remove_unreferenced_vertices = true;
};

struct RepairReport {
  VertexMerge merge;
  FaceDrop drop;
  FaceDeduplication dedup;
  VertexRemoval unreferenced;
  std::vector<int> vertex_map;  // input vertex -> output vertex (-1 removed), all steps composed
  std::vector<int> face_map;    // input face -> output face (-1 removed), all steps composed
  bool changed() const;
  // One line per step that changed something ("nothing changed" otherwise).
  std::vector<std::string> summary() const;
};

// Runs the selected steps on the soup; the report says what each changed.
RepairReport repair(PolygonSoup& soup, const RepairOptions& options = {});

}  // namespace polydec
