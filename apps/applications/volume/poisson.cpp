// apps/applications/volume/poisson.cpp — the 3D Franke function, its Laplacian, Dirichlet Poisson solves on
// volume meshes.
#include "polydec/apps/applications/volume/poisson.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "polydec/apps/applications/poisson.h"
#include "polydec/operators/registry/volume_laplacians.h"

namespace polydec {
namespace volume_poisson_detail {
namespace {

struct Franke3Terms {
  double g1, g2, g3, g4;
  Franke3Terms(double x, double y, double z) {
    const auto sq = [](double t) { return t * t; };
    g1 = 0.75 * std::exp(-(sq(9 * x - 2) + sq(9 * y - 2) + sq(9 * z - 2)) / 4);
    g2 = 0.75 * std::exp(-sq(9 * x + 1) / 49 - (9 * y + 1) / 10 - (9 * z + 1) / 10);
    g3 = 0.5 * std::exp(-(sq(9 * x - 7) + sq(9 * y - 3) + sq(9 * z - 5)) / 4);
    g4 = -0.2 * std::exp(-sq(9 * x - 4) - sq(9 * y - 7) - sq(9 * z - 5));
  }
};

// NaN when an error is 0 (a mesh without interior vertices: cube_truncated_1).
double slope(double h0, double h1, double e0, double e1) {
  if (!(e0 > 0 && e1 > 0)) return std::numeric_limits<double>::quiet_NaN();
  return std::log(e1 / e0) / std::log(h1 / h0);
}

}  // namespace
}  // namespace volume_poisson_detail

double franke3d(double x, double y, double z) {
  const volume_poisson_detail::Franke3Terms t(x, y, z);
  return t.g1 + t.g2 + t.g3 + t.g4;
}

double franke3d_laplacian(double x, double y, double z) {
  const volume_poisson_detail::Franke3Terms t(x, y, z);
  // exp(-(a^2 + b^2 + c^2) / 4) with a = 9x - x0 ...: d2/dx2 = 81 (a^2 / 4 - 1/2) term per axis.
  const double a1 = 9 * x - 2, b1 = 9 * y - 2, c1 = 9 * z - 2;
  const double a3 = 9 * x - 7, b3 = 9 * y - 3, c3 = 9 * z - 5;
  const double l1 = 81 * ((a1 * a1 + b1 * b1 + c1 * c1) / 4 - 1.5) * t.g1;
  const double l3 = 81 * ((a3 * a3 + b3 * b3 + c3 * c3) / 4 - 1.5) * t.g3;
  // exp(-(9x+1)^2/49 - (9y+1)/10 - (9z+1)/10): d2/dx2 = ((18 (9x+1)/49)^2 - 162/49) term,
  // d2/dy2 = d2/dz2 = 0.81 term.
  const double c2 = 18 * (9 * x + 1) / 49;
  const double l2 = (c2 * c2 - 162.0 / 49 + 1.62) * t.g2;
  // exp(-a^2 - b^2 - c^2), a = 9x - 4 ...: d2/dx2 = 81 (4 a^2 - 2) term per axis.
  const double a4 = 9 * x - 4, b4 = 9 * y - 7, c4 = 9 * z - 5;
  const double l4 = (324 * (a4 * a4 + b4 * b4 + c4 * c4) - 486) * t.g4;
  return l1 + l2 + l3 + l4;
}

VolumePoissonError volume_dirichlet_poisson(const OperatorSet& ops, const VolumeMesh& mesh,
                                            const ScalarField3& exact, const ScalarField3& laplacian,
                                            bool lumped_mass) {
  const int nv = mesh.n_vertices();
  Eigen::VectorXd f(nv), b(nv);
  for (int v = 0; v < nv; ++v) {
    const Eigen::Vector3d p = mesh.position(v);
    f[v] = exact(p);
    b[v] = laplacian(p);
  }
  return volume_dirichlet_poisson(ops, mesh, f, b, lumped_mass);
}

VolumePoissonError volume_dirichlet_poisson(const OperatorSet& ops, const VolumeMesh& mesh,
                                            const Eigen::VectorXd& exact, const Eigen::VectorXd& b,
                                            bool lumped_mass) {
  const int nv = mesh.n_vertices();
  if (ops.S.rows() != nv) throw std::invalid_argument("volume Poisson: operators do not match the mesh");
  if (exact.size() != nv || b.size() != nv)
    throw std::invalid_argument(
        "volume Poisson: one exact value and one Laplacian value per vertex expected");
  if (!exact.allFinite() || !b.allFinite())
    throw std::invalid_argument("volume Poisson: exact values and Laplacian values must be finite");
  VolumePoissonError e;
  e.n_vertices = nv;
  e.n_cells = mesh.n_cells();
  e.h = mesh.mean_edge_length();
  e.exact = exact;
  std::vector<int> fixed;
  for (int v = 0; v < nv; ++v)
    if (mesh.is_boundary_vertex(v)) fixed.push_back(v);
  if (fixed.empty()) throw std::invalid_argument("volume Poisson problem: the mesh has no boundary vertices");
  e.n_boundary = int(fixed.size());
  e.solution = solve_dirichlet_poisson(ops, b, fixed, e.exact, lumped_mass);
  const Eigen::VectorXd d = e.solution - e.exact;
  e.l2_error = std::sqrt(lumped_mass ? d.dot(ops.M_lumped.cwiseProduct(d)) : d.dot(ops.M * d));
  e.rms_error = std::sqrt(d.squaredNorm() / nv);
  return e;
}

VolumePoissonError volume_franke_poisson(const VolumeMesh& mesh, bool lumped_mass,
                                         const LaplacianChoice& laplacian) {
  return volume_franke_poisson(build_volume_operators(mesh, laplacian, {.with_gradient = false}), mesh, lumped_mass);
}

VolumePoissonError volume_franke_poisson(const OperatorSet& operators, const VolumeMesh& mesh, bool lumped_mass) {
  return volume_dirichlet_poisson(
      operators, mesh, [](const Eigen::Vector3d& p) { return franke3d(p.x(), p.y(), p.z()); },
      [](const Eigen::Vector3d& p) { return franke3d_laplacian(p.x(), p.y(), p.z()); }, lumped_mass);
}

VolumeConvergenceSeries volume_franke_convergence(const std::string& family,
                                                  const std::vector<VolumeMesh>& meshes,
                                                  const std::vector<std::string>& labels, bool lumped_mass,
                                                  const LaplacianChoice& laplacian) {
  if (meshes.size() != labels.size())
    throw std::invalid_argument("volume convergence study: one label per mesh");
  VolumeConvergenceSeries s;
  s.family = family;
  s.levels = labels;
  for (const VolumeMesh& mesh : meshes) {
    VolumePoissonError e = volume_franke_poisson(mesh, lumped_mass, laplacian);
    e.solution.resize(0);
    e.exact.resize(0);
    s.errors.push_back(std::move(e));
  }
  for (size_t i = 1; i < s.errors.size(); ++i) {
    const auto &a = s.errors[i - 1], &b = s.errors[i];
    s.l2_slopes.push_back(volume_poisson_detail::slope(a.h, b.h, a.l2_error, b.l2_error));
    s.rms_slopes.push_back(volume_poisson_detail::slope(a.h, b.h, a.rms_error, b.rms_error));
  }
  return s;
}

}  // namespace polydec
