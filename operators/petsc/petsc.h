// operators/petsc/petsc.h — the distributed engine on PETSc, SLEPc and MPI (built with
// -DPOLYDEC_WITH_PETSC=ON, library polydec_petsc): the mesh partition, the distributed assembly of
// S, M, lumped M with the serial per-face code, the heat method's gradient and divergence applied
// face by face on each rank's faces, heat geodesics (eq. 31-33) with MUMPS Cholesky or CG +
// algebraic multigrid, the smallest eigenpairs of -S x = lambda M x with SLEPc, and the agreement
// of errors across ranks.
//
// Every rank holds the mesh in compact form only (MeshView: positions and face index lists, no
// topology; every rank reads the file, a parallel reader is a later step) and builds a validated
// Mesh only of its own faces. The faces are ordered along a Morton (Z-order) curve of their centroids and cut into equal blocks,
// one per rank, by a rule every rank evaluates alike without communication. Each rank owns a
// contiguous range of renumbered vertices ("global" numbering: vertices in the order in which the
// curve's faces first touch them), builds the operators of its faces with build_operators on the
// sub-mesh of those faces (the serial kernels and assembly), and hands the entries to PETSc with
// MatSetValuesCOO, which sums the contributions to the vertices shared between ranks.
// Unreferenced vertices take no part (no global index). Conventions as operators/surface/laplacian.h: S
// negative semi-definite. Results come back to rank 0 in the mesh's vertex order.
#pragma once

#include <petscksp.h>
#include <slepceps.h>

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <exception>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec::petsc {

// PETSc and SLEPc initialized for the lifetime of the object (MPI too, unless already running);
// `options` (e.g. "-ksp_monitor -eps_view") are added to PETSc's options database before any
// object reads it. PETSc errors return codes (no traceback printed), turned into SolverError.
class Session {
 public:
  explicit Session(const std::string& options = "");
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  MPI_Comm comm() const { return PETSC_COMM_WORLD; }
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
  bool finalize_mpi_ = false;
};

// Runs f on every rank, then agrees (one MPI_Allreduce of a status) on whether any rank failed;
// if one did, every rank throws the error of the lowest failing rank (same type for FileError,
// InvalidMeshError, SolverError, std::out_of_range, std::invalid_argument; std::runtime_error
// otherwise; same message). Collective: call it on every rank, before anything collective that
// a failure on one rank would leave the others waiting in.
void agree(MPI_Comm comm, const std::function<void()>& f);

// The compact form of a mesh that every rank holds: positions, face index lists and coordinate
// precision (a PolygonSoup's or a Mesh's arrays, not copied; no topology). Must outlive its use.
struct MeshView {
  MeshView(const PolygonSoup& soup)  // NOLINT: implicit, so that Mesh and soup both pass
      : positions(soup.positions), face_offsets(soup.face_offsets), face_indices(soup.face_indices),
        precision(soup.precision) {}
  MeshView(const Mesh& mesh)  // NOLINT
      : positions(mesh.positions()), face_offsets(mesh.face_offsets()), face_indices(mesh.face_indices()),
        precision(mesh.precision()) {}
  const Eigen::MatrixX3d& positions;
  std::span<const int> face_offsets, face_indices;
  CoordinatePrecision precision;
  int n_vertices() const { return int(positions.rows()); }
  int n_faces() const { return int(face_offsets.size()) - 1; }
  // As Mesh::rms_radius and Mesh::coordinate_noise.
  double rms_radius() const;
  double coordinate_noise() const { return precision.noise * rms_radius(); }
};

// The partition of a mesh's faces into `n_ranks` blocks and the vertex numbering that follows.
struct Partition {
  int n_ranks = 1;
  std::vector<int> face_order;     // |F|: faces along the Morton curve of their centroids
  std::vector<int> face_begin;     // n_ranks + 1: rank r has face_order[face_begin[r] .. face_begin[r+1])
  std::vector<int> global_index;   // |V|: the vertex's global index, -1 for unreferenced vertices
  std::vector<int> mesh_vertex;    // N: inverse of global_index
  std::vector<int> vertex_begin;   // n_ranks + 1: rank r owns global indices [vertex_begin[r], vertex_begin[r+1])
  std::vector<int> vertex_component;  // |V|: connected component (faces sharing vertices), -1 unreferenced
  int n_components = 0;
  int n_global() const { return int(mesh_vertex.size()); }
};

// The partition; identical on every rank that calls it with the same mesh and count.
Partition partition_mesh(const MeshView& mesh, int n_ranks);

// Destruction of the PETSc objects a Handle holds.
inline void destroy(Mat* x) { MatDestroy(x); }
inline void destroy(Vec* x) { VecDestroy(x); }
inline void destroy(KSP* x) { KSPDestroy(x); }
inline void destroy(EPS* x) { EPSDestroy(x); }
inline void destroy(MatNullSpace* x) { MatNullSpaceDestroy(x); }
inline void destroy(VecScatter* x) { VecScatterDestroy(x); }
inline void destroy(IS* x) { ISDestroy(x); }

// A PETSc object destroyed with its owner.
template <class T>
class Handle {
 public:
  Handle() = default;
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : h_(o.h_) { o.h_ = nullptr; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      h_ = o.h_;
      o.h_ = nullptr;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  T get() const { return h_; }
  T* out() {
    reset();
    return &h_;
  }
  void reset() {
    if (h_) destroy(&h_);
    h_ = nullptr;
  }

 private:
  T h_ = nullptr;
};

// The operators of "ours" on the distributed mesh, in the global vertex numbering: S, M (N x N,
// MPIAIJ, rows owned as in the partition), lumped M (Vec); with_gradient, this rank's gradient G
// (3 rows per fan triangle of its faces, operators/surface/gradient.h) as a local Eigen matrix of its
// sub-mesh (local vertex numbering, local_to_global) and the fan triangles' areas W, so that the
// divergence is D = -G^T W (no copy of D); applied by divergence_of_gradient.
struct DistributedOperators {
  Handle<Mat> S, M;
  Handle<Vec> M_lumped;
  Eigen::SparseMatrix<double> G;        // with_gradient only: this rank's sub-mesh, local vertices
  Eigen::VectorXd fan_area;             // with_gradient only: one per fan triangle (row triple of G)
  std::vector<PetscInt> local_to_global;  // n_local_vertices: global index of each local vertex
  double mean_edge_length = 0;          // of the whole mesh (every undirected edge once)
  FanQuality quality;       // summed over the ranks
  int n_local_faces = 0;    // this rank's faces
  int n_local_vertices = 0; // vertices of this rank's faces (owned and shared)
  long n_coo_entries = 0;   // this rank's entries handed to MatSetValuesCOO (S and M each)
};

// Collective. Validates the mesh across ranks: each rank's faces form a valid Mesh (the serial
// validation), and the edges between ranks' faces (those whose both ends touch faces of two ranks,
// gathered on every rank) are shared by at most two faces in opposite directions, so that the
// whole mesh passes the serial validation. Bad input raises the same error on every rank.
// Without with_galerkin_mass, M stays empty (the lumped mass alone: default heat geodesics and spectrum).
DistributedOperators assemble_operators(MPI_Comm comm, const MeshView& mesh, const Partition& partition,
                                        bool with_gradient = true, bool with_galerkin_mass = true);

// b = D X with X = G u (normalized = false; then b = S u) or X = -G u / |G u| per fan triangle, zero
// where the gradient vanishes (normalized = true: eq. 32), computed on each rank's faces with u
// gathered at their vertices (one VecScatter) and summed into b with ADD_VALUES. Collective; needs
// operators assembled with_gradient; u and b are laid out as ops.M_lumped.
void divergence_of_gradient(const DistributedOperators& ops, Vec u, Vec b, bool normalized);

// On rank 0: the distributed vector x (global numbering) in mesh vertex order, `fill` at
// unreferenced vertices; other ranks get an empty vector. Collective.
Eigen::VectorXd gather_to_root(Vec x, const Partition& partition, double fill = 0.0);
// On rank 0: the distributed N x N matrix A as |V| x |V| in mesh vertex order (empty rows and
// columns at unreferenced vertices); other ranks get an empty matrix. Collective. For tests and
// small meshes.
Eigen::SparseMatrix<double> gather_to_root(Mat A, const Partition& partition);

// Which linear solver: direct MUMPS Cholesky, or conjugate gradients with PETSc's GAMG or hypre's
// BoomerAMG. Options with the solver's prefix override the choice (-heat_ksp_type, -poisson_pc_type,
// -st_ksp_type ...).
enum class LinearSolver { MumpsCholesky, CgGamg, CgBoomerAmg };
// "direct", "cg-gamg", "cg-hypre"; throws std::invalid_argument for other names.
LinearSolver parse_linear_solver(const std::string& name);
std::string linear_solver_name(LinearSolver s);

struct GeodesicsOptions {
  double time_step_factor = 1.0;  // t = factor * mean_edge_length^2 (of the input mesh)
  bool lumped_mass = true;        // lumped or Galerkin mass in eq. (31)
  bool mass_weighted_source = true;  // right-hand side M delta (else delta), as HeatGeodesicsOptions
  LinearSolver solver = LinearSolver::MumpsCholesky;
  double rtol = 1e-14;  // relative residual of the CG solves (1e-12 left GAMG 3e-5 of the diameter
                        // off the direct solve on suzanne-half: the far field of the heat step)
};

// Heat geodesics (eq. 31-33) on distributed operators, as HeatGeodesics (apps/applications/
// geodesics.h): the constructor sets up (factors, or builds the multigrid hierarchy of) M - t S
// and the Poisson operator -S; components are those of the mesh's faces. The Poisson step's
// constant null space per component: the direct solver pins one vertex per component; CG keeps
// the singular matrix and removes the null space (MatSetNullSpace) from the right-hand side and
// the iterates. Vertices without stiffness (only in zero-area faces) are pinned to 0 in both
// steps and get +infinity, like unreferenced vertices and components without a source.
class HeatGeodesics {
 public:
  // mean_edge_length <= 0: the operators' (the whole mesh's).
  HeatGeodesics(MPI_Comm comm, const Partition& partition, const DistributedOperators& ops, double mean_edge_length,
                const GeodesicsOptions& options = {});
  // Collective: the distances from mesh vertices `sources` (mesh indices), on rank 0 in mesh
  // order (empty elsewhere). Throws std::out_of_range on every rank for a bad source.
  Eigen::VectorXd distance(std::span<const int> sources) const;
  double time_step() const { return t_; }
  // Iterations of the last distance() call's two solves (1 each for the direct solver).
  int heat_iterations() const { return heat_its_; }
  int poisson_iterations() const { return poisson_its_; }
  // Vertices of the last distance() call whose heat value u lies below the solve's resolution, and
  // the largest distance among the resolved ones. The heat step (31) decays about e^-1 per sqrt(t)
  // from the sources; where u is below the resolution its normalized gradient (32), hence the
  // distance, is noise. Resolution: 10 rtol max(u) for CG (the residual: about 30 sqrt(t) from the
  // sources at rtol 1e-14; a cautious count: on hex_sphere(3) 70 vertices count while the distances
  // stay within 1e-6 of the diameter; on a 30k-quad torus the far field was off by 70%), 1e-280
  // max(u) for the direct solver (double precision's range: ~650 sqrt(t)). Callers warn and suggest
  // a larger time step factor (apps/applications/geodesics.h, suggested_time_factor).
  long heat_unresolved() const { return heat_unresolved_; }
  double heat_resolved_radius() const { return heat_resolved_radius_; }

 private:
  MPI_Comm comm_;
  const Partition& part_;
  const DistributedOperators& ops_;
  GeodesicsOptions options_;
  double t_ = 0;
  std::vector<unsigned char> coupled_;  // owned rows: vertex has stiffness
  std::vector<int> pin_;                // global rows pinned in the Poisson step (direct solver), owned here
  Handle<Mat> heat_matrix_, poisson_matrix_;
  Handle<KSP> heat_, poisson_;
  Handle<MatNullSpace> null_space_;
  mutable int heat_its_ = 0, poisson_its_ = 0;
  mutable long heat_unresolved_ = 0;
  mutable double heat_resolved_radius_ = 0;
};

struct SpectrumOptions {
  int k = 10;
  bool lumped_mass = true;
  double shift_factor = 0.1;  // sigma = -shift_factor / area, as apps/applications/spectrum.h
  double tolerance = 1e-10;   // SLEPc's relative tolerance
  int max_iterations = 1000;
  LinearSolver solver = LinearSolver::MumpsCholesky;  // of the shift-invert solves
  bool vectors = true;  // gather the eigenvectors on rank 0 (|V| x k doubles there)
};

struct Spectrum {
  Eigen::VectorXd eigenvalues;   // k, ascending (on every rank)
  Eigen::MatrixXd eigenvectors;  // rank 0: |V| x k in mesh order, M-orthonormal; empty elsewhere
  double shift = 0;
  int n_converged = 0;    // pairs found over all passes (at least k)
  int n_iterations = 0;   // Krylov-Schur restarts, summed over the passes
  // Largest backward error of the k pairs, ||A x - lambda B x|| / ((||A|| + |lambda| ||B||) ||x||)
  // with A = -S, B the mass and the infinity norm of the matrices: computed from the returned pairs,
  // independently of SLEPc's own test.
  double max_residual = 0;
  int n_passes = 0;       // solves with the pairs found so far as deflation space (see spectrum())
};

// The k smallest eigenpairs of -S x = lambda M x by SLEPc's Krylov-Schur with shift-and-invert at
// sigma (generalized Hermitian): the constant mode of each component is the eigenvalue 0, kept as
// the serial spectrum keeps it. Krylov-Schur from one start vector may converge before it has
// found every copy of a multiple eigenvalue, so the solve is repeated with the pairs found so far
// as deflation space until a pass finds nothing below the k-th value (usually 2 passes). Collective; SolverError when fewer than k pairs converge or a
// vertex has zero lumped mass.
Spectrum spectrum(MPI_Comm comm, const Partition& partition, const DistributedOperators& ops,
                  const SpectrumOptions& options = {});

// Peak resident memory of this process (MB, getrusage).
double peak_rss_mb();
// Every rank's `values` (same length on every rank), gathered on rank 0 (rows by rank); other
// ranks get an empty vector. Collective.
std::vector<std::vector<double>> gather_per_rank(MPI_Comm comm, const std::vector<double>& values);

}  // namespace polydec::petsc
