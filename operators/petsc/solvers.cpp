// operators/petsc/solvers.cpp — heat geodesics (eq. 31-33) with PETSc's KSP and the smallest
// eigenpairs with SLEPc's Krylov-Schur (operators/petsc/petsc.h).
#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/petsc/petsc.h"
#include "polydec/operators/petsc/petsc_check.h"

namespace polydec::petsc {

LinearSolver parse_linear_solver(const std::string& name) {
  if (name == "direct") return LinearSolver::MumpsCholesky;
  if (name == "cg-gamg") return LinearSolver::CgGamg;
  if (name == "cg-hypre") return LinearSolver::CgBoomerAmg;
  throw std::invalid_argument("unknown linear solver '" + name + "' (direct, cg-gamg, cg-hypre)");
}

std::string linear_solver_name(LinearSolver s) {
  switch (s) {
    case LinearSolver::MumpsCholesky:
      return "direct";
    case LinearSolver::CgGamg:
      return "cg-gamg";
    case LinearSolver::CgBoomerAmg:
      return "cg-hypre";
  }
  return "?";
}

namespace {

// Sets up ksp for the symmetric operator A: MUMPS Cholesky, or CG with GAMG / BoomerAMG to the
// relative residual rtol; then the options of its prefix apply.
void configure_ksp(KSP ksp, LinearSolver solver, double rtol) {
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  if (solver == LinearSolver::MumpsCholesky) {
    check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
    check(PCSetType(pc, PCCHOLESKY), "PCSetType");
    check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  } else {
    check(KSPSetType(ksp, KSPCG), "KSPSetType");
    check(KSPSetTolerances(ksp, rtol, 1e-300, PETSC_DEFAULT, 10000), "KSPSetTolerances");
    if (solver == LinearSolver::CgGamg) {
      check(PCSetType(pc, PCGAMG), "PCSetType");
    } else {
      check(PCSetType(pc, PCHYPRE), "PCSetType");
      check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
    }
  }
}

Handle<KSP> make_ksp(MPI_Comm comm, Mat A, const char* prefix, LinearSolver solver, double rtol,
                     PCType pc_type = nullptr) {
  // GAMG's coarsest level of a singular operator (the Poisson step's null space): a pseudo-inverse
  // (SVD) instead of LU, unless the user chose otherwise.
  MatNullSpace ns = nullptr;
  check(MatGetNullSpace(A, &ns), "MatGetNullSpace");
  if (ns && solver == LinearSolver::CgGamg) {
    PetscBool set = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, prefix, "-mg_coarse_sub_pc_type", &set), "PetscOptionsHasName");
    if (!set)
      check(PetscOptionsSetValue(nullptr, (std::string("-") + prefix + "mg_coarse_sub_pc_type").c_str(), "svd"),
            "PetscOptionsSetValue");
  }
  Handle<KSP> ksp;
  check(KSPCreate(comm, ksp.out()), "KSPCreate");
  check(KSPSetOperators(ksp.get(), A, A), "KSPSetOperators");
  check(KSPSetOptionsPrefix(ksp.get(), prefix), "KSPSetOptionsPrefix");
  configure_ksp(ksp.get(), solver, rtol);
  if (pc_type) {
    PC pc = nullptr;
    check(KSPGetPC(ksp.get(), &pc), "KSPGetPC");
    check(PCSetType(pc, pc_type), "PCSetType");
  }
  check(KSPSetFromOptions(ksp.get()), "KSPSetFromOptions");
  check(KSPSetUp(ksp.get()), std::string(prefix).append(" solver set-up (factorization)").c_str());
  return ksp;
}

// Solves and checks the converged reason (the same on every rank).
int solve(KSP ksp, Vec b, Vec x, const char* what) {
  check(KSPSolve(ksp, b, x), what);
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
  PetscInt its = 0;
  check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber");
  if (reason < 0)
    throw SolverError(fmt::format("{}: the linear solver did not converge ({}, {} iterations)", what,
                                  KSPConvergedReasons[reason], int(its)));
  return int(its);
}

}  // namespace

HeatGeodesics::HeatGeodesics(MPI_Comm comm, const Partition& part, const DistributedOperators& ops,
                             double mean_edge_length, const GeodesicsOptions& options)
    : comm_(comm), part_(part), ops_(ops), options_(options) {
  int no_gradient = ops.G.size() == 0 && ops.n_local_faces > 0;
  MPI_Allreduce(MPI_IN_PLACE, &no_gradient, 1, MPI_INT, MPI_MAX, comm);
  if (no_gradient) throw std::invalid_argument("heat geodesics: the operators have no gradient");
  const double h = mean_edge_length > 0 ? mean_edge_length : ops.mean_edge_length;
  t_ = options.time_step_factor * h * h;
  PetscInt lo = 0, hi = 0;
  check(MatGetOwnershipRange(ops.S.get(), &lo, &hi), "MatGetOwnershipRange");
  // Owned vertices with stiffness: a non-zero off-diagonal entry in their row of S.
  coupled_.assign(size_t(hi - lo), 0);
  std::vector<PetscInt> uncoupled;
  for (PetscInt r = lo; r < hi; ++r) {
    PetscInt n = 0;
    const PetscInt* c = nullptr;
    const PetscScalar* v = nullptr;
    check(MatGetRow(ops.S.get(), r, &n, &c, &v), "MatGetRow");
    for (PetscInt k = 0; k < n; ++k)
      if (c[k] != r && v[k] != 0.0) coupled_[size_t(r - lo)] = 1;
    check(MatRestoreRow(ops.S.get(), r, &n, &c, &v), "MatRestoreRow");
    if (!coupled_[size_t(r - lo)]) uncoupled.push_back(r);
  }
  // Heat operator M - t S, rows without stiffness set to the identity.
  if (options.lumped_mass) {
    check(MatDuplicate(ops.S.get(), MAT_COPY_VALUES, heat_matrix_.out()), "MatDuplicate");
    check(MatScale(heat_matrix_.get(), -t_), "MatScale");
    check(MatDiagonalSet(heat_matrix_.get(), ops.M_lumped.get(), ADD_VALUES), "MatDiagonalSet");
  } else {
    if (!ops.M.get()) throw std::invalid_argument("heat geodesics: Galerkin mass requested, not assembled");
    check(MatDuplicate(ops.M.get(), MAT_COPY_VALUES, heat_matrix_.out()), "MatDuplicate");
    check(MatAXPY(heat_matrix_.get(), -t_, ops.S.get(), SAME_NONZERO_PATTERN), "MatAXPY");
  }
  check(MatZeroRowsColumns(heat_matrix_.get(), PetscInt(uncoupled.size()), uncoupled.data(), 1.0, nullptr, nullptr),
        "MatZeroRowsColumns");
  check(MatSetOption(heat_matrix_.get(), MAT_SPD, PETSC_TRUE), "MatSetOption");
  // (-heat_pc_type jacobi saves the heat step's hierarchy, M - t S with t ~ h^2 being well
  // conditioned, but its far field missed tests/mpi's 1e-6 of the diameter on suzanne-half at 3
  // ranks: 1.05e-6; docs/scale.md.)
  heat_ = make_ksp(comm, heat_matrix_.get(), "heat_", options.solver, options.rtol);

  // Poisson operator -S. Per component, the vertex of least global index that has stiffness.
  const int nc = part.n_components;
  std::vector<int> first(size_t(nc), INT_MAX), count(size_t(nc), 0);
  for (PetscInt r = lo; r < hi; ++r)
    if (coupled_[size_t(r - lo)]) {
      const int c = part.vertex_component[size_t(part.mesh_vertex[size_t(r)])];
      first[size_t(c)] = std::min(first[size_t(c)], int(r));
      ++count[size_t(c)];
    }
  MPI_Allreduce(MPI_IN_PLACE, first.data(), nc, MPI_INT, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, count.data(), nc, MPI_INT, MPI_SUM, comm);
  check(MatDuplicate(ops.S.get(), MAT_COPY_VALUES, poisson_matrix_.out()), "MatDuplicate");
  check(MatScale(poisson_matrix_.get(), -1.0), "MatScale");
  pin_ = uncoupled;
  if (options.solver == LinearSolver::MumpsCholesky) {
    // Direct: one vertex pinned to 0 per component (the right-hand side D g sums to 0 on each).
    for (int c = 0; c < nc; ++c)
      if (first[size_t(c)] >= lo && first[size_t(c)] < hi) pin_.push_back(first[size_t(c)]);
    check(MatZeroRowsColumns(poisson_matrix_.get(), PetscInt(pin_.size()), pin_.data(), 1.0, nullptr, nullptr),
          "MatZeroRowsColumns");
    check(MatSetOption(poisson_matrix_.get(), MAT_SPD, PETSC_TRUE), "MatSetOption");
  } else {
    // CG: the singular operator with its null space, one normalized indicator per component.
    check(MatZeroRowsColumns(poisson_matrix_.get(), PetscInt(uncoupled.size()), uncoupled.data(), 1.0, nullptr,
                             nullptr),
          "MatZeroRowsColumns");
    std::vector<Vec> basis;
    for (int c = 0; c < nc; ++c) {
      if (count[size_t(c)] == 0) continue;
      Vec z = nullptr;
      check(VecDuplicate(ops.M_lumped.get(), &z), "VecDuplicate");
      PetscScalar* a = nullptr;
      check(VecGetArray(z, &a), "VecGetArray");
      const double value = 1.0 / std::sqrt(double(count[size_t(c)]));
      for (PetscInt r = lo; r < hi; ++r)
        a[r - lo] = coupled_[size_t(r - lo)] && part.vertex_component[size_t(part.mesh_vertex[size_t(r)])] == c
                        ? value
                        : 0.0;
      check(VecRestoreArray(z, &a), "VecRestoreArray");
      basis.push_back(z);
    }
    check(MatNullSpaceCreate(comm, PETSC_FALSE, PetscInt(basis.size()), basis.data(), null_space_.out()),
          "MatNullSpaceCreate");
    for (Vec& z : basis) VecDestroy(&z);
    check(MatSetNullSpace(poisson_matrix_.get(), null_space_.get()), "MatSetNullSpace");
    check(MatSetTransposeNullSpace(poisson_matrix_.get(), null_space_.get()), "MatSetTransposeNullSpace");
    check(MatSetNearNullSpace(poisson_matrix_.get(), null_space_.get()), "MatSetNearNullSpace");
    check(MatSetOption(poisson_matrix_.get(), MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  }
  poisson_ = make_ksp(comm, poisson_matrix_.get(), "poisson_", options.solver, options.rtol);
}

Eigen::VectorXd HeatGeodesics::distance(std::span<const int> sources) const {
  const int nv = int(part_.global_index.size());
  PetscInt lo = 0, hi = 0;
  check(MatGetOwnershipRange(ops_.S.get(), &lo, &hi), "MatGetOwnershipRange");
  std::vector<unsigned char> reached(size_t(part_.n_components), 0);
  // The same checks on every rank (every rank holds the mesh), then the owner's stiffness check.
  agree(comm_, [&] {
    if (sources.empty()) throw std::out_of_range("heat geodesics: no source vertex given");
    for (int s : sources) {
      if (s < 0 || s >= nv)
        throw std::out_of_range(fmt::format("heat geodesics: source vertex {} out of range [0, {})", s, nv));
      const int g = part_.global_index[size_t(s)];
      if (g < 0 || (g >= lo && g < hi && !coupled_[size_t(g - lo)]))
        throw std::out_of_range(fmt::format(
            "heat geodesics: source vertex {} carries no stiffness (unreferenced, or only in zero-area faces)", s));
      reached[size_t(part_.vertex_component[size_t(s)])] = 1;
    }
  });
  Handle<Vec> delta, rhs, u, b, d;
  check(VecDuplicate(ops_.M_lumped.get(), delta.out()), "VecDuplicate");
  check(VecSet(delta.get(), 0.0), "VecSet");
  for (int s : sources) {
    const PetscInt gi = part_.global_index[size_t(s)];
    if (gi >= lo && gi < hi) check(VecSetValue(delta.get(), gi, 1.0, INSERT_VALUES), "VecSetValue");
  }
  check(VecAssemblyBegin(delta.get()), "VecAssemblyBegin");
  check(VecAssemblyEnd(delta.get()), "VecAssemblyEnd");
  // (31): (M - t S) u = M delta
  check(VecDuplicate(delta.get(), rhs.out()), "VecDuplicate");
  if (!options_.mass_weighted_source)
    check(VecCopy(delta.get(), rhs.get()), "VecCopy");
  else if (options_.lumped_mass)
    check(VecPointwiseMult(rhs.get(), ops_.M_lumped.get(), delta.get()), "VecPointwiseMult");
  else
    check(MatMult(ops_.M.get(), delta.get(), rhs.get()), "MatMult");
  auto zero_rows = [&](Vec x, const std::vector<PetscInt>& rows) {
    PetscScalar* a = nullptr;
    check(VecGetArray(x, &a), "VecGetArray");
    for (PetscInt r : rows) a[r - lo] = 0.0;
    check(VecRestoreArray(x, &a), "VecRestoreArray");
  };
  std::vector<PetscInt> uncoupled;
  for (PetscInt r = lo; r < hi; ++r)
    if (!coupled_[size_t(r - lo)]) uncoupled.push_back(r);
  zero_rows(rhs.get(), uncoupled);
  check(VecDuplicate(delta.get(), u.out()), "VecDuplicate");
  heat_its_ = solve(heat_.get(), rhs.get(), u.get(), "heat operator M - t S");
  // (32), (33): -D g with g = -grad u / |grad u| per fan triangle, face by face on each rank.
  check(VecDuplicate(delta.get(), b.out()), "VecDuplicate");
  divergence_of_gradient(ops_, u.get(), b.get(), true);
  check(VecScale(b.get(), -1.0), "VecScale");
  // (-S) d = -D g with the pinned vertices at 0 (direct) or the null space removed (CG).
  zero_rows(b.get(), pin_);
  check(VecDuplicate(delta.get(), d.out()), "VecDuplicate");
  poisson_its_ = solve(poisson_.get(), b.get(), d.get(), "Poisson operator -S");
  // Minimum 0 on every reached component; +infinity elsewhere.
  const int nc = part_.n_components;
  std::vector<double> cmin(size_t(nc), std::numeric_limits<double>::infinity());
  PetscScalar* a = nullptr;
  check(VecGetArray(d.get(), &a), "VecGetArray");
  for (PetscInt r = lo; r < hi; ++r)
    if (coupled_[size_t(r - lo)]) {
      const int c = part_.vertex_component[size_t(part_.mesh_vertex[size_t(r)])];
      cmin[size_t(c)] = std::min(cmin[size_t(c)], double(a[r - lo]));
    }
  MPI_Allreduce(MPI_IN_PLACE, cmin.data(), nc, MPI_DOUBLE, MPI_MIN, comm_);
  for (PetscInt r = lo; r < hi; ++r) {
    const int c = part_.vertex_component[size_t(part_.mesh_vertex[size_t(r)])];
    a[r - lo] = coupled_[size_t(r - lo)] && reached[size_t(c)] ? a[r - lo] - cmin[size_t(c)]
                                                               : std::numeric_limits<double>::infinity();
  }
  // How far the heat step was resolved (see heat_unresolved()).
  PetscReal umax = 0;
  check(VecMax(u.get(), nullptr, &umax), "VecMax");
  const double resolution = (options_.solver == LinearSolver::MumpsCholesky ? 1e-280 : 10 * options_.rtol) * umax;
  const PetscScalar* ua = nullptr;
  check(VecGetArrayRead(u.get(), &ua), "VecGetArrayRead");
  long below = 0;
  double radius = 0;
  for (PetscInt r = lo; r < hi; ++r) {
    if (!std::isfinite(a[r - lo])) continue;
    if (ua[r - lo] > resolution)
      radius = std::max(radius, double(a[r - lo]));
    else
      ++below;
  }
  check(VecRestoreArrayRead(u.get(), &ua), "VecRestoreArrayRead");
  check(VecRestoreArray(d.get(), &a), "VecRestoreArray");
  MPI_Allreduce(&below, &heat_unresolved_, 1, MPI_LONG, MPI_SUM, comm_);
  MPI_Allreduce(&radius, &heat_resolved_radius_, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return gather_to_root(d.get(), part_, std::numeric_limits<double>::infinity());
}

Spectrum spectrum(MPI_Comm comm, const Partition& part, const DistributedOperators& ops,
                  const SpectrumOptions& options) {
  const int N = part.n_global();
  if (options.k < 1 || options.k >= N)
    throw std::invalid_argument(fmt::format("spectrum: k = {} must lie in [1, {})", options.k, N));
  PetscReal min_mass = 0;
  check(VecMin(ops.M_lumped.get(), nullptr, &min_mass), "VecMin");
  if (!(min_mass > 0))
    throw SolverError("spectrum (PETSc): a vertex has zero lumped mass (only zero-area faces around it); "
                      "the distributed spectrum needs positive mass everywhere");
  PetscScalar area = 0;
  check(VecSum(ops.M_lumped.get(), &area), "VecSum");
  Spectrum result;
  result.shift = -options.shift_factor / area;
  Handle<Mat> A, B;
  check(MatDuplicate(ops.S.get(), MAT_COPY_VALUES, A.out()), "MatDuplicate");
  check(MatScale(A.get(), -1.0), "MatScale");
  check(MatSetOption(A.get(), MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  PetscInt lo = 0, hi = 0;
  check(MatGetOwnershipRange(ops.S.get(), &lo, &hi), "MatGetOwnershipRange");
  if (options.lumped_mass) {
    check(MatCreateAIJ(comm, hi - lo, hi - lo, N, N, 1, nullptr, 0, nullptr, B.out()), "MatCreateAIJ");
    const PetscScalar* m = nullptr;
    check(VecGetArrayRead(ops.M_lumped.get(), &m), "VecGetArrayRead");
    for (PetscInt r = lo; r < hi; ++r) check(MatSetValue(B.get(), r, r, m[r - lo], INSERT_VALUES), "MatSetValue");
    check(VecRestoreArrayRead(ops.M_lumped.get(), &m), "VecRestoreArrayRead");
    check(MatAssemblyBegin(B.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(B.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  } else {
    if (!ops.M.get()) throw std::invalid_argument("spectrum: Galerkin mass requested, not assembled");
    check(MatDuplicate(ops.M.get(), MAT_COPY_VALUES, B.out()), "MatDuplicate");
  }
  check(MatSetOption(B.get(), MAT_SPD, PETSC_TRUE), "MatSetOption");
  Handle<EPS> eps;
  check(EPSCreate(comm, eps.out()), "EPSCreate");
  check(EPSSetOperators(eps.get(), A.get(), B.get()), "EPSSetOperators");
  check(EPSSetProblemType(eps.get(), EPS_GHEP), "EPSSetProblemType");
  check(EPSSetType(eps.get(), EPSKRYLOVSCHUR), "EPSSetType");
  check(EPSSetDimensions(eps.get(), options.k, PETSC_DEFAULT, PETSC_DEFAULT), "EPSSetDimensions");
  check(EPSSetTarget(eps.get(), result.shift), "EPSSetTarget");
  check(EPSSetWhichEigenpairs(eps.get(), EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
  check(EPSSetTolerances(eps.get(), options.tolerance, options.max_iterations), "EPSSetTolerances");
  ST st = nullptr;
  check(EPSGetST(eps.get(), &st), "EPSGetST");
  check(STSetType(st, STSINVERT), "STSetType");
  KSP ksp = nullptr;
  check(STGetKSP(st, &ksp), "STGetKSP");
  configure_ksp(ksp, options.solver, 1e-12);
  check(EPSSetFromOptions(eps.get()), "EPSSetFromOptions");
  // Krylov-Schur from one start vector finds the copies of a multiple eigenvalue only as rounding
  // errors grow them, and may converge first (the icosahedral sphere's lambda_1 has 3, lambda_2
  // has 5). So solve again with every pair found so far as deflation space (SLEPc keeps the
  // factorization), until a pass finds nothing below the k-th smallest value found.
  std::vector<double> lambda;
  std::vector<Vec> found;
  auto kth = [&] {
    std::vector<double> l = lambda;
    std::sort(l.begin(), l.end());
    return int(l.size()) >= options.k ? l[size_t(options.k) - 1] : std::numeric_limits<double>::infinity();
  };
  struct VecList {
    std::vector<Vec>& v;
    ~VecList() {
      for (Vec& x : v) VecDestroy(&x);
    }
  } release{found};
  for (int pass = 0; pass <= options.k; ++pass) {
    if (pass > 0) check(EPSSetDeflationSpace(eps.get(), PetscInt(found.size()), found.data()), "EPSSetDeflationSpace");
    check(EPSSolve(eps.get()), "EPSSolve (SLEPc Krylov-Schur, shift-and-invert)");
    PetscInt nconv = 0, its = 0;
    check(EPSGetConverged(eps.get(), &nconv), "EPSGetConverged");
    check(EPSGetIterationNumber(eps.get(), &its), "EPSGetIterationNumber");
    result.n_iterations += int(its);
    ++result.n_passes;
    if (pass == 0 && nconv < options.k)
      throw SolverError(fmt::format("spectrum (SLEPc): {} of {} eigenpairs converged after {} restarts", int(nconv),
                                    options.k, int(its)));
    const double bound = kth();
    int below = 0;
    for (PetscInt i = 0; i < nconv; ++i) {
      PetscScalar kr = 0, ki = 0;
      check(EPSGetEigenvalue(eps.get(), i, &kr, &ki), "EPSGetEigenvalue");
      Vec x = nullptr;
      check(MatCreateVecs(A.get(), &x, nullptr), "MatCreateVecs");
      found.push_back(x);
      check(EPSGetEigenvector(eps.get(), i, x, nullptr), "EPSGetEigenvector");
      lambda.push_back(kr);
      if (kr < bound * (1 - 1e-9)) ++below;
    }
    if (below == 0) break;
  }
  result.n_converged = int(lambda.size());
  // The k smallest pairs, ascending; vectors scaled to unit M-norm (SLEPc's are B-orthonormal for
  // GHEP already; the scaling makes the output independent of that detail).
  std::vector<int> order(lambda.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return lambda[size_t(a)] < lambda[size_t(b)]; });
  result.eigenvalues.resize(options.k);
  Handle<Vec> Ax, Bx;
  PetscReal normA = 0, normB = 0;
  check(MatNorm(A.get(), NORM_INFINITY, &normA), "MatNorm");
  check(MatNorm(B.get(), NORM_INFINITY, &normB), "MatNorm");
  check(MatCreateVecs(A.get(), nullptr, Ax.out()), "MatCreateVecs");
  check(MatCreateVecs(A.get(), nullptr, Bx.out()), "MatCreateVecs");
  for (int c = 0; c < options.k; ++c) {
    const int i = order[size_t(c)];
    Vec x = found[size_t(i)];
    result.eigenvalues[c] = lambda[size_t(i)];
    check(MatMult(B.get(), x, Bx.get()), "MatMult");
    PetscScalar xBx = 0;
    check(VecDot(x, Bx.get(), &xBx), "VecDot");
    check(VecScale(x, 1.0 / std::sqrt(xBx)), "VecScale");
    check(VecScale(Bx.get(), 1.0 / std::sqrt(xBx)), "VecScale");
    check(MatMult(A.get(), x, Ax.get()), "MatMult");
    PetscReal nx = 0, nr = 0;
    check(VecNorm(x, NORM_2, &nx), "VecNorm");
    check(VecAXPY(Ax.get(), -lambda[size_t(i)], Bx.get()), "VecAXPY");
    check(VecNorm(Ax.get(), NORM_2, &nr), "VecNorm");
    result.max_residual =
        std::max(result.max_residual, double(nr / ((normA + std::abs(lambda[size_t(i)]) * normB) * nx)));
    if (!options.vectors) continue;
    const Eigen::VectorXd col = gather_to_root(x, part, 0.0);
    if (col.size() > 0) {
      if (result.eigenvectors.size() == 0) result.eigenvectors.resize(col.size(), options.k);
      result.eigenvectors.col(c) = col;
    }
  }
  return result;
}

}  // namespace polydec::petsc
