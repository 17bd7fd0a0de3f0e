// dec/mesh/mesh_checks.h — diagnostics of a valid Mesh: the things validation accepts but a user may
// want to know about (duplicate faces, zero-area and extremely thin faces, collinear consecutive
// corners, non-manifold vertices, unreferenced vertices, connected components, fan-triangle
// quality). Reports only; nothing is changed (see dec/mesh/repair.h for the opt-in repairs).
#pragma once

#include <string>
#include <vector>

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec {

struct MeshCheckOptions {
  // Zero area: sigma_2 <= tolerance * sigma_1 for the singular values of a face's centred corner
  // positions (all corners on one line or point), as in dec/mesh/repair.h.
  double zero_area_tolerance = 1e-10;
  // Extremely thin: not zero-area, but sigma_2 / sigma_1 below this ratio.
  double thin_ratio = 1e-6;
  // Collinear corner k: |sin| of the angle between the edges (x_{k-1}, x_k) and (x_k, x_{k+1})
  // at most this tolerance (straight through, or folding back as a spike).
  double collinear_tolerance = 1e-10;
  RefinementOptions refinement;  // for the fan-triangle quality
};

struct CollinearCorner {
  int face = -1;
  int vertex = -1;
  bool spike = false;  // the two edges point in opposite directions (the polygon folds back)
};

struct MeshReport {
  std::vector<std::pair<int, int>> duplicate_faces;  // (face, earlier face with the same vertex cycle)
  std::vector<int> zero_area_faces;
  std::vector<int> thin_faces;
  std::vector<CollinearCorner> collinear_corners;
  std::vector<int> non_manifold_vertices;  // faces around them form more than one edge-connected fan
  std::vector<int> unreferenced_vertices;
  int n_components = 0;
  std::vector<int> component;        // per vertex, -1 for unreferenced vertices
  std::vector<int> component_faces;  // number of faces per component
  FanQuality fan;                    // degenerate and inverted fan triangles of the refinement

  // True when none of the lists is non-empty, there is at most one component and every fan
  // triangle is valid.
  bool clean() const;
  // One line per finding, naming the first few elements.
  std::vector<std::string> summary() const;
};

// Diagnoses a validated mesh.
MeshReport check_mesh(const Mesh& mesh, const MeshCheckOptions& options = {});

}  // namespace polydec
