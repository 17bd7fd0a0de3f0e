// bench/gc_like_heat.h — a geometry-central-like heat-geodesics path, the benchmark's timed stand-in
// for geometry-central's PolygonMeshHeatSolver (which cannot be built here). It mirrors that
// solver's per-source work as read from its source, written here, not their code: de Goes, Butts &
// Desbrun 2020 operators (lambda 1), t = mean edge length squared, heat operator M_lumped - t S and
// Poisson operator -S each factored by CHOLMOD's simplicial LDL^T through the long-integer
// interface, and per source two dense CHOLMOD solves around G, the per-face normalization and D.
// Compiled only where CHOLMOD is found (POLYDEC_HAVE_GC_LIKE_HEAT).
#pragma once

#include <Eigen/Dense>
#include <memory>

#include "polydec/dec/mesh/mesh.h"

namespace gc_like_heat {

// The precomputation once (constructor), then distance(source) per source. Not thread-safe: the
// solves share one CHOLMOD workspace.
class GcLikeHeat {
 public:
  // Operators and both factorizations. supernodal = true factors with CHOLMOD's supernodal LDL^T
  // instead (still the long-integer interface, default orderings): for meshes where the simplicial
  // factorization would take too long; geometry-central's own path is simplicial.
  explicit GcLikeHeat(const polydec::Mesh& mesh, bool supernodal = false);
  ~GcLikeHeat();
  GcLikeHeat(const GcLikeHeat&) = delete;
  GcLikeHeat& operator=(const GcLikeHeat&) = delete;

  // Distances from one vertex, shifted to zero at their minimum; throws std::runtime_error if a
  // right-hand side is not finite, as geometry-central's solver checks.
  Eigen::VectorXd distance(int source);

  // Non-zeros of both factors (CHOLMOD's count of the factors' stored entries, diagonal included).
  double factor_nonzeros() const;
  // Whether the factors are supernodal (as asked for, and as CHOLMOD made them).
  bool supernodal() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gc_like_heat
