// tests/apps/test_spectrum.cpp — eigenpairs of -S x = lambda M x: residuals, M-orthonormality,
// agreement with a dense solver, the spherical-harmonic clustering on the unit sphere.
#include "apps/spectrum.h"
#include "dec/generators.h"
#include "dec/io.h"
#include "tests/support.h"

#include <Eigen/Eigenvalues>

using namespace polydec;

namespace {

Mesh unit_sphere_mesh(const std::string& path) { return project_to_unit_sphere(read_mesh(path)); }

SparseMatrix mass_of(const OperatorSet& ops, bool lumped) {
  if (!lumped) return ops.M;
  SparseMatrix M(ops.M_lumped.size(), ops.M_lumped.size());
  M.setIdentity();
  M.diagonal() = ops.M_lumped;
  return M;
}

}  // namespace

TEST_CASE("spectrum: residuals, M-orthonormality and a dense solver agree (lumped and unlumped)", "[apps]") {
  POLYDEC_SHARED_MESH(path, "quad-sphere.off");
  const Mesh sphere = unit_sphere_mesh(path);
  const OperatorSet ops = build_operators(sphere, parse_laplacian("ours"), false);
  for (bool lumped : {true, false}) {
    SpectrumOptions o;
    o.k = 16;
    o.lumped_mass = lumped;
    const Spectrum sp = laplacian_spectrum(ops, o);
    const SparseMatrix M = mass_of(ops, lumped);
    const Eigen::MatrixXd& U = sp.eigenvectors;
    const Eigen::MatrixXd R = ops.S * U + M * U * sp.eigenvalues.asDiagonal();
    CHECK(R.norm() <= 1e-8 * (ops.S * U).norm());
    CHECK((U.transpose() * M * U - Eigen::MatrixXd::Identity(o.k, o.k)).cwiseAbs().maxCoeff() <= 1e-8);
    CHECK(std::abs(sp.eigenvalues[0]) <= 1e-8 * sp.eigenvalues[1]);  // constants: lambda = 0
    for (int i = 1; i < o.k; ++i) CHECK(sp.eigenvalues[i] >= sp.eigenvalues[i - 1]);
    // Independent route: dense generalized symmetric eigensolver.
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(Eigen::MatrixXd(-ops.S),
                                                                          Eigen::MatrixXd(M));
    REQUIRE(dense.info() == Eigen::Success);
    for (int i = 0; i < o.k; ++i)
      CHECK(sp.eigenvalues[i] == Approx(dense.eigenvalues()[i]).margin(1e-8 * dense.eigenvalues()[o.k]));
  }
}

TEST_CASE("spectrum: eigenvalues cluster at l(l+1) with multiplicity 2l+1 on the REGULAR SPHERE", "[apps]") {
  POLYDEC_SHARED_MESH(path, "quad-sphere.off");
  SpectrumOptions o;
  o.k = 25;  // l = 0..4
  const Spectrum sp = laplacian_spectrum(unit_sphere_mesh(path), o);
  // Measured on this 512-face sphere (mean edge 0.1): the largest relative deviation for
  // l <= 4 is 6.8% (l = 4, the first eigenvalue of the cluster); asserted: 8%.
  int i = 1;
  for (int l = 1; l <= 4; ++l)
    for (int m = -l; m <= l; ++m, ++i) CHECK(sp.eigenvalues[i] == Approx(l * (l + 1.0)).epsilon(0.08));
}

TEST_CASE("spectrum: unreferenced vertices are left out, scaling the mesh scales lambda by 1/s^2", "[apps]") {
  POLYDEC_SHARED_MESH(path, "quad-sphere.off");
  PolygonSoup soup = read_polygon_soup(path);
  const int n = soup.n_vertices();
  soup.positions.conservativeResize(n + 1, 3);
  soup.positions.row(n) = Eigen::RowVector3d(5, 5, 5);
  const Mesh mesh(std::move(soup));
  SpectrumOptions o;
  o.k = 6;
  const Spectrum sp = laplacian_spectrum(mesh, o);
  CHECK(sp.eigenvectors.row(n).cwiseAbs().maxCoeff() == 0.0);
  const double s = 1e3;
  const Spectrum big = laplacian_spectrum(mesh.with_positions(s * mesh.positions()), o);
  for (int i = 1; i < o.k; ++i) CHECK(big.eigenvalues[i] * s * s == Approx(sp.eigenvalues[i]).epsilon(1e-8));
  o.k = n;
  CHECK_THROWS_AS(laplacian_spectrum(mesh, o), std::invalid_argument);
}
