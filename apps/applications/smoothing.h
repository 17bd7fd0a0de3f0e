// apps/applications/smoothing.h — conformalized mean curvature flow (Kazhdan et al. 2012; paper section 5.1,
// eq. 28, Figures 4-5): the stiffness S^0 of the input mesh is kept, the mass M^t is
// re-assembled on the current positions, and every step solves
//   (M^t - eps S^0) X^{t+eps} = M^t X^t.
// After each step the mesh is translated so that its area centroid (lumped-mass weighted) is
// at the origin and scaled uniformly back to the input's surface area.
#pragma once

#include <memory>

#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec {

struct SmoothingOptions {
  // eps (units of area). 0 picks eps = 1e-3 * (surface area of the input), which does the same
  // to a mesh and to a scaled copy of it.
  double time_step = 0;
  bool lumped_mass = true;  // lumped (default) or Galerkin M^t
};

class CurvatureFlow {
 public:
  // With the Laplacian `choice` (any method whose operators live on the input mesh's vertices;
  // std::invalid_argument otherwise). S^0 is built once; M^t is re-assembled every step — for
  // the virtual-vertex methods ("ours", "centroid") on the kept sparsity pattern and refinement
  // options.
  explicit CurvatureFlow(const Mesh& mesh, const SmoothingOptions& options = {},
                         const LaplacianChoice& choice = parse_laplacian("ours"));

  // One step of eq. (28) followed by re-centering and re-scaling; returns the new mesh.
  // Throws SolverError when M^t - eps S^0 cannot be factored.
  const Mesh& step();

  const Mesh& mesh() const { return mesh_; }
  double time_step() const { return eps_; }
  double area() const { return area_; }  // the input's area, kept after every step
  const std::string& laplacian_name() const { return name_; }

 private:
  struct MassAssembler;
  Mesh mesh_;
  SmoothingOptions options_;
  LaplacianChoice choice_;
  std::string name_;
  SparseMatrix S0_;
  SparseMatrix M_;            // mass on the current positions (diagonal when lumped)
  Eigen::VectorXd M_lumped_;  // lumped mass on the current positions
  double eps_ = 0, area_ = 0;
  std::shared_ptr<MassAssembler> assembler_;
  std::unique_ptr<SparseCholesky> chol_;
  void assemble_mass();
};

// Runs `steps` steps and returns every mesh (the input first, then one per step).
std::vector<Mesh> curvature_flow(const Mesh& mesh, int steps, const SmoothingOptions& options = {},
                                 const LaplacianChoice& choice = parse_laplacian("ours"));

}  // namespace polydec
