// operators/solvers/span_solver.h — solving with the singular Hodge stars star1, star2 on the span of
// the Whitney forms (reduced basis of dec/surface/form_span.h; docs/feec.md, "Rank").
#pragma once

#include <memory>
#include <string>

#include "polydec/dec/surface/form_span.h"
#include "polydec/operators/solvers/cholesky.h"

namespace polydec {

// Solves star x = b on the span: factors R^T star R once (SparseCholesky; SolverError names
// `name` when it is not positive definite).
// solve(b) requires b in the range of star, i.e. b orthogonal to ker P_k: true for every
// b = star y, and for b = d1^T star2 c (d1 maps ker P1 into ker P2 = ker star2). It returns
// the unique x supported on span.cells with star x = b; every other solution differs from it
// by an element of ker P_k, i.e. represents the same Whitney form.
class SpanSolver {
 public:
  SpanSolver(const Eigen::SparseMatrix<double>& star, FormSpan span, std::string name);

  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  // The representative of x's Whitney form supported on the span cells: solve(star x).
  Eigen::VectorXd canonical(const Eigen::VectorXd& x) const;

  const FormSpan& span() const { return span_; }

 private:
  Eigen::SparseMatrix<double> star_;
  FormSpan span_;
  std::unique_ptr<SparseCholesky> chol_;
};

}  // namespace polydec
