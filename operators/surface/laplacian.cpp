// operators/surface/laplacian.cpp — face-by-face assembly of S, M and lumped M into a precomputed
// pattern. Per face, the compact rank-structured local matrices (operators/surface/local_matrices.h)
// are computed without allocation and expanded column by column straight into the value
// arrays. With T threads, the faces are split into T patches (ranges of a breadth-first order);
// a vertex all of whose faces lie in one patch has its column summed by that patch's thread, the
// other vertices' columns (on the seams between patches) by a serial pass over their faces. Each entry is a
// sum over the faces around one vertex, taken in ascending face order either way, so results are bitwise
// identical to one thread.
#include "polydec/operators/surface/laplacian.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "polydec/dec/detail/element_pattern.h"
#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/detail/threads.h"
#include "polydec/operators/surface/local_matrices.h"

namespace polydec {

FacePattern face_pattern(const Mesh& mesh, int threads) {
  const int nf = mesh.n_faces();
  const int* offsets = mesh.face_offsets().data();
  const int* indices = mesh.face_indices().data();
  detail::ElementPattern ep = detail::element_pattern<detail::SlotKind::absolute>(
      mesh.n_vertices(), nf, [&](int f) { return mesh.face(f); });
  FacePattern fp;
  fp.pattern.swap(ep.pattern);
  fp.local_offsets = std::move(ep.offsets);
  fp.slots = std::move(ep.slots);
  // Breadth-first order over faces sharing a vertex, one component after another: contiguous
  // ranks form compact patches whatever the file's face order, so the threads' face sets share
  // few vertices (with file order, half of FINE SPHERE's faces touched a vertex of both halves).
  if (resolve_threads(threads) <= 1) return fp;
  fp.face_rank.assign(size_t(nf), -1);
  std::vector<int> queue;
  queue.reserve(size_t(nf));
  for (int seed = 0; seed < nf; ++seed) {
    if (fp.face_rank[size_t(seed)] >= 0) continue;
    fp.face_rank[size_t(seed)] = int(queue.size());
    queue.push_back(seed);
    for (size_t q = queue.size() - 1; q < queue.size(); ++q) {
      const int f = queue[q];
      for (int h = offsets[f]; h < offsets[f + 1]; ++h)
        for (int g : mesh.vertex_faces(indices[h]))
          if (fp.face_rank[size_t(g)] < 0) {
            fp.face_rank[size_t(g)] = int(queue.size());
            queue.push_back(g);
          }
    }
  }
  return fp;
}

namespace {

// Below this many halfedges per thread, threads cost more than they save.
constexpr int kHalfedgesPerThread = 8192;

// Calls f with std::integral_constant<int, n> for the common face sizes, else with 0 (any
// size), so that the per-face loops are unrolled for triangles, quads, pentagons and hexagons.
template <class F>
inline void with_size(int n, F&& f) {
  switch (n) {
    case 3:
      f(std::integral_constant<int, 3>{});
      break;
    case 4:
      f(std::integral_constant<int, 4>{});
      break;
    case 5:
      f(std::integral_constant<int, 5>{});
      break;
    case 6:
      f(std::integral_constant<int, 6>{});
      break;
    default:
      f(std::integral_constant<int, 0>{});
      break;
  }
}

// Where face f's local entries sit in the value arrays: entry (a, b) (row a, column b of its n x n
// local matrix) at index base(v_b) + slots[start(f) + a n + b], v_b the face's corner b. Absolute
// (Slot = int, FacePattern::slots): base 0; relative to the column's start (narrow Slot): base
// outer[v_b], the column's start in the pattern.
template <class Slot>
struct SlotTable {
  static constexpr bool relative = !std::is_same_v<Slot, int>;
  const Slot* slots;
  const long* offsets;  // |F| + 1 starts, or null when every face has `uniform` corners
  long uniform;         // uniform * uniform slots per face when offsets is null
  long start(int f) const { return offsets ? offsets[f] : f * uniform * uniform; }
};

template <class Slot>
struct Assembler {
  const Mesh& mesh;
  const Refinement& r;
  SlotTable<Slot> table;
  const int* face_rank;  // FacePattern::face_rank, or null: file order
  const int* outer;  // the pattern's column starts
  double* sv;        // stiffness values or null
  double* mv;        // mass values or null
  double* lv;        // lumped mass summed face by face (when M is not assembled; zeroed) or null
  const int* offsets = mesh.face_offsets().data();
  const int* indices = mesh.face_indices().data();

  // Compact local matrices of face f (N corners, 0: any) into cs, cm (3n doubles each; either
  // may be null).
  template <int N>
  void compact(int f, double* x, double* cs, double* cm) const {
    const int h0 = offsets[f], n = N > 0 ? N : offsets[f + 1] - h0;
    const Eigen::MatrixX3d& P = mesh.positions();
    for (int k = 0; k < n; ++k) {
      const int v = indices[h0 + k];
      x[3 * k] = P(v, 0);
      x[3 * k + 1] = P(v, 1);
      x[3 * k + 2] = P(v, 2);
    }
    const double xf[3] = {r.virtual_points(f, 0), r.virtual_points(f, 1), r.virtual_points(f, 2)};
    detail::polygon_compact<N>(x, n, r.weights.data() + h0, xf, r.fan.data() + h0, cs, cm);
  }

  // Adds face f's columns whose vertex v passes keep(v) to the value arrays, and their sums to
  // the lumped mass lv. col: n doubles, sums: n doubles.
  template <int N, class Keep>
  void scatter(int f, const double* cs, const double* cm, Keep keep, double* col, double* sums) const {
    const int h0 = offsets[f], n = N > 0 ? N : offsets[f + 1] - h0;
    const double* w = r.weights.data() + h0;
    const Slot* slot = table.slots + table.start(f);
    if (lv) detail::column_sums<N>(n, w, cm, sums);
    for (int b = 0; b < n; ++b) {
      const int v = indices[h0 + b];
      if (!keep(v)) continue;
      if (lv) lv[v] += sums[b];
      if (!sv && !mv) continue;
      const long base = SlotTable<Slot>::relative ? outer[v] : 0;
      if (sv) {
        detail::expand_column<N>(n, b, w, cs, col);
        double* s = sv + base;
        for (int a = 0; a < n; ++a) s[slot[a * n + b]] += col[a];
      }
      if (mv) {
        detail::expand_column<N>(n, b, w, cm, col);
        double* m = mv + base;
        for (int a = 0; a < n; ++a) m[slot[a * n + b]] += col[a];
      }
    }
  }

  // Lumped mass of the vertices in [lo, hi): column sums of M, in row order (M is bitwise
  // symmetric, so these equal its row sums).
  void lump(Eigen::VectorXd& lumped, int lo, int hi) const {
    for (int j = lo; j < hi; ++j) {
      double s = 0.0;
      for (int k = outer[j]; k < outer[j + 1]; ++k) s += mv[k];
      lumped[j] = s;
    }
  }

  // lumped: the lumped mass to take from M's column sums (mv), or null.
  void run_serial(Eigen::VectorXd* lumped) const {
    const int nmax = mesh.max_face_size(), nv = mesh.n_vertices();
    std::vector<double> buf(11 * size_t(nmax));
    double* x = buf.data();
    double* cs = x + 3 * nmax;
    double* cm = cs + 3 * nmax;
    double* col = cm + 3 * nmax;
    double* sums = col + nmax;
    double* want_s = sv ? cs : nullptr;
    double* want_m = mv || lv ? cm : nullptr;
    for (int f = 0; f < mesh.n_faces(); ++f)
      with_size(offsets[f + 1] - offsets[f], [&](auto N) {
        compact<decltype(N)::value>(f, x, want_s, want_m);
        scatter<decltype(N)::value>(
            f, cs, cm, [](int) { return true; }, col, sums);
      });
    if (lumped) lump(*lumped, 0, nv);
  }

  // lumped: as in run_serial.
  void run_parallel(int T, Eigen::VectorXd* lumped) const {
    const int nf = mesh.n_faces(), nv = mesh.n_vertices(), nmax = mesh.max_face_size();
    // Thread of face f: its breadth-first rank (FacePattern::face_rank) split into T equal ranges.
    auto thread_of = [&](int f) { return int(long(face_rank ? face_rank[f] : f) * T / nf); };
    // owner[v]: the thread holding every face around v, or kSeam.
    constexpr int kNone = -2, kSeam = -1;
    std::vector<int> owner(nv, kNone);
    for (int f = 0; f < nf; ++f) {
      const int t = thread_of(f);
      for (int h = offsets[f]; h < offsets[f + 1]; ++h) {
        int& o = owner[indices[h]];
        o = (o == kNone || o == t) ? t : kSeam;
      }
    }
    // Faces in ascending order: those of thread t (t >= 0), or those touching a seam vertex (t < 0).
    auto faces = [&](int t, auto keep) {
      std::vector<double> scratch(11 * size_t(nmax));
      double* x = scratch.data();
      double* cs = x + 3 * nmax;
      double* cm = cs + 3 * nmax;
      double* col = cm + 3 * nmax;
      double* sums = col + nmax;
      for (int f = 0; f < nf; ++f) {
        if (t >= 0 ? thread_of(f) != t
                   : std::none_of(indices + offsets[f], indices + offsets[f + 1],
                                  [&](int v) { return owner[v] == kSeam; }))
          continue;
        with_size(offsets[f + 1] - offsets[f], [&](auto N) {
          compact<decltype(N)::value>(f, x, sv ? cs : nullptr, mv || lv ? cm : nullptr);
          scatter<decltype(N)::value>(f, cs, cm, keep, col, sums);
        });
      }
    };
    run_on_threads(T, [&](int t) { faces(t, [&](int v) { return owner[v] == t; }); });
    faces(-1, [&](int v) { return owner[v] == kSeam; });
    if (lumped) {
      // Column ranges with about equal numbers of non-zeros.
      const long nnz = outer[nv];
      run_on_threads(T, [&](int t) {
        const auto [first, last] = part_of(nnz, t, T);
        const int lo = int(std::lower_bound(outer, outer + nv + 1, first) - outer);
        const int hi = t + 1 == T ? nv : int(std::lower_bound(outer, outer + nv + 1, last) - outer);
        lump(*lumped, lo, hi);
      });
    }
  }
};

int thread_count(const AssemblyOptions& options, const Mesh& mesh) {
  // Results do not depend on T.
  return std::max(1, std::min(resolve_threads(options.threads), mesh.n_halfedges() / kHalfedgesPerThread));
}

// Assembles the requested parts of L on the sparsity structure `structure` (a FacePattern's
// pattern, or a matrix of L that holds it) with the faces' slots in `table`. The lumped mass is
// M's column sums when M is assembled, else the sum over the faces around each vertex, in
// ascending face order, of the local mass matrices' row sums: no nnz-sized mass buffer.
template <class Slot>
void assemble_values(const Mesh& mesh, const Refinement& refinement, SlotTable<Slot> table, const int* face_rank,
                     const SparseMatrix& structure, LaplacianParts parts, Laplacian& L,
                     const AssemblyOptions& options) {
  const long nnz = structure.nonZeros();
  auto prepare = [&](SparseMatrix& A) {
    if (A.rows() != structure.rows() || A.nonZeros() != nnz || !A.isCompressed()) {
      A.resize(structure.rows(), structure.cols());
      A.resizeNonZeros(nnz);
      advise_huge_pages(A.innerIndexPtr(), sizeof(int) * nnz);
      advise_huge_pages(A.valuePtr(), sizeof(double) * nnz);
      std::copy(structure.outerIndexPtr(), structure.outerIndexPtr() + structure.outerSize() + 1,
                A.outerIndexPtr());
      std::copy(structure.innerIndexPtr(), structure.innerIndexPtr() + nnz, A.innerIndexPtr());
    }
    std::fill(A.valuePtr(), A.valuePtr() + nnz, 0.0);
  };
  L.quality = refinement.quality;
  if (!parts.stiffness && !parts.mass && !parts.lumped_mass) return;
  if (parts.stiffness) prepare(L.S);
  if (parts.mass) prepare(L.M);
  if (parts.lumped_mass) {
    L.M_lumped.resize(mesh.n_vertices());
    advise_huge_pages(L.M_lumped.data(), sizeof(double) * mesh.n_vertices());
    if (!parts.mass) L.M_lumped.setZero();
  }
  const Assembler<Slot> as{mesh,
                           refinement,
                           table,
                           face_rank,
                           structure.outerIndexPtr(),
                           parts.stiffness ? L.S.valuePtr() : nullptr,
                           parts.mass ? L.M.valuePtr() : nullptr,
                           parts.lumped_mass && !parts.mass ? L.M_lumped.data() : nullptr};
  Eigen::VectorXd* lumped = parts.lumped_mass && parts.mass ? &L.M_lumped : nullptr;
  const int T = thread_count(options, mesh);
  if (T == 1)
    as.run_serial(lumped);
  else
    as.run_parallel(T, lumped);
}

// Assembles into L with the slots of `fp` and the sparsity structure `structure` (fp.pattern,
// or a matrix that took over its storage).
void assemble_into(const Mesh& mesh, const Refinement& refinement, const FacePattern& fp,
                   const SparseMatrix& structure, LaplacianParts parts, Laplacian& L,
                   const AssemblyOptions& options) {
  if (long(refinement.weights.size()) != mesh.n_halfedges() ||
      refinement.virtual_points.rows() != mesh.n_faces())
    throw std::invalid_argument("assemble_laplacian: the refinement does not belong to this mesh");
  if (structure.rows() != mesh.n_vertices() || long(fp.local_offsets.size()) != mesh.n_faces() + 1)
    throw std::invalid_argument("assemble_laplacian: the face pattern does not belong to this mesh");
  assemble_values<int>(mesh, refinement, {fp.slots.data(), fp.local_offsets.data(), 0},
                       fp.face_rank.empty() ? nullptr : fp.face_rank.data(), structure, parts, L, options);
}

// An upper bound on the rows of any column of the pattern: 1 + sum over the faces around a
// vertex of their other corners.
long longest_column_bound(const Mesh& mesh) {
  int valence = 0;
  for (int v = 0; v < mesh.n_vertices(); ++v) valence = std::max(valence, int(mesh.vertex_faces(v).size()));
  return 1 + long(valence) * std::max(0, mesh.max_face_size() - 1);
}

// The pattern of a one-off assembly, built in A (column starts, rows ascending; values not
// written), and the faces' slots relative to their columns' starts, from the mesh's own faces
// around each vertex. Slot must hold the longest column's length. Cheaper in time and memory than
// face_pattern: no vertex-face lists of its own, slots of 1 or 2 bytes. Each column's rows are
// collected in first-seen order and ordered as element_pattern's ColumnOrder says: sorted in
// place and their slots written in the same pass when no face has more than 4 corners (columns of
// ~9 rows), else by one transposition of the whole pattern (hexagons: ~13 rows, which insertion
// sort handles slowly).
template <class Slot>
struct RelativePattern {
  std::unique_ptr<Slot[]> slots;
  std::vector<long> starts;  // |F| + 1 slot starts; empty when all faces have `uniform` corners
  long uniform = 0;
};

template <class Slot>
RelativePattern<Slot> relative_pattern(const Mesh& mesh, SparseMatrix& A) {
  const int nv = mesh.n_vertices(), nf = mesh.n_faces();
  const int* fo = mesh.face_offsets().data();
  const int* fi = mesh.face_indices().data();
  RelativePattern<Slot> rp;
  const int n0 = nf > 0 ? fo[1] - fo[0] : 0;
  bool uniform = true;
  for (int f = 0; f < nf && uniform; ++f) uniform = fo[f + 1] - fo[f] == n0;
  long bound = long(nf) * n0 * n0;  // sum of n_f^2: the number of slots, at least nnz
  if (uniform) {
    rp.uniform = n0;
  } else {
    rp.starts.resize(size_t(nf) + 1);
    rp.starts[0] = 0;
    for (int f = 0; f < nf; ++f) {
      const long n = fo[f + 1] - fo[f];
      rp.starts[size_t(f) + 1] = rp.starts[size_t(f)] + n * n;
    }
    bound = rp.starts[size_t(nf)];
  }
  const bool in_place = mesh.max_face_size() <= 4;
  rp.slots = uninitialized_on_huge_pages<Slot>(size_t(bound));  // every slot written below
  Slot* slots = rp.slots.get();
  std::vector<int> mark(size_t(nv), -1), outer(size_t(nv) + 1);
  const auto where = uninitialized_on_huge_pages<int>(size_t(nv));  // read only for rows of the column
  // Column v's rows in first-seen order appended at rows[nnz...].
  auto gather = [&](int v, int* rows, int& nnz) {
    for (const int f : mesh.vertex_faces(v))
      for (int h = fo[f]; h < fo[f + 1]; ++h) {
        const int u = fi[h];
        if (mark[size_t(u)] != v) {
          mark[size_t(u)] = v;
          rows[nnz++] = u;
        }
      }
  };
  // The slots of column v, whose sorted rows are rows[0..len).
  auto write_slots = [&](int v, const int* rows, int len) {
    for (int k = 0; k < len; ++k) where[size_t(rows[k])] = k;
    for (const int f : mesh.vertex_faces(v)) {
      const int h0 = fo[f], n = fo[f + 1] - h0;
      int b = 0;
      while (fi[h0 + b] != v) ++b;
      Slot* s = slots + (uniform ? long(f) * n0 * n0 : rp.starts[size_t(f)]) + b;
      for (int a = 0; a < n; ++a) s[long(a) * n] = Slot(where[size_t(fi[h0 + a])]);
    }
  };
  int nnz = 0;
  outer[0] = 0;
  if (in_place) {
    A.resize(nv, nv);
    A.resizeNonZeros(bound);  // trimmed to nnz below, within the capacity (pages past nnz never touched)
    advise_huge_pages(A.innerIndexPtr(), sizeof(int) * size_t(bound));
    advise_huge_pages(A.valuePtr(), sizeof(double) * size_t(bound));
    int* rows = A.innerIndexPtr();
    for (int v = 0; v < nv; ++v) {
      const int col = nnz;
      gather(v, rows, nnz);
      detail::element_pattern_impl::sort_column(rows + col, rows + nnz);
      write_slots(v, rows + col, nnz - col);
      outer[size_t(v) + 1] = nnz;
    }
    A.data().resize(nnz);  // within the capacity: no copy
  } else {
    const auto unsorted = uninitialized_on_huge_pages<int>(size_t(bound));  // the first nnz written
    for (int v = 0; v < nv; ++v) {
      gather(v, unsorted.get(), nnz);
      outer[size_t(v) + 1] = nnz;
    }
    A.resize(nv, nv);
    A.resizeNonZeros(nnz);
    advise_huge_pages(A.innerIndexPtr(), sizeof(int) * size_t(nnz));
    advise_huge_pages(A.valuePtr(), sizeof(double) * size_t(nnz));
    // The pattern is symmetric: appending v to column u for each row u of column v, columns v in
    // order, leaves every column's rows ascending.
    int* rows = A.innerIndexPtr();
    std::vector<int> next(outer.begin(), outer.end() - 1);
    for (int v = 0; v < nv; ++v)
      for (int k = outer[size_t(v)]; k < outer[size_t(v) + 1]; ++k) rows[next[size_t(unsorted[k])]++] = v;
    for (int v = 0; v < nv; ++v) write_slots(v, rows + outer[size_t(v)], outer[size_t(v) + 1] - outer[size_t(v)]);
  }
  std::copy(outer.begin(), outer.end(), A.outerIndexPtr());
  return rp;
}

// A one-off assembly of S or M (and the other parts asked for) with slots of type Slot
// (relative_pattern), the pattern built in S (or M).
template <class Slot>
void assemble_fresh(const Mesh& mesh, const Refinement& refinement, LaplacianParts parts, Laplacian& L,
                    const AssemblyOptions& options) {
  SparseMatrix& A = parts.stiffness ? L.S : L.M;
  const RelativePattern<Slot> rp = relative_pattern<Slot>(mesh, A);
  assemble_values<Slot>(mesh, refinement, {rp.slots.get(), rp.starts.empty() ? nullptr : rp.starts.data(), rp.uniform},
                        nullptr, A, parts, L, options);
}

}  // namespace

void reassemble_laplacian(const Mesh& mesh, const Refinement& refinement, const FacePattern& pattern,
                          LaplacianParts parts, Laplacian& L, const AssemblyOptions& options) {
  check_refinement(mesh, refinement, "reassemble_laplacian");
  assemble_into(mesh, refinement, pattern, pattern.pattern, parts, L, options);
}

Laplacian assemble_laplacian(const Mesh& mesh, const Refinement& refinement, LaplacianParts parts,
                             const FacePattern* pattern, const AssemblyOptions& options) {
  check_refinement(mesh, refinement, "assemble_laplacian");
  Laplacian L;
  if (pattern) {
    reassemble_laplacian(mesh, refinement, *pattern, parts, L, options);
    return L;
  }
  if (long(refinement.weights.size()) != mesh.n_halfedges() || refinement.virtual_points.rows() != mesh.n_faces())
    throw std::invalid_argument("assemble_laplacian: the refinement does not belong to this mesh");
  if (!parts.stiffness && !parts.mass) {
    // The lumped mass alone is summed face by face: no pattern (`none` is never read).
    const SparseMatrix none;
    assemble_values<int>(mesh, refinement, {nullptr, nullptr, 0}, nullptr, none, parts, L, options);
    return L;
  }
  // The threads split the faces in file order: the breadth-first patches (face_pattern(mesh, T))
  // cost more than they save in a one-off assembly (~0.3 s serial on 1.5M quads); they pay off
  // when the pattern is kept for re-assembly.
  const long longest = longest_column_bound(mesh);
  if (longest <= 255) {
    assemble_fresh<std::uint8_t>(mesh, refinement, parts, L, options);
  } else if (longest <= 65535) {
    assemble_fresh<std::uint16_t>(mesh, refinement, parts, L, options);
  } else {
    FacePattern own = face_pattern(mesh);
    // The pattern's storage becomes S's (or M's) instead of being copied (swap: Eigen 3.4's
    // SparseMatrix has no move assignment, std::move would copy).
    SparseMatrix& host = parts.stiffness ? L.S : L.M;
    host.swap(own.pattern);
    assemble_into(mesh, refinement, own, host, parts, L, options);
  }
  return L;
}

SparseMatrix stiffness(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "stiffness");
  return assemble_laplacian(mesh, refinement, {true, false, false}).S;
}

SparseMatrix mass(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "mass");
  return assemble_laplacian(mesh, refinement, {false, true, false}).M;
}

Eigen::VectorXd lumped_mass(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "lumped_mass");
  return assemble_laplacian(mesh, refinement, {false, false, true}).M_lumped;
}

}  // namespace polydec
