// dec/mesh/mesh.h — the polygon mesh: positions (|V| x 3), faces as offsets + indices, and the
// connectivity derived once at construction (edges, halfedges, boundary loops, vertex-face
// adjacency). Immutable after validation.
#pragma once

#include "polydec/dec/mesh/eigen_abi.h"
#include <Eigen/Dense>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace polydec {

// The precision the vertex coordinates carry, relative to the mesh's size (Mesh::rms_radius()),
// so that it moves, turns and scales with the mesh (Mesh::with_positions keeps it). Readers
// record what the file's digits resolve (dec/io/mesh_io.h); generated and in-memory data default to 0,
// i.e. exact doubles (only their round-off counts). Decides which nearly planar polygons count as
// planar for the least-norm virtual-vertex weights (dec/surface/virtual_vertex.h, dec/surface/refinement.h).
struct CoordinatePrecision {
  double noise = 0.0;  // largest uncertainty of a coordinate / rms_radius()
  // Overrides `noise` when > 0: a polygon whose out-of-plane extent is at most this fraction of
  // its size counts as planar (the fixed cut of earlier versions was 1e-5).
  double planarity_tolerance = 0.0;
  bool operator==(const CoordinatePrecision&) const = default;
};

// Raw polygon data, as a reader or generator produces it, before validation.
// Face f has the vertex indices face_indices[face_offsets[f] .. face_offsets[f+1]).
struct PolygonSoup {
  Eigen::MatrixX3d positions;        // |V| x 3
  std::vector<int> face_offsets{0};  // |F| + 1 entries, starts at 0
  std::vector<int> face_indices;     // sum of face valences
  CoordinatePrecision precision;     // what the source's digits resolve

  int n_vertices() const { return int(positions.rows()); }
  int n_faces() const { return int(face_offsets.size()) - 1; }
  void add_face(std::span<const int> f);
};

// Thrown when a soup is not a valid polygon mesh. `element` names the kind of element
// ("face", "vertex", "edge") and `index` which one, so callers can point at the culprit.
class InvalidMeshError : public std::runtime_error {
 public:
  InvalidMeshError(std::string element, long index, const std::string& what);
  std::string element;
  long index;
};

// Root-mean-square distance of the rows of X (|V| x 3) from their mean; 0 for no rows.
double rms_radius(const Eigen::MatrixX3d& X);

// Throws InvalidMeshError (element "mesh") unless the noise and planarity tolerance of p are in
// [0, 1) (what Mesh and VolumeMesh accept).
void check_coordinate_precision(const CoordinatePrecision& p);

// A validated polygon mesh.
//
// Halfedges are face corners: halfedge h is position h in face_indices(); it starts at
// vertex face_indices()[h] and ends at the next corner of the same face. Undirected edges are
// numbered in lexicographic order of (i, j) with i < j. Validation rejects faces with fewer
// than 3 vertices, indices out of range, a vertex repeated in a face, an edge shared by more
// than two faces or by two faces with the same direction (inconsistent orientation), and
// non-finite coordinates or coordinates of magnitude above kMaxCoordinate. Unreferenced vertices are accepted and counted: every operator
// gives them zero rows and columns.
// Largest accepted coordinate magnitude: the operators form fourth powers of lengths (squared
// areas), which stay finite in double up to about 1e77.
inline constexpr double kMaxCoordinate = 1e75;

class Mesh {
 public:
  Mesh() = default;
  explicit Mesh(PolygonSoup soup);  // throws InvalidMeshError

  // The same connectivity and coordinate precision with new positions (|V| x 3, finite);
  // cheap: shares connectivity. Moved positions resolve no more than the ones they came from.
  Mesh with_positions(Eigen::MatrixX3d positions) const;
  // The same mesh with another coordinate precision (e.g. a user's planarity tolerance).
  Mesh with_precision(const CoordinatePrecision& precision) const;
  const CoordinatePrecision& precision() const { return precision_; }
  // Root-mean-square distance of the vertices from their mean: the size the precision refers to.
  double rms_radius() const;
  // The coordinates' absolute uncertainty, precision().noise * rms_radius().
  double coordinate_noise() const { return precision_.noise * rms_radius(); }

  const Eigen::MatrixX3d& positions() const { return positions_; }
  Eigen::Vector3d position(int v) const { return positions_.row(v).transpose(); }

  int n_vertices() const { return int(positions_.rows()); }
  int n_faces() const { return int(topo_->face_offsets.size()) - 1; }
  int n_halfedges() const { return int(topo_->face_indices.size()); }
  int n_edges() const { return int(topo_->edges.rows()); }

  const std::vector<int>& face_offsets() const { return topo_->face_offsets; }
  const std::vector<int>& face_indices() const { return topo_->face_indices; }
  std::span<const int> face(int f) const {
    const auto& o = topo_->face_offsets;
    return {topo_->face_indices.data() + o[f], size_t(o[f + 1] - o[f])};
  }
  int face_size(int f) const { return topo_->face_offsets[f + 1] - topo_->face_offsets[f]; }
  int max_face_size() const { return topo_->max_face_size; }

  // Halfedge (corner) queries.
  int halfedge_face(int h) const { return topo_->halfedge_face[h]; }
  int halfedge_next(int h) const {
    const int f = topo_->halfedge_face[h];
    return h + 1 < topo_->face_offsets[f + 1] ? h + 1 : topo_->face_offsets[f];
  }
  int halfedge_source(int h) const { return topo_->face_indices[h]; }
  int halfedge_target(int h) const { return topo_->face_indices[halfedge_next(h)]; }
  int halfedge_edge(int h) const { return topo_->halfedge_edge[h]; }
  int halfedge_opposite(int h) const { return topo_->halfedge_opposite[h]; }  // -1 on boundary

  // Undirected edges: |E| x 2, row e = (i, j) with i < j, lexicographic order.
  const Eigen::MatrixX2i& edges() const { return topo_->edges; }
  bool is_boundary_edge(int e) const { return topo_->edge_is_boundary[e] != 0; }
  int n_boundary_edges() const { return topo_->n_boundary_edges; }

  // Boundary loops, each a vertex sequence in the direction of its boundary halfedges.
  const std::vector<std::vector<int>>& boundary_loops() const { return topo_->boundary_loops; }
  bool is_boundary_vertex(int v) const { return topo_->vertex_is_boundary[v] != 0; }

  // Faces around vertex v, ascending.
  std::span<const int> vertex_faces(int v) const {
    const auto& o = topo_->vertex_face_offsets;
    return {topo_->vertex_face_indices.data() + o[v], size_t(o[v + 1] - o[v])};
  }
  int n_unreferenced_vertices() const { return topo_->n_unreferenced; }
  int n_components() const { return topo_->n_components; }
  int euler_characteristic() const { return n_vertices() - n_edges() + n_faces(); }

  // Length scale: mean edge length (used for relative tolerances and the heat time step).
  double mean_edge_length() const;
  // Diagonal of the axis-aligned bounding box.
  double bounding_box_diagonal() const;

 private:
  struct Topology {
    std::vector<int> face_offsets{0}, face_indices;
    std::vector<int> halfedge_face, halfedge_edge, halfedge_opposite;
    Eigen::MatrixX2i edges;
    std::vector<unsigned char> edge_is_boundary, vertex_is_boundary;
    std::vector<std::vector<int>> boundary_loops;
    std::vector<int> vertex_face_offsets{0}, vertex_face_indices;
    int n_boundary_edges = 0, n_unreferenced = 0, n_components = 0, max_face_size = 0;
  };
  Eigen::MatrixX3d positions_;
  CoordinatePrecision precision_;
  std::shared_ptr<const Topology> topo_ = std::make_shared<Topology>();
};

}  // namespace polydec
