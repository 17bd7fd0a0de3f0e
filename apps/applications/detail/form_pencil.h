// apps/applications/detail/form_pencil.h — (internal, not installed) the eigen-solve and the
// bookkeeping that the surface (form_spectrum.cpp) and volume (volume/spectrum.cpp) form spectra
// share once each has built its mixed pencil on reduced bases.
#pragma once

#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "polydec/apps/applications/detail/complete_eigs.h"
#include "polydec/apps/applications/detail/mixed_shift_invert.h"
#include "polydec/apps/applications/form_spectrum.h"
#include "polydec/apps/applications/spectrum.h"

namespace polydec::form_pencil_detail {

using SpMat = Eigen::SparseMatrix<double>;

// The k smallest eigenpairs of K y = lambda B y, K = A + C D^-1 C^T, by shift-invert about
// out.shift through the quasi-definite mixed system (mixed_shift_invert.h). Fills out.rank,
// eigenvalues, eigenvectors (R y), n_converged, n_solves and method and, when options.decompose,
// sizes the Hodge-part arrays (zero); returns the vectors y on the reduced basis. `what` names
// the caller in errors (std::invalid_argument for k, SolverError from the solver).
inline Eigen::MatrixXd solve(const SpMat& A, const SpMat& B, const SpMat& C, const SpMat& D, const SpMat& R,
                             const std::string& name, const FormSpectrumOptions& options, const char* what,
                             FormSpectrum& out) {
  out.rank = int(B.rows());
  const int n = out.rank;
  if (options.k < 1 || options.k >= n)
    throw std::invalid_argument(fmt::format("{}: k = {} must lie in [1, {})", what, options.k, n));
  const int ncv = options.krylov_size > 0 ? std::clamp(options.krylov_size, options.k + 1, n)
                                          : spectrum_krylov_size(options.k, n);
  mixed_shift_invert_detail::MixedShiftInvert op(A, B, C, D, name);
  op.set_shift(out.shift);
  // Complete in the copies of multiple eigenvalues (complete_eigs.h).
  complete_eigs_detail::Pairs pairs = complete_eigs_detail::smallest_pairs(
      op, B, options.k, ncv, out.shift, options.max_iterations, options.tolerance, what);
  out.n_converged = pairs.n_converged;
  out.n_solves = pairs.n_solves;
  out.method = "Spectra SymGEigsShiftSolver + quasi-definite SimplicialLDLT";
  out.eigenvalues = pairs.values;
  out.eigenvectors = R * pairs.vectors;
  if (options.decompose) {
    const int k = options.k;
    out.exact = Eigen::MatrixXd::Zero(out.eigenvectors.rows(), k);
    out.coexact = out.exact;
    out.harmonic = out.exact;
    out.norm_exact.resize(k);
    out.norm_coexact.resize(k);
    out.norm_harmonic.resize(k);
    out.kinds.resize(size_t(k));
  }
  return std::move(pairs.vectors);
}

// Each eigenform's kind: the Hodge part of largest norm (ties: harmonic, then exact).
inline void classify(FormSpectrum& out) {
  for (Eigen::Index i = 0; i < out.norm_exact.size(); ++i) {
    const double e = out.norm_exact[i], c = out.norm_coexact[i], h = out.norm_harmonic[i];
    out.kinds[size_t(i)] = h >= e && h >= c ? FormKind::Harmonic : e >= c ? FormKind::Exact : FormKind::Coexact;
  }
}

}  // namespace polydec::form_pencil_detail
