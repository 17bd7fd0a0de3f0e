// apps/applications/volume/poisson.h — the 3D Franke Poisson study on polyhedral volume meshes:
// Delta f = b in the unit cube with Dirichlet values on the boundary vertices, discretized with
// a volume Laplacian of operators/registry/volume_laplacians.h as S f = M b at the interior vertices.
//
// The 3D Franke function is the trivariate extension used by polyLaplace (Bunge, Botsch et al.,
// src/Volume/Franke_PoissonSystem_3D.cpp, function franke3d) and by PolyFEM's Franke3dProblem:
//   f = 3/4 exp(-((9x-2)^2 + (9y-2)^2 + (9z-2)^2) / 4)
//     + 3/4 exp(-(9x+1)^2 / 49 - (9y+1) / 10 - (9z+1) / 10)
//     + 1/2 exp(-((9x-7)^2 + (9y-3)^2 + (9z-5)^2) / 4)
//     - 1/5 exp(-(9x-4)^2 - (9y-7)^2 - (9z-5)^2).
// Its Laplacian is derived term by term in volume_poisson.cpp (tested against finite differences).
//
// Errors: e = f - f* at the vertices; the mass-weighted L2 error sqrt(e^T M e) and, as polyLaplace
// reports it, the root mean square of e over all vertices (boundary ones included, where e = 0).
// h is the mean edge length. M is the Galerkin mass by default (right-hand side and error norm; on
// the shared cubes only it makes the error decrease from level 1 on, docs/volumes.md);
// lumped_mass = true uses the lumped mass, as the surface study does by default.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "polydec/dec/mesh/volume_mesh.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec {

// The 3D Franke function and its exact Laplacian f_xx + f_yy + f_zz.
double franke3d(double x, double y, double z);
double franke3d_laplacian(double x, double y, double z);

using ScalarField3 = std::function<double(const Eigen::Vector3d&)>;

struct VolumePoissonError {
  double h = 0;          // mean edge length
  double l2_error = 0;   // sqrt(e^T M e) (M Galerkin or lumped, as the solve used)
  double rms_error = 0;  // sqrt(sum_v e_v^2 / |V|), all vertices
  int n_vertices = 0, n_cells = 0, n_boundary = 0;
  Eigen::VectorXd solution, exact;
};

// Solves S f = M b with b = laplacian(x_v) at the interior vertices, f = exact(x_v) at the boundary
// vertices, and measures the error against exact. Throws std::invalid_argument on a mesh without
// boundary vertices.
VolumePoissonError volume_dirichlet_poisson(const OperatorSet& operators, const VolumeMesh& mesh,
                                            const ScalarField3& exact, const ScalarField3& laplacian,
                                            bool lumped_mass = false);
// The same with the exact solution and its Laplacian given at the vertices (|V| values each).
VolumePoissonError volume_dirichlet_poisson(const OperatorSet& operators, const VolumeMesh& mesh,
                                            const Eigen::VectorXd& exact, const Eigen::VectorXd& laplacian,
                                            bool lumped_mass = false);
// The Franke problem (franke3d, franke3d_laplacian) on a mesh of the unit cube, with the volume
// Laplacian `laplacian` (operators/registry/volume_laplacians.h; default "ours").
VolumePoissonError volume_franke_poisson(const VolumeMesh& mesh, bool lumped_mass = false,
                                         const LaplacianChoice& laplacian = {});
// The same with operators of `mesh` the caller already built (S, M and the lumped M).
VolumePoissonError volume_franke_poisson(const OperatorSet& operators, const VolumeMesh& mesh,
                                         bool lumped_mass = false);

struct VolumeConvergenceSeries {
  std::string family;
  std::vector<std::string> levels;         // a label per mesh (file name or resolution)
  std::vector<VolumePoissonError> errors;  // solution vectors dropped
  std::vector<double> l2_slopes,
      rms_slopes;  // log(e_{i+1}/e_i) / log(h_{i+1}/h_i) between levels; NaN where an error is 0
};

// The Franke study over meshes of increasing resolution (labels one per mesh).
VolumeConvergenceSeries volume_franke_convergence(const std::string& family,
                                                  const std::vector<VolumeMesh>& meshes,
                                                  const std::vector<std::string>& labels,
                                                  bool lumped_mass = false,
                                                  const LaplacianChoice& laplacian = {});

}  // namespace polydec
