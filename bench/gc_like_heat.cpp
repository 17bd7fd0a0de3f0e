// bench/gc_like_heat.cpp — the geometry-central-like heat-geodesics path (see gc_like_heat.h): a timed
// stand-in mirroring the per-source work of geometry-central's PolygonMeshHeatSolver, written here
// from a reading of what it does, not their code.
#include "bench/gc_like_heat.h"

#include <suitesparse/cholmod.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "polydec/operators/registry/laplacians.h"
#include "polydec/operators/solvers/cholesky.h"

namespace gc_like_heat {

namespace {

using polydec::SparseMatrix;

// The lower triangle of symmetric A as a CHOLMOD matrix (long indices, stype -1); the caller frees it.
cholmod_sparse* lower_to_cholmod(const SparseMatrix& A, cholmod_common* c) {
  const long n = long(A.rows());
  long nnz = 0;
  for (long j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j) ++nnz;
  cholmod_sparse* S = cholmod_l_allocate_sparse(size_t(n), size_t(n), size_t(nnz), 1, 1, -1, CHOLMOD_REAL, c);
  if (!S) throw std::runtime_error("gc_like_heat: cholmod_l_allocate_sparse failed");
  auto* p = static_cast<SuiteSparse_long*>(S->p);
  auto* i = static_cast<SuiteSparse_long*>(S->i);
  auto* x = static_cast<double*>(S->x);
  long k = 0;
  for (long j = 0; j < n; ++j) {
    p[j] = k;
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j) {
        i[k] = it.row();
        x[k] = it.value();
        ++k;
      }
  }
  p[n] = k;
  return S;
}

// Throws unless every entry of x is finite (geometry-central checks each right-hand side).
void check_finite(const Eigen::VectorXd& x, const char* what) {
  if (!x.allFinite()) throw std::runtime_error(std::string("gc_like_heat: non-finite ") + what);
}

}  // namespace

struct GcLikeHeat::Impl {
  cholmod_common common;
  cholmod_factor* heat = nullptr;
  cholmod_factor* poisson = nullptr;
  double lnz = 0;  // both factors' non-zeros
  bool supernodal = false;
  SparseMatrix G, D;  // gradient 3|F| x |V| and divergence |V| x 3|F| (D = -G^T W)
  long n = 0;

  // Analysis with CHOLMOD's default orderings, then the numerical factorization.
  cholmod_factor* factor(const SparseMatrix& A, const char* what) {
    cholmod_sparse* a = lower_to_cholmod(A, &common);
    cholmod_factor* L = cholmod_l_analyze(a, &common);
    if (L && !cholmod_l_factorize(a, L, &common)) {
      cholmod_l_free_factor(&L, &common);
      L = nullptr;
    }
    cholmod_l_free_sparse(&a, &common);
    if (!L || common.status != CHOLMOD_OK)
      throw std::runtime_error(std::string("gc_like_heat: factorization of the ") + what + " failed");
    lnz += common.lnz;
    return L;
  }

  // One solve as geometry-central's solver does it: finiteness check, copy into a CHOLMOD dense
  // vector, cholmod_l_solve, copy back, free both dense objects.
  Eigen::VectorXd solve(cholmod_factor* L, const Eigen::VectorXd& rhs, const char* what) {
    check_finite(rhs, what);
    cholmod_dense* b = cholmod_l_allocate_dense(size_t(n), 1, size_t(n), CHOLMOD_REAL, &common);
    if (!b) throw std::runtime_error("gc_like_heat: cholmod_l_allocate_dense failed");
    std::copy(rhs.data(), rhs.data() + n, static_cast<double*>(b->x));
    cholmod_dense* x = cholmod_l_solve(CHOLMOD_A, L, b, &common);
    if (!x) {
      cholmod_l_free_dense(&b, &common);
      throw std::runtime_error("gc_like_heat: cholmod_l_solve failed");
    }
    Eigen::VectorXd out(n);
    std::copy(static_cast<const double*>(x->x), static_cast<const double*>(x->x) + n, out.data());
    cholmod_l_free_dense(&b, &common);
    cholmod_l_free_dense(&x, &common);
    return out;
  }
};

// Precomputation: de Goes et al. operators with lambda 1 (geometry-central's polygon lambda), the
// heat operator M_lumped + t L and the Poisson operator L with L = -S positive semi-definite, both
// factored. Unlike geometry-central, which factors the singular L, vertex 0's row and column of L
// are set to the identity (the mesh is assumed closed and connected, so one pinned vertex makes it
// definite; the factorization costs the same).
GcLikeHeat::GcLikeHeat(const polydec::Mesh& mesh, bool supernodal) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  cholmod_l_start(&m.common);
  m.common.supernodal = supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
  m.common.final_ll = false;  // LDL^T (a supernodal factor stays LL^T)
  polydec::OperatorSet ops = polydec::build_operators(mesh, polydec::parse_laplacian("degoes20:1"));
  m.n = long(ops.S.rows());
  m.G.swap(ops.G);
  m.D.swap(ops.D);
  const double h = mesh.mean_edge_length(), t = h * h;
  SparseMatrix heat = -t * ops.S;
  for (int v = 0; v < heat.rows(); ++v) heat.coeffRef(v, v) += ops.M_lumped[v];
  m.heat = m.factor(heat, "heat operator");
  std::vector<unsigned char> pinned(size_t(m.n), 0);
  pinned[0] = 1;
  m.poisson = m.factor(polydec::pin_to_identity(-ops.S, pinned), "Poisson operator");
  m.supernodal = m.heat->is_super && m.poisson->is_super;
}

// Frees both factors and CHOLMOD's workspace.
GcLikeHeat::~GcLikeHeat() {
  cholmod_l_free_factor(&impl_->heat, &impl_->common);
  cholmod_l_free_factor(&impl_->poisson, &impl_->common);
  cholmod_l_finish(&impl_->common);
}

// Per source: a dense unit right-hand side, the heat solve, Y = G X normalized per face, the
// divergence, the Poisson solve, the shift to zero at the minimum.
Eigen::VectorXd GcLikeHeat::distance(int source) {
  Impl& m = *impl_;
  if (source < 0 || source >= m.n) throw std::out_of_range("gc_like_heat: source out of range");
  Eigen::VectorXd rho = Eigen::VectorXd::Zero(m.n);
  rho[source] = 1.0;
  const Eigen::VectorXd X = m.solve(m.heat, rho, "heat right-hand side");
  Eigen::VectorXd Y = m.G * X;
  // Each face's gradient to unit length. Far from the source the heat value falls below 1e-154 and
  // the gradient's squares underflow (past ~370 edge lengths at t = h^2): such a block is rescaled
  // first, and a block that is exactly zero stays zero, where geometry-central's g / |g| gives NaN.
  for (Eigen::Index f = 0; f + 2 < Y.size(); f += 3) {
    double norm = Y.segment<3>(f).norm();
    if (norm < 1e-150) {
      const double largest = Y.segment<3>(f).cwiseAbs().maxCoeff();
      if (!(largest > 0)) continue;
      Y.segment<3>(f) /= largest;
      norm = Y.segment<3>(f).norm();
    }
    Y.segment<3>(f) /= norm;
  }
  // geometry-central's right-hand side -Div Y is D Y in our convention (D = -G^T W, S = D G + ...):
  // then (-S) d = D Y gives d growing away from the source.
  Eigen::VectorXd div = m.D * Y;
  div[0] = 0.0;  // the pinned vertex
  Eigen::VectorXd d = m.solve(m.poisson, div, "Poisson right-hand side");
  d.array() -= d.minCoeff();
  return d;
}

double GcLikeHeat::factor_nonzeros() const { return impl_->lnz; }

bool GcLikeHeat::supernodal() const { return impl_->supernodal; }

}  // namespace gc_like_heat
