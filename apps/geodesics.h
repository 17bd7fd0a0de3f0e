// apps/geodesics.h — geodesic distances by the heat method (Crane et al. 2013; paper section
// 5.5, eq. 31-33) on the polygon operators.
//
// Time step t = factor * (mean edge length)^2 (factor 1 by default, as in the paper). The
// constructor assembles S, M, G, D and factors (M - t S) and the pinned Poisson matrix once;
// every distance() call then costs two back-substitutions and linear work.
// Distances are shifted so that their minimum over each connected component that contains a
// source is 0; vertices that no source reaches (other components, unreferenced vertices) get
// +infinity.
#pragma once

#include "dec/refinement.h"
#include "operators/cholesky.h"
#include "operators/laplacian.h"

#include <span>

namespace polydec {

struct HeatGeodesicsOptions {
  double time_step_factor = 1.0;  // t = factor * mean_edge_length^2
  bool lumped_mass = true;        // lumped (default, as in the paper's tables) or Galerkin mass in eq. (31)
  RefinementOptions refinement;
};

class HeatGeodesics {
 public:
  HeatGeodesics(const Mesh& mesh, const HeatGeodesicsOptions& options = {});

  // Distances from the given source vertices (at least one; throws std::out_of_range for a
  // vertex index outside the mesh).
  Eigen::VectorXd distance(std::span<const int> sources) const;
  Eigen::VectorXd distance(int source) const { return distance(std::span<const int>(&source, 1)); }

  double time_step() const { return t_; }
  const Refinement& refinement() const { return refinement_; }

 private:
  Mesh mesh_;
  HeatGeodesicsOptions options_;
  Refinement refinement_;
  double t_ = 0;
  SparseMatrix M_, G_, D_;
  Eigen::VectorXd M_lumped_;
  std::vector<int> component_;        // component id per vertex, -1 for unreferenced
  std::vector<unsigned char> pinned_;  // vertices fixed to 0 in the Poisson solve
  std::unique_ptr<SparseCholesky> heat_, poisson_;
};

// Root-mean-square of (a - b).
double rmse(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

}  // namespace polydec
