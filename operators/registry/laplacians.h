// operators/registry/laplacians.h — every Laplacian polydec offers, behind one interface, selectable by
// name (`--laplacian NAME` on the command line). Applications take an OperatorSet, so any of
// them can be compared on equal terms.
//
// Names (docs/laplacians.md describes each):
//   ours                      the paper's operator (squared-area virtual vertex, affine weights)
//   centroid, abs-area, convex, trace-min   ours with another virtual vertex (dec/surface/virtual_vertex.h)
//   split                     ours with several virtual vertices in faces whose fan is invalid
//                             (operators/surface/split_laplacian.h)
//   triangulated-minarea, triangulated-maxminangle   cotangent Laplacian of a triangulation of
//                             each polygon without new vertices (operators/comparison/triangulation.h)
//   refined                   cotangent Laplacian of the refined mesh with the virtual vertices made
//                             real; domain = refined mesh, results at its first |V| vertices
//   intrinsic-delaunay        [BS07] on the min-area triangulation (operators/comparison/intrinsic_delaunay.h)
//   aw11:LAMBDA               Alexa & Wardetzky 2011 (operators/comparison/aw11.h)
//   degoes20:LAMBDA           de Goes, Butts & Desbrun 2020 (operators/comparison/degoes20.h)
//   diamond                   Bunge, Botsch & Alexa 2021, the Diamond Laplacian (operators/comparison/diamond.h)
// A parameter follows a colon, e.g. "aw11:0.5".
#pragma once

#include <optional>
#include <string>

#include "polydec/dec/surface/refinement.h"
#include "polydec/dec/volume/refinement.h"
#include "polydec/operators/surface/laplacian.h"

namespace polydec {

// The operators of one method on its domain mesh. Conventions as in operators/surface/laplacian.h:
// S symmetric negative semi-definite, |V| x |V| of `domain`.
struct OperatorSet {
  std::string name;          // canonical name, e.g. "ours", "aw11:0.5"
  Mesh domain;               // the mesh the operators act on: the input mesh, or a refinement of it whose
                             // first n_input_vertices vertices are the input's (method "refined")
  int n_input_vertices = 0;  // read results at vertices [0, n_input_vertices)
  SparseMatrix S;            // stiffness
  SparseMatrix M;            // Galerkin (consistent) mass; empty where the method defines none
  Eigen::VectorXd M_lumped;  // lumped mass (diagonal)
  // Gradient (3k x |V|, one 3-vector per element) and divergence D = -G^T W (|V| x 3k) with
  // S = D G; empty where the method defines none.
  SparseMatrix G, D;
  // Row blocks of G that the heat method normalizes as one vector: block k is rows
  // [G_blocks[k], G_blocks[k+1]). Empty means blocks of 3 rows (one 3-vector per element).
  std::vector<int> G_blocks;
  FanQuality quality;              // fan-triangle counts where the method refines faces
  int n_degenerate_triangles = 0;  // triangle-based methods: triangles given no stiffness (zero area)
  int n_folded_triangles = 0;      // triangulations: triangles oriented against their polygon's normal
  int n_flips = 0;                 // intrinsic-delaunay: edge flips performed
  // Mean edge length of the mesh the operators are built on: the input's for polygon methods,
  // the triangulation's (diagonals included) for triangulation-based ones, the refined mesh's for
  // "refined". The heat method's time step uses the input's by default (paper section 5.5);
  // reference implementations of triangulation methods (libigl) use this one.
  double mean_edge_length = 0.0;
  // Volume methods (operators/registry/volume_laplacians.h): the sub-tetrahedron counts of the
  // refinement the operators were built on, and, when VolumeOperatorOptions::keep_refinement asked
  // for it, that refinement itself (for pictures of their fields, apps/pictures/volume_cut.h).
  SubTetQuality sub_tet_quality;
  std::optional<VolumeRefinement> volume_refinement;
  // Methods with one virtual vertex per face on the input mesh ("ours", "centroid", "abs-area",
  // "convex", "trace-min", lifted or not, and "split" where no face is split): the refinement S, M,
  // G and D were built from, so that whoever needs its fan triangles (the heat method's face-wise
  // pass, apps/applications/geodesics.h) takes them from the same object instead of refining again.
  // Empty for the other methods.
  std::optional<Refinement> refinement;
};

// A parsed method name with its parameter.
struct LaplacianChoice {
  std::string method = "ours";
  double parameter = 0.0;  // method-specific (e.g. lambda); NaN-free, validated by parse_laplacian
  bool has_parameter = false;
  std::string canonical_name() const;
};

// Parses "NAME" or "NAME:PARAM"; throws std::invalid_argument naming the known methods.
LaplacianChoice parse_laplacian(const std::string& spec);

// Names of all methods, for help texts.
std::vector<std::string> laplacian_names();

// What build_operators builds besides S, M and the lumped M, and how.
struct OperatorOptions {
  bool with_gradient = true;  // G and D too
  // With with_gradient, false leaves G and D out of a set that carries its refinement
  // (OperatorSet::refinement) and keeps them for every other method: for consumers that read the
  // fan triangles instead (the heat method's face-wise pass, apps/applications/geodesics.h).
  bool gradient_with_refinement = true;
  int threads = 1;            // assembly threads of "ours" and its virtual-vertex variants (0: all
                              // hardware threads); the results do not depend on it
  // Virtual vertices off their affine points (dec/surface/virtual_lift.h) for "ours", its virtual-vertex
  // variants and "refined"; another method with a lift other than none throws std::invalid_argument.
  // A lift appends "+lift:NAME" to OperatorSet::name (e.g. "ours+lift:sphere").
  VirtualLift lift = {};
};

// Builds the operator set of `choice` on `mesh`, e.g.
//   build_operators(mesh, parse_laplacian("aw11:0.5"), {.with_gradient = false}).
// The volume counterpart is build_volume_operators (operators/registry/volume_laplacians.h).
OperatorSet build_operators(const Mesh& mesh, const LaplacianChoice& choice,
                            const OperatorOptions& options = {});

// Shorthand for build_operators(mesh, choice, {.with_gradient = with_gradient}).
OperatorSet build_operators(const Mesh& mesh, const LaplacianChoice& choice, bool with_gradient);

// `ops` moved into the returned set without copying its sparse matrices (left empty in `ops`):
// Eigen 3.4's SparseMatrix has no move constructor, so std::move(ops) deep-copies S, M, G and D
// (~0.3 s on FINE SPHERE), e.g. into a consumer taking a set by value:
// HeatGeodesics(take_operators(ops), h).
OperatorSet take_operators(OperatorSet& ops);

}  // namespace polydec
