// dec/mesh/volume_mesh.h — the polyhedral volume mesh: positions (|V| x 3), polygonal faces (each
// stored once), cells as closed cycles of oriented faces (half-faces), and the connectivity
// derived once at construction. Immutable after validation; the volume counterpart of Mesh.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <polydec/dec/mesh/mesh.h>

namespace polydec {

// Raw polyhedral data, as a reader or generator produces it, before validation.
// Face f has the vertices face_indices[face_offsets[f] .. face_offsets[f+1]). Cell c has the
// half-faces cell_halffaces[cell_offsets[c] .. cell_offsets[c+1]): half-face 2f is face f with its
// vertices as listed, 2f+1 the same face reversed (the OpenVolumeMesh convention).
struct PolyhedronSoup {
  Eigen::MatrixX3d positions;        // |V| x 3
  std::vector<int> face_offsets{0};  // |F| + 1 entries
  std::vector<int> face_indices;
  std::vector<int> cell_offsets{0};  // |C| + 1 entries
  std::vector<int> cell_halffaces;
  CoordinatePrecision precision;  // what the source's digits resolve (dec/mesh/mesh.h)

  int n_vertices() const { return int(positions.rows()); }
  int n_faces() const { return int(face_offsets.size()) - 1; }
  int n_cells() const { return int(cell_offsets.size()) - 1; }
  int add_face(std::span<const int> f);        // returns the new face's index
  void add_cell(std::span<const int> halffaces);
};

// A validated polyhedral mesh (throws InvalidMeshError, element "vertex", "face", "cell" or
// "edge" with its index, on the first violation).
//
// Validation: finite coordinates of magnitude at most kMaxVolumeCoordinate; faces with at least 3
// distinct vertices in range; every face used by one or two cells, at most once per cell; each
// cell closed (every edge of its half-faces used exactly twice, in opposite directions) and
// connected; a face shared by two cells appears as 2f in one and 2f+1 in the other (consistent
// orientation). Orientation: after validation every cell's half-faces have right-hand normals
// pointing out of the cell. If the soup's cells are consistently oriented inward (negative total
// signed volume, as in the OVM files of polyLaplace), every half-face is flipped once; the
// per-cell signed volumes are not otherwise used to reorient, so a mesh whose cells disagree
// with each other is rejected rather than silently repaired.
// Largest accepted coordinate magnitude of a volume mesh: the volume kernels work in coordinates
// relative to each element, scaled by a power of two (dec/detail/scale.h), so they need only the
// differences and sums of a cell's coordinates to stay finite. What an operator's entries (length^k)
// cannot represent is refused when it is built (check_length_power()).
inline constexpr double kMaxVolumeCoordinate = 1e300;

class VolumeMesh {
 public:
  VolumeMesh() = default;
  explicit VolumeMesh(PolyhedronSoup soup);

  // The same connectivity and coordinate precision with new positions (|V| x 3, finite); shares
  // connectivity.
  VolumeMesh with_positions(Eigen::MatrixX3d positions) const;
  // The same mesh with another coordinate precision (noise and planarity tolerance in [0, 1)).
  VolumeMesh with_precision(const CoordinatePrecision& precision) const;
  // What the coordinates resolve, relative to rms_radius(), as on surfaces (Mesh::precision()):
  // recorded by the readers from the file's digits (float32: half an ulp), 0 (exact doubles) for
  // generated meshes. Decides which nearly planar faces count as planar for the face points'
  // least-norm weights (dec/volume/refinement.h) and in `polydec info`.
  const CoordinatePrecision& precision() const { return precision_; }
  // Root-mean-square distance of the vertices from their mean: the size the precision refers to.
  double rms_radius() const;
  // The coordinates' absolute uncertainty, precision().noise * rms_radius().
  double coordinate_noise() const { return precision_.noise * rms_radius(); }

  const Eigen::MatrixX3d& positions() const { return positions_; }
  Eigen::Vector3d position(int v) const { return positions_.row(v).transpose(); }

  int n_vertices() const { return int(positions_.rows()); }
  int n_edges() const { return int(topo_->edges.rows()); }
  int n_faces() const { return int(topo_->face_offsets.size()) - 1; }
  int n_cells() const { return int(topo_->cell_offsets.size()) - 1; }

  // Faces: vertex cycles as given in the soup.
  std::span<const int> face(int f) const {
    const auto& o = topo_->face_offsets;
    return {topo_->face_indices.data() + o[f], size_t(o[f + 1] - o[f])};
  }
  int face_size(int f) const { return topo_->face_offsets[f + 1] - topo_->face_offsets[f]; }
  const std::vector<int>& face_offsets() const { return topo_->face_offsets; }
  const std::vector<int>& face_indices() const { return topo_->face_indices; }
  // The (up to) two cells of face f: [0] the cell that has half-face 2f, [1] the one with 2f+1;
  // -1 where there is none. Boundary faces have exactly one -1.
  std::array<int, 2> face_cells(int f) const { return topo_->face_cells[f]; }
  bool is_boundary_face(int f) const { return face_cells(f)[0] < 0 || face_cells(f)[1] < 0; }

  // Cells: half-faces (2f or 2f+1) whose right-hand normals point out of the cell.
  std::span<const int> cell(int c) const {
    const auto& o = topo_->cell_offsets;
    return {topo_->cell_halffaces.data() + o[c], size_t(o[c + 1] - o[c])};
  }
  int cell_size(int c) const { return topo_->cell_offsets[c + 1] - topo_->cell_offsets[c]; }
  // Vertices of cell c, ascending, without repetition.
  std::span<const int> cell_vertices(int c) const {
    const auto& o = topo_->cell_vertex_offsets;
    return {topo_->cell_vertex_indices.data() + o[c], size_t(o[c + 1] - o[c])};
  }

  // Undirected edges: |E| x 2, row e = (i, j) with i < j, lexicographic order.
  const Eigen::MatrixX2i& edges() const { return topo_->edges; }
  bool is_boundary_vertex(int v) const { return topo_->vertex_is_boundary[v] != 0; }
  int n_unreferenced_vertices() const { return topo_->n_unreferenced; }

  // The boundary surface (boundary faces, oriented outward) as a surface Mesh on all |V|
  // vertices (interior vertices unreferenced, the same coordinate precision: the same positions,
  // so the same rms_radius), so every surface tool applies to it.
  Mesh boundary_surface() const;

  // Signed volume of cell c (divergence theorem over its half-faces, each split into triangles
  // around its vertex centroid, so independent of where a face's vertex cycle starts; positive
  // after validation's orientation) and the total. Both throw InvalidMeshError when the volume
  // lies outside double's normal range (overflow near kMaxVolumeCoordinate, or underflow).
  double cell_volume(int c) const;
  double volume() const;

  double mean_edge_length() const;
  double bounding_box_diagonal() const;

 private:
  struct Topology {
    std::vector<int> face_offsets{0}, face_indices;
    std::vector<int> cell_offsets{0}, cell_halffaces;
    std::vector<int> cell_vertex_offsets{0}, cell_vertex_indices;
    std::vector<std::array<int, 2>> face_cells;
    Eigen::MatrixX2i edges;
    std::vector<unsigned char> vertex_is_boundary;
    int n_unreferenced = 0;
  };
  Eigen::MatrixX3d positions_;
  CoordinatePrecision precision_;
  std::shared_ptr<const Topology> topo_ = std::make_shared<Topology>();
};

// Throws InvalidMeshError (element "edge": the shortest or the longest edge) when quantities that
// scale as length^power (a mass or star0: 3, a stiffness or star1: 1, a gradient: -1, star3: -3)
// cannot be held in double with full precision on this mesh: that edge's length^power must lie
// within 2^-960 .. 2^960. `what` names the quantity in the message. Called by the volume
// operators and stars before they are assembled.
void check_length_power(const VolumeMesh& mesh, int power, const std::string& what);

// One quantity for check_length_powers(): its power of length and its name in the message.
struct LengthPower {
  int power = 0;
  std::string what;
};

// check_length_power() for several quantities with one pass over the edges (the first failing
// quantity, in the given order, throws).
void check_length_powers(const VolumeMesh& mesh, const std::vector<LengthPower>& quantities);

// The stars star_0 .. star_max_degree as such quantities: star_k scales as length^(3 - 2k).
std::vector<LengthPower> star_length_powers(int max_degree);

}  // namespace polydec
