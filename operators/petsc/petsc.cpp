// operators/petsc/petsc.cpp — session, error agreement, partition, distributed assembly and the
// gathers of the PETSc engine (operators/petsc/petsc.h).
#include "polydec/operators/petsc/petsc.h"

#include <fmt/format.h>
#include <slepcsys.h>
#include <sys/resource.h>

#include <algorithm>
#include <limits>
#include <cstdint>
#include <numeric>
#include <stdexcept>

#include "polydec/dec/io.h"
#include "polydec/dec/union_find.h"
#include "polydec/operators/cholesky.h"
#include "polydec/operators/laplacians.h"
#include "polydec/operators/petsc/petsc_check.h"

namespace polydec::petsc {

void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw SolverError(fmt::format("PETSc: {} failed (error {}: {})", what, int(code), text ? text : "?"));
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
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
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

Partition partition_mesh(const Mesh& mesh, int n_ranks) {
  if (n_ranks < 1) throw std::invalid_argument("partition: at least one rank needed");
  const int nf = mesh.n_faces(), nv = mesh.n_vertices();
  if (nf < n_ranks)
    throw std::invalid_argument(fmt::format("partition: {} faces cannot be split over {} ranks", nf, n_ranks));
  const int* offsets = mesh.face_offsets().data();
  const int* indices = mesh.face_indices().data();
  const Eigen::MatrixX3d& X = mesh.positions();
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

DistributedOperators assemble_operators(MPI_Comm comm, const Mesh& mesh, const Partition& part, bool with_gradient) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (part.n_ranks != size)
    throw std::invalid_argument(
        fmt::format("assemble_operators: partition for {} ranks used on {}", part.n_ranks, size));
  DistributedOperators out;
  OperatorSet ops;
  std::vector<int> l2g;  // local vertex -> global index
  // The sub-mesh of this rank's faces, through the serial code: any failure is agreed first.
  agree(comm, [&] {
    const int* offsets = mesh.face_offsets().data();
    const int* indices = mesh.face_indices().data();
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
    soup.positions.resize(Eigen::Index(verts.size()), 3);
    l2g.resize(verts.size());
    for (size_t l = 0; l < verts.size(); ++l) {
      soup.positions.row(Eigen::Index(l)) = mesh.positions().row(verts[l]);
      l2g[l] = part.global_index[size_t(verts[l])];
    }
    Mesh sub(std::move(soup));
    // The global mesh's coordinate precision, in absolute terms (it is stored relative to a
    // mesh's size), so that every rank decides planarity as the serial code does.
    CoordinatePrecision precision = mesh.precision();
    const double radius = sub.rms_radius();
    precision.noise = radius > 0 ? std::min<double>(mesh.coordinate_noise() / radius, 0.5) : 0.0;
    sub = sub.with_precision(precision);
    ops = build_operators(sub, parse_laplacian("ours"), with_gradient);
    out.n_local_faces = sub.n_faces();
    out.n_local_vertices = sub.n_vertices();
  });
  const PetscInt n_own = part.vertex_begin[size_t(rank) + 1] - part.vertex_begin[size_t(rank)];
  const PetscInt N = part.n_global();
  std::vector<PetscInt> I, J;
  std::vector<PetscScalar> V;
  auto g = [&](int l) { return l2g[size_t(l)]; };
  coo_entries(ops.S, g, g, I, J, V);
  out.n_coo_entries = long(I.size());
  out.S = coo_matrix(comm, n_own, n_own, N, N, I, J, V);
  SparseMatrix().swap(ops.S);  // the local copies go as soon as PETSc holds the entries
  check(MatSetOption(out.S.get(), MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  coo_entries(ops.M, g, g, I, J, V);
  out.M = coo_matrix(comm, n_own, n_own, N, N, I, J, V);
  SparseMatrix().swap(ops.M);
  check(MatSetOption(out.M.get(), MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  check(VecCreateMPI(comm, n_own, N, out.M_lumped.out()), "VecCreateMPI");
  check(VecSet(out.M_lumped.get(), 0.0), "VecSet");
  {
    std::vector<PetscInt> rows(l2g.begin(), l2g.end());
    check(VecSetValues(out.M_lumped.get(), PetscInt(rows.size()), rows.data(), ops.M_lumped.data(), ADD_VALUES),
          "VecSetValues");
    check(VecAssemblyBegin(out.M_lumped.get()), "VecAssemblyBegin");
    check(VecAssemblyEnd(out.M_lumped.get()), "VecAssemblyEnd");
  }
  if (with_gradient) {
    // G's rows are this rank's fan triangles (3 each), numbered after the lower ranks'.
    long rows_local = long(ops.G.rows()), first = 0, total = 0;
    MPI_Exscan(&rows_local, &first, 1, MPI_LONG, MPI_SUM, comm);
    if (rank == 0) first = 0;
    MPI_Allreduce(&rows_local, &total, 1, MPI_LONG, MPI_SUM, comm);
    if (total > long(std::numeric_limits<PetscInt>::max()))
      throw SolverError("assemble_operators: the gradient has more rows than PetscInt indexes");
    auto t = [&](int r) { return PetscInt(first + r); };
    coo_entries(ops.G, t, g, I, J, V);
    out.G = coo_matrix(comm, PetscInt(rows_local), n_own, PetscInt(total), N, I, J, V);
    SparseMatrix().swap(ops.G);
    coo_entries(ops.D, g, t, I, J, V);
    out.D = coo_matrix(comm, n_own, PetscInt(rows_local), N, PetscInt(total), I, J, V);
  }
  int q[3] = {ops.quality.n_degenerate, ops.quality.n_inverted, ops.quality.n_faces_affected};
  MPI_Allreduce(MPI_IN_PLACE, q, 3, MPI_INT, MPI_SUM, comm);
  out.quality = {q[0], q[1], q[2]};
  return out;
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
