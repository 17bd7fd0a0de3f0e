// apps/applications/hodge_parts.h — the result of a Hodge decomposition of a coarse 1-cochain,
// shared by surfaces (hodge_decomposition.h) and volumes (volume/hodge_decomposition.h):
// omega = exact + coexact + harmonic, star1-orthogonal, with the exact part's potential and norms.
#pragma once

#include "polydec/dec/mesh/eigen_abi.h"
#include <Eigen/Core>
#include <Eigen/Sparse>

namespace polydec {

struct HodgeParts {
  Eigen::VectorXd exact, coexact, harmonic;  // |C1| each; exact + coexact + harmonic = omega
  Eigen::VectorXd potential;                 // alpha, |V|, exact = d0 alpha
  double norm = 0, norm_exact = 0, norm_coexact = 0, norm_harmonic = 0;  // sqrt(x^T star1 x)
};

// The parts of omega from its exact potential alpha (d0^T star1 d0 alpha = d0^T star1 omega) and a
// star1-orthonormal basis H (|C1| x dim) of the harmonic 1-forms: exact = d0 alpha, harmonic = the
// star1-projection onto H, coexact = the rest; norms in the star1 (semi-)norm.
HodgeParts hodge_parts(const Eigen::VectorXd& omega, Eigen::VectorXd potential,
                       const Eigen::SparseMatrix<double>& d0, const Eigen::SparseMatrix<double>& star1,
                       const Eigen::MatrixXd& H);

}  // namespace polydec
