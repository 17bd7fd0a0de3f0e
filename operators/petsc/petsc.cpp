// operators/petsc/petsc.cpp — session, error agreement, partition, distributed assembly and the
// gathers of the PETSc engine (operators/petsc/petsc.h).
#include "polydec/operators/petsc/petsc.h"

#include <fmt/format.h>
#include <slepcsys.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <numeric>
#include <stdexcept>
#include <string>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/detail/union_find.h"
#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/surface/gradient.h"
#include "polydec/operators/registry/laplacians.h"
#include "polydec/operators/petsc/petsc_check.h"

namespace polydec::petsc {

namespace {

// PETSc's own words for the error being returned: the message and function where it was raised
// (the innermost call), recorded by the error handler and appended by check().
thread_local std::string petsc_detail;

PetscErrorCode record_error(MPI_Comm, int, const char* func, const char*, PetscErrorCode code, PetscErrorType type,
                            const char* message, void*) {
  if (type == PETSC_ERROR_INITIAL)
    petsc_detail = fmt::format("{} (in {})", message && *message ? message : "no detail", func ? func : "?");
  return code;
}

}  // namespace

void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  std::string detail = std::move(petsc_detail);
  petsc_detail.clear();
  throw SolverError(fmt::format("PETSc: {} failed (error {}: {}{}{})", what, int(code), text ? text : "?",
                                detail.empty() ? "" : ": ", detail));
}

Session::Session(const std::string& options) {
  int mpi_up = 0;
  MPI_Initialized(&mpi_up);
  if (!mpi_up) {
    int provided = 0;
    if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
      throw SolverError("MPI_Init failed");
    finalize_mpi_ = true;
  }
  // PETSc reads its options at initialization and when objects call *SetFromOptions.
  if (SlepcInitialize(nullptr, nullptr, nullptr, nullptr) != 0) throw SolverError("SlepcInitialize failed");
  PetscPushErrorHandler(record_error, nullptr);
  if (!options.empty()) check(PetscOptionsInsertString(nullptr, options.c_str()), "reading --petsc-options");
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank_);
  MPI_Comm_size(PETSC_COMM_WORLD, &size_);
}

Session::~Session() {
  SlepcFinalize();
  if (finalize_mpi_) MPI_Finalize();
}

namespace {

// Kinds of error carried across ranks by agree().
enum ErrorKind : long long { kNone = 0, kFile, kMesh, kSolver, kRange, kArgument, kOther };

struct Carried {
  long long kind = kNone, a = 0, b = 0;
  std::string s1, s2, s3;
};

}  // namespace

void agree(MPI_Comm comm, const std::function<void()>& f) {
  Carried c;
  try {
    f();
  } catch (const FileError& e) {
    c = {kFile, e.line, e.byte_offset, e.file, e.reason, ""};
  } catch (const InvalidMeshError& e) {
    c = {kMesh, e.index, 0, e.element, e.what(), ""};
  } catch (const SolverError& e) {
    c = {kSolver, 0, 0, e.what(), "", ""};
  } catch (const std::out_of_range& e) {
    c = {kRange, 0, 0, e.what(), "", ""};
  } catch (const std::invalid_argument& e) {
    c = {kArgument, 0, 0, e.what(), "", ""};
  } catch (const std::exception& e) {
    c = {kOther, 0, 0, e.what(), "", ""};
  }
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int first = c.kind != kNone ? rank : size;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  // The lowest failing rank's error, to everyone.
  std::string text = c.s1 + '\0' + c.s2 + '\0' + c.s3;
  long long head[4] = {c.kind, c.a, c.b, (long long)text.size()};
  MPI_Bcast(head, 4, MPI_LONG_LONG, first, comm);
  text.resize(static_cast<size_t>(head[3]));
  MPI_Bcast(text.data(), int(head[3]), MPI_CHAR, first, comm);
  const size_t z1 = text.find('\0'), z2 = text.find('\0', z1 + 1);
  const std::string s1 = text.substr(0, z1), s2 = text.substr(z1 + 1, z2 - z1 - 1);
  switch (head[0]) {
    case kFile:
      throw FileError(s1, long(head[1]), long(head[2]), s2);
    case kMesh:
      throw InvalidMeshError(s1, long(head[1]), s2);
    case kSolver:
      throw SolverError(s1);
    case kRange:
      throw std::out_of_range(s1);
    case kArgument:
      throw std::invalid_argument(s1);
    default:
      throw std::runtime_error(s1);
  }
}

namespace {

// Bits of x (21 of them) spread to every third bit.
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

}  // namespace

double MeshView::rms_radius() const {
  if (n_vertices() == 0) return 0.0;
  const Eigen::RowVector3d c = positions.colwise().mean();
  return std::sqrt((positions.rowwise() - c).rowwise().squaredNorm().mean());
}

Partition partition_mesh(const MeshView& mesh, int n_ranks) {
  if (n_ranks < 1) throw std::invalid_argument("partition: at least one rank needed");
  const int nf = mesh.n_faces(), nv = mesh.n_vertices();
  if (nf < n_ranks)
    throw std::invalid_argument(fmt::format("partition: {} faces cannot be split over {} ranks", nf, n_ranks));
  const int* offsets = mesh.face_offsets.data();
  const int* indices = mesh.face_indices.data();
  const Eigen::MatrixX3d& X = mesh.positions;
  Eigen::MatrixX3d c(nf, 3);
  for (int f = 0; f < nf; ++f) {
    Eigen::RowVector3d s = Eigen::RowVector3d::Zero();
    for (int h = offsets[f]; h < offsets[f + 1]; ++h) s += X.row(indices[h]);
    c.row(f) = s / double(offsets[f + 1] - offsets[f]);
  }
  const Eigen::RowVector3d lo = c.colwise().minCoeff(), ext = c.colwise().maxCoeff() - lo;
  std::vector<std::uint64_t> code(static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    std::uint64_t key = 0;
    for (int a = 0; a < 3; ++a) {
      const double u = ext[a] > 0 ? (c(f, a) - lo[a]) / ext[a] : 0.0;
      key |= spread_bits(std::uint64_t(std::clamp(u, 0.0, 1.0) * 2097151.0)) << a;
    }
    code[size_t(f)] = key;
  }
  c.resize(0, 3);
  Partition p;
  p.n_ranks = n_ranks;
  p.face_order.resize(static_cast<size_t>(nf));
  std::iota(p.face_order.begin(), p.face_order.end(), 0);
  std::sort(p.face_order.begin(), p.face_order.end(),
            [&](int a, int b) { return code[size_t(a)] != code[size_t(b)] ? code[size_t(a)] < code[size_t(b)] : a < b; });
  p.face_begin.resize(size_t(n_ranks) + 1);
  p.vertex_begin.assign(size_t(n_ranks) + 1, 0);
  p.global_index.assign(size_t(nv), -1);
  int next = 0;
  for (int r = 0; r < n_ranks; ++r) {
    p.face_begin[size_t(r)] = int(long(nf) * r / n_ranks);
    p.face_begin[size_t(r) + 1] = int(long(nf) * (r + 1) / n_ranks);
    for (int i = p.face_begin[size_t(r)]; i < p.face_begin[size_t(r) + 1]; ++i) {
      const int f = p.face_order[size_t(i)];
      for (int h = offsets[f]; h < offsets[f + 1]; ++h)
        if (p.global_index[size_t(indices[h])] < 0) p.global_index[size_t(indices[h])] = next++;
    }
    p.vertex_begin[size_t(r) + 1] = next;
  }
  p.mesh_vertex.resize(static_cast<size_t>(next));
  for (int v = 0; v < nv; ++v)
    if (p.global_index[size_t(v)] >= 0) p.mesh_vertex[size_t(p.global_index[size_t(v)])] = v;
  // Components: vertices joined by faces.
  std::vector<int> parent(static_cast<size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0);
  for (int f = 0; f < nf; ++f) {
    const int a = find_root(parent, indices[offsets[f]]);
    for (int h = offsets[f] + 1; h < offsets[f + 1]; ++h) {
      const int b = find_root(parent, indices[h]);
      if (a != b) parent[size_t(b)] = a;
    }
  }
  p.vertex_component.assign(size_t(nv), -1);
  std::vector<int> label(size_t(nv), -1);
  for (int v = 0; v < nv; ++v) {
    if (p.global_index[size_t(v)] < 0) continue;
    int& l = label[size_t(find_root(parent, v))];
    if (l < 0) l = p.n_components++;
    p.vertex_component[size_t(v)] = l;
  }
  return p;
}

namespace {

// A PETSc AIJ matrix (local sizes m x n, global M x N) from COO entries, summed where repeated.
Handle<Mat> coo_matrix(MPI_Comm comm, PetscInt m, PetscInt n, PetscInt M, PetscInt N, std::vector<PetscInt>& I,
                       std::vector<PetscInt>& J, const std::vector<PetscScalar>& V) {
  Handle<Mat> A;
  check(MatCreate(comm, A.out()), "MatCreate");
  check(MatSetSizes(A.get(), m, n, M, N), "MatSetSizes");
  check(MatSetType(A.get(), MATAIJ), "MatSetType");
  check(MatSetPreallocationCOO(A.get(), PetscCount(I.size()), I.data(), J.data()), "MatSetPreallocationCOO");
  check(MatSetValuesCOO(A.get(), V.data(), INSERT_VALUES), "MatSetValuesCOO");
  return A;
}

// Entries of a local sparse matrix with rows and columns mapped to global indices.
template <class RowMap, class ColMap>
void coo_entries(const SparseMatrix& A, RowMap row, ColMap col, std::vector<PetscInt>& I, std::vector<PetscInt>& J,
                 std::vector<PetscScalar>& V) {
  I.clear();
  J.clear();
  V.clear();
  I.reserve(static_cast<size_t>(A.nonZeros()));
  J.reserve(static_cast<size_t>(A.nonZeros()));
  V.reserve(static_cast<size_t>(A.nonZeros()));
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
      I.push_back(PetscInt(row(int(it.row()))));
      J.push_back(PetscInt(col(int(it.col()))));
      V.push_back(it.value());
    }
}

}  // namespace

namespace {

// One halfedge (a -> b, global vertex indices) of a face of `rank` whose both ends touch faces of
// two or more ranks: the edges across which the ranks' sub-meshes meet.
struct InterfaceHalfedge {
  int a, b, face, rank;  // face: in the mesh's numbering
};

// Every rank's interface halfedges, on every rank, sorted by undirected edge, then rank, face, a.
std::vector<InterfaceHalfedge> gather_interface(MPI_Comm comm, const MeshView& mesh, const Partition& part, int rank) {
  const int* offsets = mesh.face_offsets.data();
  const int* indices = mesh.face_indices.data();
  // A vertex touches two ranks iff a rank other than its owner (the first to touch it) holds a face with it.
  auto owner = [&](int v) {
    return int(std::upper_bound(part.vertex_begin.begin(), part.vertex_begin.end(), part.global_index[size_t(v)]) -
               part.vertex_begin.begin()) - 1;
  };
  std::vector<unsigned char> shared(size_t(mesh.n_vertices()), 0);
  for (int r = 0; r < part.n_ranks; ++r)
    for (int i = part.face_begin[size_t(r)]; i < part.face_begin[size_t(r) + 1]; ++i) {
      const int f = part.face_order[size_t(i)];
      for (int h = offsets[f]; h < offsets[f + 1]; ++h)
        if (!shared[size_t(indices[h])] && owner(indices[h]) != r) shared[size_t(indices[h])] = 1;
    }
  std::vector<int> mine;
  for (int i = part.face_begin[size_t(rank)]; i < part.face_begin[size_t(rank) + 1]; ++i) {
    const int f = part.face_order[size_t(i)];
    for (int h = offsets[f]; h < offsets[f + 1]; ++h) {
      const int a = indices[h], b = indices[h + 1 < offsets[f + 1] ? h + 1 : offsets[f]];
      if (shared[size_t(a)] && shared[size_t(b)])
        mine.insert(mine.end(), {part.global_index[size_t(a)], part.global_index[size_t(b)], f, rank});
    }
  }
  int size = 1;
  MPI_Comm_size(comm, &size);
  int n = int(mine.size());
  std::vector<int> counts(static_cast<size_t>(size)), displs(static_cast<size_t>(size) + 1, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 0; r < size; ++r) displs[size_t(r) + 1] = displs[size_t(r)] + counts[size_t(r)];
  std::vector<int> all(size_t(displs[size_t(size)]));
  MPI_Allgatherv(mine.data(), n, MPI_INT, all.data(), counts.data(), displs.data(), MPI_INT, comm);
  std::vector<InterfaceHalfedge> out(all.size() / 4);
  for (size_t k = 0; k < out.size(); ++k) out[k] = {all[4 * k], all[4 * k + 1], all[4 * k + 2], all[4 * k + 3]};
  auto key = [](const InterfaceHalfedge& e) { return std::tuple(std::min(e.a, e.b), std::max(e.a, e.b), e.rank, e.face, e.a); };
  std::sort(out.begin(), out.end(), [&](const auto& x, const auto& y) { return key(x) < key(y); });
  return out;
}

// The serial validation of the edges across ranks (Mesh's messages, mesh vertex and face numbers).
void check_interface(const std::vector<InterfaceHalfedge>& e, const Partition& part) {
  for (size_t k = 0; k < e.size();) {
    size_t l = k;
    auto same = [&](size_t m) { return std::min(e[m].a, e[m].b) == std::min(e[k].a, e[k].b) && std::max(e[m].a, e[m].b) == std::max(e[k].a, e[k].b); };
    while (l < e.size() && same(l)) ++l;
    const int a = part.mesh_vertex[size_t(std::min(e[k].a, e[k].b))], b = part.mesh_vertex[size_t(std::max(e[k].a, e[k].b))];
    std::vector<int> faces;
    for (size_t m = k; m < l; ++m) faces.push_back(e[m].face);
    std::sort(faces.begin(), faces.end());
    if (l - k > 2)
      throw InvalidMeshError("edge", 0,
                             fmt::format("edge ({}, {}) is shared by {} faces (non-manifold; faces {}, {}, {}...)",
                                         std::min(a, b), std::max(a, b), l - k, faces[0], faces[1], faces[2]));
    if (l - k == 2 && e[k].a == e[k + 1].a)
      throw InvalidMeshError(
          "edge", 0,
          fmt::format("faces {} and {} traverse edge ({}, {}) in the same direction (inconsistent orientation)",
                      faces[0], faces[1], std::min(a, b), std::max(a, b)));
    k = l;
  }
}

}  // namespace

DistributedOperators assemble_operators(MPI_Comm comm, const MeshView& mesh, const Partition& part, bool with_gradient,
                                        bool with_galerkin_mass) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (part.n_ranks != size)
    throw std::invalid_argument(
        fmt::format("assemble_operators: partition for {} ranks used on {}", part.n_ranks, size));
  DistributedOperators out;
  OperatorSet ops;
  std::vector<int> l2g;  // local vertex -> global index
  double edge_sum[2] = {0, 0};  // lengths and count of the edges this rank counts
  // The sub-mesh of this rank's faces, through the serial code (its validation included), then the
  // edges between ranks, then the operators: any failure is agreed.
  Mesh sub;
  agree(comm, [&] {
    const int* offsets = mesh.face_offsets.data();
    const int* indices = mesh.face_indices.data();
    std::vector<int> local(size_t(mesh.n_vertices()), -1);
    std::vector<int> verts;
    PolygonSoup soup;
    for (int i = part.face_begin[size_t(rank)]; i < part.face_begin[size_t(rank) + 1]; ++i) {
      const int f = part.face_order[size_t(i)];
      for (int h = offsets[f]; h < offsets[f + 1]; ++h) {
        int& l = local[size_t(indices[h])];
        if (l < 0) {
          l = int(verts.size());
          verts.push_back(indices[h]);
        }
        soup.face_indices.push_back(l);
      }
      soup.face_offsets.push_back(int(soup.face_indices.size()));
    }
    std::vector<int>().swap(local);
    soup.positions.resize(Eigen::Index(verts.size()), 3);
    l2g.resize(verts.size());
    for (size_t l = 0; l < verts.size(); ++l) {
      soup.positions.row(Eigen::Index(l)) = mesh.positions.row(verts[l]);
      l2g[l] = part.global_index[size_t(verts[l])];
    }
    try {
      sub = Mesh(std::move(soup));
    } catch (const InvalidMeshError&) {
      // The sub-mesh numbers vertices and faces its own way: for the serial message (file
      // numbering), validate the whole mesh on this rank. Only on this failure path.
      PolygonSoup whole;
      whole.positions = mesh.positions;
      whole.face_offsets.assign(mesh.face_offsets.begin(), mesh.face_offsets.end());
      whole.face_indices.assign(mesh.face_indices.begin(), mesh.face_indices.end());
      const Mesh whole_mesh(std::move(whole));
      throw;  // not reached: the whole mesh is invalid where its faces are
    }
    // The global mesh's coordinate precision, in absolute terms (it is stored relative to a
    // mesh's size), so that every rank decides planarity as the serial code does.
    CoordinatePrecision precision = mesh.precision;
    const double radius = sub.rms_radius();
    precision.noise = radius > 0 ? std::min<double>(mesh.coordinate_noise() / radius, 0.5) : 0.0;
    sub = sub.with_precision(precision);
  });
  std::vector<InterfaceHalfedge> interface = gather_interface(comm, mesh, part, rank);
  agree(comm, [&] {
    check_interface(interface, part);
    // Edges: inside this rank's faces counted here; an edge between ranks by the lowest of them.
    for (int e = 0; e < sub.n_edges(); ++e) {
      const int ga = l2g[size_t(sub.edges()(e, 0))], gb = l2g[size_t(sub.edges()(e, 1))];
      if (sub.is_boundary_edge(e)) {
        const InterfaceHalfedge probe{std::min(ga, gb), std::max(ga, gb), -1, -1};
        auto it = std::lower_bound(interface.begin(), interface.end(), probe, [](const auto& x, const auto& y) {
          return std::pair(std::min(x.a, x.b), std::max(x.a, x.b)) < std::pair(std::min(y.a, y.b), std::max(y.a, y.b));
        });
        if (it != interface.end() && std::min(it->a, it->b) == probe.a && std::max(it->a, it->b) == probe.b &&
            it->rank < rank)
          continue;
      }
      edge_sum[0] += (sub.position(sub.edges()(e, 0)) - sub.position(sub.edges()(e, 1))).norm();
      edge_sum[1] += 1;
    }
    std::vector<InterfaceHalfedge>().swap(interface);
    ops = build_operators(sub, parse_laplacian("ours"), false);
    out.n_local_faces = sub.n_faces();
    out.n_local_vertices = sub.n_vertices();
  });
  MPI_Allreduce(MPI_IN_PLACE, edge_sum, 2, MPI_DOUBLE, MPI_SUM, comm);
  out.mean_edge_length = edge_sum[1] > 0 ? edge_sum[0] / edge_sum[1] : 0.0;
  const PetscInt n_own = part.vertex_begin[size_t(rank) + 1] - part.vertex_begin[size_t(rank)];
  const PetscInt N = part.n_global();
  {
    std::vector<PetscInt> I, J;
    std::vector<PetscScalar> V;
    auto g = [&](int l) { return l2g[size_t(l)]; };
    coo_entries(ops.S, g, g, I, J, V);
    out.n_coo_entries = long(I.size());
    out.S = coo_matrix(comm, n_own, n_own, N, N, I, J, V);
    SparseMatrix().swap(ops.S);  // the local copies go as soon as PETSc holds the entries
    check(MatSetOption(out.S.get(), MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
    if (with_galerkin_mass) {
      coo_entries(ops.M, g, g, I, J, V);
      out.M = coo_matrix(comm, n_own, n_own, N, N, I, J, V);
      check(MatSetOption(out.M.get(), MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
    }
    SparseMatrix().swap(ops.M);
  }  // and the COO arrays with them
  out.local_to_global.assign(l2g.begin(), l2g.end());
  check(VecCreateMPI(comm, n_own, N, out.M_lumped.out()), "VecCreateMPI");
  check(VecSet(out.M_lumped.get(), 0.0), "VecSet");
  check(VecSetValues(out.M_lumped.get(), PetscInt(l2g.size()), out.local_to_global.data(), ops.M_lumped.data(),
                     ADD_VALUES),
        "VecSetValues");
  check(VecAssemblyBegin(out.M_lumped.get()), "VecAssemblyBegin");
  check(VecAssemblyEnd(out.M_lumped.get()), "VecAssemblyEnd");
  ops.M_lumped.resize(0);
  // The gradient after S and M have gone to PETSc (the peak is the larger of the two phases, not
  // their sum): the refinement of "ours" again, G and the fan areas; D is -G^T W when applied.
  if (with_gradient)
    agree(comm, [&] {
      RefinementOptions ro;
      ro.rule = VirtualVertexRule::SquaredArea;  // "ours", as build_operators
      const Refinement r = refine(sub, ro);
      SparseMatrix G = gradient(sub, r);
      out.G.swap(G);  // swap, not move: std::move copies an Eigen 3.4 SparseMatrix
      out.fan_area = fan_areas(sub, r);
    });
  sub = Mesh();
  int q[3] = {ops.quality.n_degenerate, ops.quality.n_inverted, ops.quality.n_faces_affected};
  MPI_Allreduce(MPI_IN_PLACE, q, 3, MPI_INT, MPI_SUM, comm);
  out.quality = {q[0], q[1], q[2]};
  return out;
}

void divergence_of_gradient(const DistributedOperators& ops, Vec u, Vec b, bool normalized) {
  if (ops.G.size() == 0 && ops.n_local_faces > 0)
    throw std::invalid_argument("divergence_of_gradient: the operators were assembled without gradient");
  const PetscInt n = PetscInt(ops.local_to_global.size());
  // u at this rank's vertices (owned and shared): one scatter from the global vector.
  Handle<IS> from;
  Handle<Vec> ul;
  Handle<VecScatter> scatter;
  check(ISCreateGeneral(PETSC_COMM_SELF, n, ops.local_to_global.data(), PETSC_USE_POINTER, from.out()), "ISCreateGeneral");
  check(VecCreateSeq(PETSC_COMM_SELF, n, ul.out()), "VecCreateSeq");
  check(VecScatterCreate(u, from.get(), ul.get(), nullptr, scatter.out()), "VecScatterCreate");
  check(VecScatterBegin(scatter.get(), u, ul.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(scatter.get(), u, ul.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  PetscScalar* a = nullptr;
  check(VecGetArray(ul.get(), &a), "VecGetArray");
  Eigen::Map<Eigen::VectorXd> x(a, n);
  Eigen::VectorXd g = ops.G * x;
  if (normalized)
    for (Eigen::Index k = 0; k + 2 < g.size(); k += 3) {
      const double m = std::max({std::abs(g[k]), std::abs(g[k + 1]), std::abs(g[k + 2])});
      if (!(m > 0) || !std::isfinite(m)) {
        g[k] = g[k + 1] = g[k + 2] = 0.0;
        continue;
      }
      const double s0 = g[k] / m, s1 = g[k + 1] / m, s2 = g[k + 2] / m;
      const double norm = std::sqrt(s0 * s0 + s1 * s1 + s2 * s2);
      g[k] = -s0 / norm;
      g[k + 1] = -s1 / norm;
      g[k + 2] = -s2 / norm;
    }
  for (Eigen::Index k = 0; k < g.size(); ++k) g[k] *= -ops.fan_area[k / 3];  // D = -G^T W
  x = ops.G.transpose() * g;
  check(VecRestoreArray(ul.get(), &a), "VecRestoreArray");
  // The local sums into the owners' rows.
  check(VecSet(b, 0.0), "VecSet");
  check(VecScatterBegin(scatter.get(), ul.get(), b, ADD_VALUES, SCATTER_REVERSE), "VecScatterBegin");
  check(VecScatterEnd(scatter.get(), ul.get(), b, ADD_VALUES, SCATTER_REVERSE), "VecScatterEnd");
}

Eigen::VectorXd gather_to_root(Vec x, const Partition& part, double fill) {
  Handle<VecScatter> ctx;
  Handle<Vec> y;
  check(VecScatterCreateToZero(x, ctx.out(), y.out()), "VecScatterCreateToZero");
  check(VecScatterBegin(ctx.get(), x, y.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(ctx.get(), x, y.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  int rank = 0;
  MPI_Comm_rank(PetscObjectComm(PetscObject(x)), &rank);
  if (rank != 0) return {};
  Eigen::VectorXd out = Eigen::VectorXd::Constant(Eigen::Index(part.global_index.size()), fill);
  const PetscScalar* a = nullptr;
  check(VecGetArrayRead(y.get(), &a), "VecGetArrayRead");
  for (int gi = 0; gi < part.n_global(); ++gi) out[part.mesh_vertex[size_t(gi)]] = a[gi];
  check(VecRestoreArrayRead(y.get(), &a), "VecRestoreArrayRead");
  return out;
}

Eigen::SparseMatrix<double> gather_to_root(Mat A, const Partition& part) {
  MPI_Comm comm = PetscObjectComm(PetscObject(A));
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  PetscInt lo = 0, hi = 0;
  check(MatGetOwnershipRange(A, &lo, &hi), "MatGetOwnershipRange");
  std::vector<int> rows, cols;
  std::vector<double> vals;
  for (PetscInt r = lo; r < hi; ++r) {
    PetscInt n = 0;
    const PetscInt* c = nullptr;
    const PetscScalar* v = nullptr;
    check(MatGetRow(A, r, &n, &c, &v), "MatGetRow");
    for (PetscInt k = 0; k < n; ++k) {
      rows.push_back(int(r));
      cols.push_back(int(c[k]));
      vals.push_back(v[k]);
    }
    check(MatRestoreRow(A, r, &n, &c, &v), "MatRestoreRow");
  }
  int mine = int(rows.size());
  std::vector<int> counts(static_cast<size_t>(size)), displs(static_cast<size_t>(size) + 1, 0);
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  for (int r = 0; r < size; ++r) displs[size_t(r) + 1] = displs[size_t(r)] + counts[size_t(r)];
  const int total = rank == 0 ? displs[size_t(size)] : 0;
  std::vector<int> R(static_cast<size_t>(total)), C(static_cast<size_t>(total));
  std::vector<double> W(static_cast<size_t>(total));
  MPI_Gatherv(rows.data(), mine, MPI_INT, R.data(), counts.data(), displs.data(), MPI_INT, 0, comm);
  MPI_Gatherv(cols.data(), mine, MPI_INT, C.data(), counts.data(), displs.data(), MPI_INT, 0, comm);
  MPI_Gatherv(vals.data(), mine, MPI_DOUBLE, W.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, comm);
  if (rank != 0) return {};
  const int nv = int(part.global_index.size());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(total));
  for (int k = 0; k < total; ++k)
    t.emplace_back(part.mesh_vertex[size_t(R[size_t(k)])], part.mesh_vertex[size_t(C[size_t(k)])], W[size_t(k)]);
  Eigen::SparseMatrix<double> out(nv, nv);
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

std::vector<std::vector<double>> gather_per_rank(MPI_Comm comm, const std::vector<double>& values) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int n = int(values.size());
  std::vector<double> all(rank == 0 ? size_t(n) * size_t(size) : 0);
  MPI_Gather(values.data(), n, MPI_DOUBLE, all.data(), n, MPI_DOUBLE, 0, comm);
  std::vector<std::vector<double>> out;
  if (rank == 0)
    for (int r = 0; r < size; ++r) out.emplace_back(all.begin() + long(r) * n, all.begin() + long(r + 1) * n);
  return out;
}

}  // namespace polydec::petsc
