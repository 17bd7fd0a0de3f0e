// apps/applications/geodesics.h — geodesic distances by the heat method (Crane et al. 2013; paper section
// 5.5, eq. 31-33) on the polygon operators.
//
// Time step t = factor * (mean edge length of the input mesh)^2 (factor 1 by default, as in the
// paper). The constructor factors (M - t S) and the pinned Poisson matrix -S once; every
// distance() call then costs a forward solve over the sources' reach in the elimination tree, three
// full triangular solves and linear work. Works with any
// OperatorSet that has G and D (operators/registry/laplacians.h), including the volume ones of
// operators/registry/volume_laplacians.h (pass the volume mesh's mean edge length); sources and results are
// indexed by the input mesh's vertices.
// Distances are shifted so that their minimum over each connected component that contains a
// source is 0; vertices that no source reaches get +infinity: other components, unreferenced
// vertices, and vertices held only by zero-area faces (components are those of S's non-zero
// pattern, so a strip of zero-area faces separates, as it does for the heat flow).
#pragma once

#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/registry/laplacians.h"

#include <limits>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

namespace polydec {

struct HeatGeodesicsOptions {
  double time_step_factor = 1.0;  // t = factor * mean_edge_length^2
  bool lumped_mass = true;        // lumped (default, as in the paper's tables) or Galerkin mass in eq. (31)
  // Right-hand side of eq. (31): M delta (the paper's equation) or delta alone (what the authors'
  // program solves; identical up to a factor with lumped mass, different with Galerkin mass: their
  // Table 6 "un-lumped" column is reproduced only with delta).
  bool mass_weighted_source = true;
};

// How far the heat step (eq. 31) carries. Its solution decays like exp(-d / sqrt(t)) with the distance
// d from the sources; where it falls below what the solve resolves, its gradient and so the distance
// are noise. For the direct solver that is double precision's range (values below 1e-280 of the
// maximum): about 650 sqrt(t) from the sources, 650 mean edge lengths at the paper's t = h^2, so
// meshes more than ~650 edges across need a larger time step factor (suggested_time_factor).
struct HeatDiagnostics {
  int unresolved_vertices = 0;  // reached vertices whose heat value lies below the resolution
  double resolved_radius = 0;   // the largest distance among the reached vertices that are resolved
};

// The time step factor that makes the heat step reach 1.25 `extent` (`extent` e.g. the bounding-box
// diagonal), from a run at `factor`: the implicit step decays per mean edge length by
// kappa(f) = 2 asinh(1 / (2 sqrt(f))) (1 / sqrt(f) for large f: reach ~ sqrt(t); ln(1 / f) for
// small f), so the result f' solves kappa(f') = kappa(factor) resolved_radius / (1.25 extent);
// for large factors that is factor * (1.25 extent / resolved_radius)^2. `factor` itself when
// nothing was unresolved (never less than `factor`). One suggestion from any factor in [1e-4, 1]
// resolves the [geodesics] strip.
double suggested_time_factor(double factor, const HeatDiagnostics& diagnostics, double extent);

namespace detail {
// HeatGeodesics' fan triangles, face by face in the order of each face's first row in the factors'
// order (so that consecutive faces read nearby rows of distances()'s blocks): per face the offset
// of its corners; per corner its vertex, its weight in the face's virtual vertex, whether the fan
// triangle from it to the next corner and the virtual vertex is degenerate, and that triangle in
// its own frame (3 values).
struct HeatFanTable {
  std::vector<int> offsets, corners;
  std::vector<double> weights, frames;
  std::vector<unsigned char> degenerate;
};
}  // namespace detail

class HeatGeodesics {
 public:
  // With the paper's operator ("ours"), built without G and D (the face-wise pass reads the fan
  // triangles of the refinement instead; operators().G and .D are empty).
  explicit HeatGeodesics(const Mesh& mesh, const HeatGeodesicsOptions& options = {});
  // With any operator set; `mean_edge_length` sets the time step (that of the input mesh). A set
  // that carries its refinement (OperatorSet::refinement; G and D, if present, must be those of its
  // fan triangles) is solved face by face from it and needs no G and D
  // (OperatorOptions::gradient_with_refinement = false); any other through its G and D.
  HeatGeodesics(OperatorSet operators, double mean_edge_length, const HeatGeodesicsOptions& options = {});

  // Distances from the given source vertices (at least one; throws std::out_of_range for a
  // vertex index outside the mesh). Calls on one object run one at a time (they share the
  // factors' workspaces and the buffers below).
  Eigen::VectorXd distance(std::span<const int> sources) const { return distance(sources, nullptr); }
  // The same, and how far the heat step was resolved (HeatDiagnostics) when `diagnostics` is given.
  Eigen::VectorXd distance(std::span<const int> sources, HeatDiagnostics* diagnostics) const;
  Eigen::VectorXd distance(int source) const { return distance(std::span<const int>(&source, 1)); }

  // One distance field per source (unlike distance(sources), the distance to the set): column c
  // holds the distances from sources[c], |V| x k, equal to distance(sources[c]) up to round-off.
  // Solved as blocks of up to `block` right-hand sides stored row by row in the factors' order
  // (SparseCholesky::solve_rows_in_factor_order), and the normalized gradient (eq. 32) and its
  // divergence fused in one pass: face by face for a set that carries its refinement, else over a
  // row-major copy of G made for the call. The two blocks (2 |V| min(block, k) doubles: 98 MB for
  // 64 columns on FINE SPHERE) are kept for the next call of the same width, as fresh pages cost
  // more than the passes that fill them; release_blocks() frees them. Throws as distance() does;
  // std::invalid_argument for block < 1.
  Eigen::MatrixXd distances(std::span<const int> sources, int block = 64) const;
  // The same written into `out` (|V| x k: a matrix, or k columns of a larger one, e.g. of an
  // all-pairs matrix). No new matrix is made and nothing is copied: a caller that reuses `out`
  // pays no fresh pages for the result (49 MB for 64 columns on FINE SPHERE). Throws as above, and
  // std::invalid_argument when `out` has another shape (then nothing is written).
  void distances(std::span<const int> sources, Eigen::Ref<Eigen::MatrixXd> out, int block = 64) const;
  // Frees the blocks distances() keeps.
  void release_blocks() const;

  double time_step() const { return t_; }
  const OperatorSet& operators() const { return ops_; }

 private:
  // std::out_of_range for no source, or one outside the mesh or without stiffness.
  void check_sources(std::span<const int> sources) const;

  OperatorSet ops_;
  HeatGeodesicsOptions options_;
  double t_ = 0;
  std::vector<int> component_;        // component id per vertex, -1 for unreferenced
  std::vector<unsigned char> pinned_;  // vertices fixed to 0 in the Poisson solve
  std::unique_ptr<SparseCholesky> heat_, poisson_;
  // For operator sets that carry their refinement (OperatorSet::refinement: "ours" and the other
  // one-virtual-vertex methods): their fan triangles, from which eqs. (32)-(33)'s gradient,
  // normalization and divergence run face by face without reading G and D. Empty for other
  // operator sets (their G and D are used).
  detail::HeatFanTable fan_;
  // distance()'s buffers, kept between calls: the heat step's right-hand side, u, the Poisson
  // right-hand side and its solution; the lock that serializes distance() and distances() (the
  // Python binding calls them without the GIL).
  std::unique_ptr<std::mutex> lock_ = std::make_unique<std::mutex>();
  mutable std::vector<int> work_rows_;
  mutable std::vector<double> work_values_;
  mutable Eigen::VectorXd work_u_, work_b_, work_d_;
  // distances()'s two blocks of block_cells_ values each, on huge pages.
  mutable std::unique_ptr<double[]> block_u_, block_b_;
  mutable size_t block_cells_ = 0;
};

// Root-mean-square of (a - b).
double rmse(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

}  // namespace polydec
