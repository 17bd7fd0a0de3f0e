// apps/applications/mesh_statistics.h — what `polydec info` reports about a mesh: counts, face-valence
// histogram, boundary loops, Euler characteristic and genus, planarity and convexity of the
// faces, and the fan quality of the paper's refinement.
#pragma once

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/refinement.h"

#include <map>

namespace polydec {

struct MeshStatistics {
  int vertices = 0, faces = 0, edges = 0, halfedges = 0;
  int boundary_edges = 0, unreferenced_vertices = 0, components = 0;
  std::vector<int> boundary_loop_lengths;
  std::map<int, int> valence_histogram;  // face size -> count
  int euler_characteristic = 0;
  // Sum over components of the genus, from chi = sum_c (2 - 2 g_c - b_c) (orientable surfaces).
  int genus = 0;
  double mean_edge_length = 0, bounding_box_diagonal = 0;
  // Planarity: per face, the largest distance of a corner to its least-squares plane divided by
  // the face's diameter. Faces above `planarity_tolerance` count as non-planar.
  double planarity_tolerance = 1e-5;
  double max_nonplanarity = 0, mean_nonplanarity = 0;
  int nonplanar_faces = 0;
  // Convexity, in each face's least-squares plane: convex faces; non-convex but star-shaped with
  // respect to the paper's virtual vertex (all fan triangles valid); neither.
  int convex_faces = 0, nonconvex_faces = 0;
  FanQuality fan;  // of the squared-area refinement
};

MeshStatistics mesh_statistics(const Mesh& mesh);

}  // namespace polydec
