// apps/applications/volume/spectrum.cpp — spherical Bessel zeros, the unit ball's spectrum, volume Laplacian
// eigenpairs, and the Hodge Laplacian eigenpairs of 1-, 2- and 3-forms.
#include "polydec/apps/applications/volume/spectrum.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "polydec/apps/applications/detail/form_pencil.h"
#include "polydec/apps/applications/volume/poisson.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/registry/volume_laplacians.h"

namespace polydec {

double spherical_bessel_j(int l, double x) {
  if (l < 0 || !(x > 0)) throw std::invalid_argument("spherical_bessel_j: need l >= 0 and x > 0");
  const double j0 = std::sin(x) / x, j1 = std::sin(x) / (x * x) - std::cos(x) / x;
  if (l == 0) return j0;
  if (l == 1) return j1;
  // Start well above both l and x, where j_L is negligible against j_l; rescale against overflow.
  const int L = std::max(l, int(x)) + 40;
  double next = 0, cur = 1e-300, at_l = 0, at_0 = 0, at_1 = 0;
  for (int m = L; m >= 1; --m) {
    const double prev = (2 * m + 1) / x * cur - next;  // j_{m-1}
    next = cur;
    cur = prev;
    if (m - 1 == l) at_l = cur;
    if (std::abs(cur) > 1e250) {
      next *= 1e-250;
      cur *= 1e-250;
      at_l *= 1e-250;
      at_1 *= 1e-250;
    }
    if (m - 1 == 1) at_1 = cur;
    if (m - 1 == 0) at_0 = cur;
  }
  return std::abs(j0) >= std::abs(j1) ? at_l * (j0 / at_0) : at_l * (j1 / at_1);
}

double spherical_bessel_j_derivative(int l, double x) {
  if (l == 0) return -spherical_bessel_j(1, x);
  return spherical_bessel_j(l - 1, x) - (l + 1) / x * spherical_bessel_j(l, x);
}

std::vector<double> spherical_bessel_zeros(int l, int count, bool derivative) {
  if (l < 0 || count < 0) throw std::invalid_argument("spherical_bessel_zeros: need l >= 0, count >= 0");
  const auto f = [&](double x) {
    return derivative ? spherical_bessel_j_derivative(l, x) : spherical_bessel_j(l, x);
  };
  std::vector<double> zeros;
  const double step = 0.05;
  double a = step, fa = f(a);
  while (int(zeros.size()) < count) {
    const double b = a + step, fb = f(b);
    if (fa == 0) {
      zeros.push_back(a);
    } else if ((fa < 0) != (fb < 0)) {
      double lo = a, hi = b, flo = fa;
      for (int it = 0; it < 200 && hi - lo > 4e-16 * hi; ++it) {
        const double mid = 0.5 * (lo + hi), fm = f(mid);
        if ((fm < 0) == (flo < 0)) {
          lo = mid;
          flo = fm;
        } else {
          hi = mid;
        }
      }
      zeros.push_back(0.5 * (lo + hi));
    }
    a = b;
    fa = fb;
  }
  return zeros;
}

std::vector<BallEigenvalue> ball_eigenvalues(int count, bool dirichlet) {
  if (count < 0) throw std::invalid_argument("ball_eigenvalues: count must be >= 0");
  // All zeros below x_max: the first zero of j_l and of j_l' (l >= 1) exceeds l, so l <= x_max suffices.
  for (double x_max = 8;; x_max *= 2) {
    std::vector<BallEigenvalue> all;
    if (!dirichlet) all.push_back({0.0, 0, 0});
    for (int l = 0; l <= int(x_max) + 1; ++l) {
      const std::vector<double> z = spherical_bessel_zeros(l, int(x_max / 3) + 2, !dirichlet);
      for (size_t i = 0; i < z.size(); ++i)
        if (z[i] < x_max)
          for (int m = 0; m < 2 * l + 1; ++m) all.push_back({z[i] * z[i], l, int(i) + 1});
    }
    if (int(all.size()) >= count) {
      std::stable_sort(all.begin(), all.end(),
                       [](const BallEigenvalue& p, const BallEigenvalue& q) { return p.lambda < q.lambda; });
      all.resize(size_t(count));
      return all;
    }
  }
}

Spectrum volume_laplacian_spectrum(const VolumeMesh& mesh, bool dirichlet, const SpectrumOptions& options) {
  return volume_laplacian_spectrum(build_volume_operators(mesh, LaplacianChoice{}, {.with_gradient = false}),
                                   mesh, dirichlet, options);
}

Spectrum volume_laplacian_spectrum(const OperatorSet& ops, const VolumeMesh& mesh, bool dirichlet,
                                   const SpectrumOptions& options) {
  if (ops.S.rows() != mesh.n_vertices())
    throw std::invalid_argument("volume spectrum: operators do not match the mesh");
  if (!dirichlet) return laplacian_spectrum(ops, options);
  const int nv = mesh.n_vertices();
  std::vector<int> index(size_t(nv), -1), interior;
  for (int v = 0; v < nv; ++v)
    if (!mesh.is_boundary_vertex(v)) {
      index[size_t(v)] = int(interior.size());
      interior.push_back(v);
    }
  if (interior.empty())
    throw std::invalid_argument("volume spectrum (Dirichlet): the mesh has no interior vertex");
  OperatorSet inner;
  inner.name = ops.name + ", Dirichlet";
  inner.S = principal_submatrix(ops.S, index);
  if (ops.M.rows() > 0) inner.M = principal_submatrix(ops.M, index);
  inner.M_lumped.resize(Eigen::Index(interior.size()));
  for (size_t i = 0; i < interior.size(); ++i) inner.M_lumped[Eigen::Index(i)] = ops.M_lumped[interior[i]];
  Spectrum s = laplacian_spectrum(inner, options);
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(nv, s.eigenvectors.cols());
  for (size_t i = 0; i < interior.size(); ++i) U.row(interior[i]) = s.eigenvectors.row(Eigen::Index(i));
  s.eigenvectors = std::move(U);
  return s;
}

BallSpectrum ball_spectrum(int n, int k, bool dirichlet, bool lumped_mass) {
  if (n < 2) throw std::invalid_argument("ball spectrum: n must be >= 2");
  if (k < 1) throw std::invalid_argument("ball spectrum: k must be >= 1");
  const VolumeMesh mesh = hex_ball_volume(n);
  BallSpectrum b;
  b.n = n;
  b.dirichlet = dirichlet;
  b.n_vertices = mesh.n_vertices();
  b.n_cells = mesh.n_cells();
  b.h = mesh.mean_edge_length();
  // The ball's cubic symmetry repeats eigenvalues exactly (multiplicities 2 and 3); single-vector
  // Lanczos can stop before it has found every copy of a cluster at the end of the wanted set, so
  // ask for 2k + 10 pairs and keep the k smallest.
  SpectrumOptions opt;
  int n_free = b.n_vertices;
  if (dirichlet)
    for (int v = 0; v < b.n_vertices; ++v) n_free -= mesh.is_boundary_vertex(v) ? 1 : 0;
  opt.k = std::min(2 * k + 10, n_free - 1);
  opt.lumped_mass = lumped_mass;
  const Spectrum s = volume_laplacian_spectrum(mesh, dirichlet, opt);
  b.method = s.method;
  if (opt.k < k)
    throw std::invalid_argument(
        fmt::format("ball spectrum: k = {} needs more than {} free vertices", k, n_free));
  b.analytic = ball_eigenvalues(k, dirichlet);
  for (int i = 0; i < k; ++i) {
    const double lh = s.eigenvalues[i], l = b.analytic[size_t(i)].lambda;
    b.eigenvalues.push_back(lh);
    b.relative_error.push_back(l > 0 ? std::abs(lh - l) / l : std::abs(lh));
  }
  return b;
}

FormSpectrum volume_form_spectrum(const VolumeMesh& mesh, const FormSpectrumOptions& options) {
  using SpMat = Eigen::SparseMatrix<double>;
  const int degree = options.degree;
  if (degree < 1 || degree > 3)
    throw std::invalid_argument(fmt::format("volume form spectrum: degree {} must be 1, 2 or 3", degree));
  if (mesh.n_cells() == 0) throw InvalidMeshError("mesh", -1, "volume form spectrum: the mesh has no cells");
  const VolumeRefinement ref = refine_volume(mesh);
  const bool on_mesh = options.complex == DecComplex::Mesh;
  const int top = std::min(degree + 1, 3);
  const VolumeDec dec = volume_dec(mesh, ref, VolumeDecOptions{.max_degree = top, .complex = options.complex});
  const Eigen::VectorXd lumped = dec.star[0] * Eigen::VectorXd::Ones(dec.star[0].cols());
  const double volume = lumped.sum();
  if (!(volume > 0)) throw SolverError("volume form spectrum: the mesh has zero volume");
  const double scale = std::pow(volume, 2.0 / 3.0);  // length^2

  // Reduced bases: the identity on the mesh complex (its stars are definite), volume_form_span on
  // the complete one; degree 0 keeps the vertices with mass.
  auto basis = [&](int j) {
    if (j == 0) {
      std::vector<Eigen::Triplet<double>> t;
      for (int v = 0; v < mesh.n_vertices(); ++v)
        if (lumped[v] > 0) t.emplace_back(v, int(t.size()), 1.0);
      SpMat R(mesh.n_vertices(), long(t.size()));
      R.setFromTriplets(t.begin(), t.end());
      return R;
    }
    if (on_mesh) {
      SpMat R(dec.star[j].rows(), dec.star[j].rows());
      R.setIdentity();
      return R;
    }
    return volume_form_span(dec, mesh, ref, j).R;
  };
  const SpMat Rk = basis(degree), Rm = basis(degree - 1);
  const SpMat& star = dec.star[degree];
  const SpMat& d_in = dec.d[degree - 1];  // d_{k-1}
  const SpMat B = Rk.transpose() * star * Rk;
  const SpMat A = degree < 3 ? SpMat(Rk.transpose() * dec.d[degree].transpose() * dec.star[degree + 1] *
                                     dec.d[degree] * Rk)
                             : SpMat(B.rows(), B.cols());
  const SpMat C = Rk.transpose() * star * d_in * Rm;
  SpMat M;
  if (degree == 1 && options.lumped_mass) {
    const Eigen::VectorXd m = Rm.transpose() * lumped;
    M = SpMat(m.asDiagonal());
  } else {
    M = Rm.transpose() * dec.star[degree - 1] * Rm;
  }

  FormSpectrum out;
  out.degree = degree;
  out.shift = -options.shift_factor / scale;
  const std::string name = fmt::format("[d{0}^T star{1} d{0} - sigma star{2}, star{2} d{3}; d{3}^T star{2}, -star{3}]",
                                       degree, degree + 1, degree, degree - 1);
  const Eigen::MatrixXd Y = form_pencil_detail::solve(A, B, C, M, Rk, name, options, "volume form spectrum", out);
  if (!options.decompose) return out;

  const int k = options.k;
  const double zero = 1e-8 / scale;
  const SparseCholesky solve_M(M, fmt::format("the {}-form mass", degree - 1));
  const std::unique_ptr<SparseCholesky> solve_B =
      degree < 3 ? std::make_unique<SparseCholesky>(B, fmt::format("star{}", degree)) : nullptr;
  auto norm = [&](const Eigen::VectorXd& x) { return std::sqrt(std::max(0.0, x.dot(star * x))); };
  for (int i = 0; i < k; ++i) {
    const double lambda = out.eigenvalues[i];
    const Eigen::VectorXd y = Y.col(i);
    if (std::abs(lambda) > zero) {
      out.exact.col(i) = d_in * (Rm * solve_M.solve(Eigen::VectorXd(C.transpose() * y))) / lambda;
      if (solve_B) out.coexact.col(i) = Rk * solve_B->solve(Eigen::VectorXd(A * y)) / lambda;
    }
    out.harmonic.col(i) = out.eigenvectors.col(i) - out.exact.col(i) - out.coexact.col(i);
    out.norm_exact[i] = norm(out.exact.col(i));
    out.norm_coexact[i] = norm(out.coexact.col(i));
    out.norm_harmonic[i] = norm(out.harmonic.col(i));
  }
  form_pencil_detail::classify(out);
  return out;
}

}  // namespace polydec
