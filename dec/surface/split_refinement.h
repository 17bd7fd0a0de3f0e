// dec/surface/split_refinement.h — several virtual vertices in one face (the paper's section 6 asks
// for non-convex polygons): a face whose squared-area fan is invalid is cut by interior diagonals
// into the fewest pieces whose own squared-area virtual vertices give valid fans, one virtual
// vertex per piece. Faces with a valid fan stay one piece, with the paper's weights and point.
// The DEC of this folder (P1, P2, the stars) keeps one virtual vertex per face; this refinement
// serves the 0-form operators (operators/surface/split_laplacian.h).
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec {

// How faces are split.
struct SplitOptions {
  // Fan triangles count as degenerate as in RefinementOptions::degenerate_tolerance.
  double degenerate_tolerance = 1e-8;
  int max_pieces = 4;    // pieces tried: 2 .. max_pieces (exhaustive over max_pieces - 1 diagonals)
  int max_corners = 16;  // larger faces with an invalid fan are not searched (kept whole, counted)
};

// The pieces of one polygon: each piece lists the polygon's corner indices (0 .. n-1) it spans, in
// the polygon's cyclic order starting at its smallest index. `worst` is the smallest
// 2 area / longest edge^2 over all fan triangles of all pieces (negative: an inverted triangle).
struct PolygonSplit {
  std::vector<std::vector<int>> pieces;
  double worst = 0.0;
  bool valid = false;  // every fan triangle of every piece valid
};

// The quality 2 area / (longest edge)^2 of the fan triangle (a, b, x) of a polygon with vector area
// `normal`: negative when the triangle is oriented against it; 0 up to the `degenerate_tolerance`
// (then reported as 0).
double fan_triangle_quality(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& x,
                            const Eigen::Vector3d& normal, double degenerate_tolerance);

// The interior diagonals (i, j), i < j, of polygon X (n x 3; tested in its best-fit plane): the
// segments between non-adjacent corners inside the polygon that touch its boundary only at their
// ends. Lexicographic order.
std::vector<std::pair<int, int>> interior_diagonals(const PolygonPositions& X);

// The best split of polygon X (n x 3): the whole polygon when its squared-area fan is valid, else the
// fewest pieces (2 .. max_pieces) cut by non-crossing interior diagonals such that each piece's own
// squared-area fan is valid, ties broken by the largest `worst` (equal to 1e-9 relative: the first in
// lexicographic order of the diagonals). When none exists (or n exceeds
// max_corners) the whole polygon, with valid = false.
// The pieces' weights use planarity_cut(planarity_tolerance, noise, piece corners) (virtual_vertex.h).
PolygonSplit split_polygon(const PolygonPositions& X, const SplitOptions& options = {},
                           double planarity_tolerance = 0.0, double noise = 0.0);

// The split refinement of a mesh. Pieces are numbered face by face; piece p of face f covers the
// face's local corners corners[corner_offsets[p] .. corner_offsets[p+1]) (in face order), with the
// squared-area weights of the piece on them (summing to 1) and the virtual point x_p.
struct SplitRefinement {
  SplitOptions options;
  std::vector<int> piece_offsets;   // |F| + 1
  std::vector<int> corner_offsets;  // n_pieces + 1
  std::vector<int> corners;         // face-local corner index per piece corner
  std::vector<double> weights;      // one per piece corner
  Eigen::MatrixX3d virtual_points;  // n_pieces x 3
  FanQuality before;                // the single squared-area fans (the paper's refinement)
  FanQuality after;                 // the pieces' fans
  int n_faces_split = 0;            // faces cut into two or more pieces
  int n_faces_unsplittable = 0;     // faces with an invalid fan and no valid split
  std::vector<int> pieces_histogram;  // [k]: faces of k pieces (k = 1 .. max_pieces)
  double worst_before = 0.0;        // smallest fan-triangle quality 2 area / longest^2, single fans
  double worst_after = 0.0;         // the same over the pieces' fans
  int n_pieces() const { return int(corner_offsets.size()) - 1; }
};

// Splits every face of `mesh` whose squared-area fan (refine(mesh), the paper's) is invalid.
// Faces with a valid fan keep the refinement's weights and virtual point, bit for bit.
SplitRefinement split_refine(const Mesh& mesh, const SplitOptions& options = {});

// The refined triangles: vertices 0 .. |V|-1 the mesh's, |V| + p the virtual vertex of piece p; one
// triangle (a, b, |V| + p) per edge (a, b) of piece p (polygon edges and diagonals), pieces in order.
std::vector<Eigen::Vector3i> split_triangles(const Mesh& mesh, const SplitRefinement& split);

// The positions of the refined vertices ((|V| + n_pieces) x 3).
Eigen::MatrixX3d split_positions(const Mesh& mesh, const SplitRefinement& split);

// The prolongation P ((|V| + n_pieces) x |V|): the identity on the mesh's vertices, one row of the
// piece's weights per virtual vertex (zero on the face's other corners). Rows sum to 1.
Eigen::SparseMatrix<double> split_prolongation(const Mesh& mesh, const SplitRefinement& split);

}  // namespace polydec
