// operators/solvers/cholesky.cpp — SparseCholesky on CHOLMOD (supernodal) or Eigen's SimplicialLDLT.
#include "polydec/operators/solvers/cholesky.h"

#include <dlfcn.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/detail/simd.h"

#ifdef POLYDEC_HAVE_CHOLMOD
#include <cholmod.h>
#endif

namespace polydec {

namespace {

using SpMat = Eigen::SparseMatrix<double>;

void check_eigen(const Eigen::SimplicialLDLT<SpMat>& s, const std::string& name) {
  if (s.info() != Eigen::Success)
    throw SolverError("Cholesky factorization of " + name + " failed (matrix not positive definite?)");
  // A singular positive semi-definite matrix leaves a rounding-level last pivot of either sign:
  // pivots at most kSingularPivot times the largest count as zero.
  constexpr double kSingularPivot = 1e-12;
  const Eigen::VectorXd d = s.vectorD();
  if (d.size() > 0 && (!d.allFinite() || !(d.minCoeff() > kSingularPivot * d.cwiseAbs().maxCoeff())))
    throw SolverError("Cholesky factorization of " + name + " failed: matrix is singular or not positive definite");
}

// FNV-1a over the rows and column starts of A's lower triangle: matrices with the same
// fingerprint have the same pattern for the factorization (up to a 2^-64 chance).
std::uint64_t lower_pattern_hash(const SpMat& A) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&](std::uint64_t x) {
    h ^= x;
    h *= 1099511628211ull;
  };
  mix(std::uint64_t(A.rows()));
  for (int j = 0; j < int(A.cols()); ++j) {
    mix(std::uint64_t(j) << 32);
    for (SpMat::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j) mix(std::uint64_t(it.row()));
  }
  return h;
}

#ifdef POLYDEC_HAVE_CHOLMOD
// A read-only CHOLMOD view of a compressed column-major matrix; stype -1: only the lower
// triangle is used.
cholmod_sparse view_lower(const SpMat& A) {
  cholmod_sparse s{};
  s.nrow = size_t(A.rows());
  s.ncol = size_t(A.cols());
  s.nzmax = size_t(A.nonZeros());
  s.p = const_cast<int*>(A.outerIndexPtr());
  s.i = const_cast<int*>(A.innerIndexPtr());
  s.x = const_cast<double*>(A.valuePtr());
  s.stype = -1;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

// Solves through CHOLMOD's supernodal LL^T factor with our own loops, supernode by supernode: the
// diagonal block's triangular solve and one update with the rows below (gathered or scattered
// once per row). cholmod_solve2 makes two BLAS calls per supernode on the many small supernodes of
// a surface mesh's factor: one FINE SPHERE solve took ~10 ms, ~4 ms with these loops
// (docs/benchmarks.md). A supernode's nsrow x nscol block is
// column-major at px, its diagonal block on top, the rows below listed in s; `work` holds at least
// twice the largest supernode's row count.
struct SupernodalView {
  const int *super, *pi, *px, *s;
  const double* x;
  const double* inv;  // 1 / L_jj, in the factor's column order
  int n_super;
  SupernodalView(const cholmod_factor& L, const std::vector<double>& inverse_diagonal)
      : super(static_cast<const int*>(L.super)), pi(static_cast<const int*>(L.pi)),
        px(static_cast<const int*>(L.px)), s(static_cast<const int*>(L.s)), x(static_cast<const double*>(L.x)),
        inv(inverse_diagonal.data()), n_super(int(L.nsuper)) {}
};

// The kernels below are plain loops that GCC vectorizes, compiled for AVX2 with FMA and for the
// SSE2 baseline (dec/detail/simd.h). They multiply by the reciprocals of L's diagonal (kept per
// factorization) instead of dividing: a division sits on each column's dependency chain.

// x[0..n) . y[0..n) with eight partial sums (GCC does not reorder a floating-point sum by itself;
// these let it vectorize and keep two AVX2 accumulators in flight).
[[gnu::always_inline]] inline double dot(const double* __restrict x, const double* __restrict y, int n) {
  double a[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  int i = 0;
  for (; i + 8 <= n; i += 8)
    for (int l = 0; l < 8; ++l) a[l] += x[i + l] * y[i + l];
  for (; i < n; ++i) a[0] += x[i] * y[i];
  return ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7]));
}

// L y = y for supernode k (forward elimination), in `work` (the supernode's rows: its own columns,
// then the rows below): four columns at a time, their four values solved in the diagonal block
// and then one update of the rows below them with all four (each row of `work` read and written
// once per four columns instead of once per column), then the rows below scattered back once.
[[gnu::always_inline]] inline void forward_supernode(const SupernodalView& L, int k, double* y, double* work) {
  const int k1 = L.super[k], n_col = L.super[k + 1] - k1, n_row = L.pi[k + 1] - L.pi[k];
  const double* block = L.x + L.px[k];
  const double* inv = L.inv + k1;
  double* __restrict t = work;
  for (int i = 0; i < n_col; ++i) t[i] = y[k1 + i];
  for (int i = n_col; i < n_row; ++i) t[i] = 0.0;
  int j = 0;
  for (; j + 4 <= n_col; j += 4) {
    const double* __restrict c0 = block + size_t(j) * size_t(n_row);
    const double* __restrict c1 = c0 + n_row;
    const double* __restrict c2 = c1 + n_row;
    const double* __restrict c3 = c2 + n_row;
    const double y0 = t[j] * inv[j];
    const double y1 = (t[j + 1] - c0[j + 1] * y0) * inv[j + 1];
    const double y2 = (t[j + 2] - c0[j + 2] * y0 - c1[j + 2] * y1) * inv[j + 2];
    const double y3 = (t[j + 3] - c0[j + 3] * y0 - c1[j + 3] * y1 - c2[j + 3] * y2) * inv[j + 3];
    t[j] = y0, t[j + 1] = y1, t[j + 2] = y2, t[j + 3] = y3;
    for (int i = j + 4; i < n_row; ++i) t[i] -= (c0[i] * y0 + c1[i] * y1) + (c2[i] * y2 + c3[i] * y3);
  }
  for (; j < n_col; ++j) {
    const double* __restrict c = block + size_t(j) * size_t(n_row);
    const double yj = t[j] * inv[j];
    t[j] = yj;
    for (int i = j + 1; i < n_row; ++i) t[i] -= c[i] * yj;
  }
  for (int i = 0; i < n_col; ++i) y[k1 + i] = t[i];
  const int* r = L.s + L.pi[k];
  for (int i = n_col; i < n_row; ++i) y[r[i]] += t[i];
}

// L^T z = z for supernode k (backward substitution; the supernodes after k are done), in `work`
// (its own columns, the rows below gathered, then one sum per column). First the rows below,
// column after column in storage order (the factor streams forward, as the hardware prefetches
// it), then the diagonal block from its last column back; in each column's dot product the
// newest value (its right neighbour) is added last, so that the rest of the sum does not wait.
[[gnu::always_inline]] inline void backward_supernode(const SupernodalView& L, int k, double* z, double* work) {
  const int k1 = L.super[k], n_col = L.super[k + 1] - k1, n_row = L.pi[k + 1] - L.pi[k], nb = n_row - n_col;
  const double* block = L.x + L.px[k];
  const double* inv = L.inv + k1;
  const int* r = L.s + L.pi[k];
  double* __restrict t = work;
  double* __restrict below = work + n_row;
  for (int i = 0; i < n_col; ++i) t[i] = z[k1 + i];
  for (int i = n_col; i < n_row; ++i) t[i] = z[r[i]];
  for (int j = 0; j < n_col; ++j) below[j] = dot(block + size_t(j) * size_t(n_row) + n_col, t + n_col, nb);
  for (int j = n_col - 1; j >= 0; --j) {
    const double* __restrict c = block + size_t(j) * size_t(n_row);
    double acc = below[j] + (j + 2 < n_col ? dot(c + j + 2, t + j + 2, n_col - j - 2) : 0.0);
    if (j + 1 < n_col) acc += c[j + 1] * t[j + 1];
    t[j] = (t[j] - acc) * inv[j];
  }
  for (int i = 0; i < n_col; ++i) z[k1 + i] = t[i];
}

// One-column passes: forward over the supernodes `list` names (all n_super when null), backward
// over all. The forward pass prefetches the factor's values kForwardPrefetchBytes beyond the
// supernode at hand: with the four-column update 1-11% less time per pass on a 1.5M-quad sphere,
// each of the two alone slower (docs/benchmarks.md).
constexpr long kForwardPrefetchBytes = 16384;
[[gnu::always_inline]] inline void forward_pass_body(const SupernodalView& L, const int* list, int count, double* y,
                                                     double* work) {
  const char* base = reinterpret_cast<const char*>(L.x);
  const char* end = base + sizeof(double) * size_t(L.px[L.n_super]);
  const char* next = base;  // the lowest address not yet prefetched
  for (int q = 0; q < count; ++q) {
    const int k = list ? list[q] : q;
    const char* start = base + sizeof(double) * size_t(L.px[k]);
    const char* ahead = std::min(end, base + sizeof(double) * size_t(L.px[k + 1]) + kForwardPrefetchBytes);
    if (next < start) next = start;
    for (; next < ahead; next += 64) __builtin_prefetch(next);
    forward_supernode(L, k, y, work);
  }
}
// The backward pass visits the supernodes last to first, so the factor's values go by in
// descending blocks that the hardware prefetcher does not follow: they are prefetched
// kPrefetchBytes ahead.
constexpr long kPrefetchBytes = 16384;
[[gnu::always_inline]] inline void backward_pass_body(const SupernodalView& L, int n_super, double* z, double* work) {
  const char* base = reinterpret_cast<const char*>(L.x);
  const char* next = base + sizeof(double) * size_t(n_super > 0 ? L.px[n_super] : 0);  // lowest address prefetched
  for (int k = n_super - 1; k >= 0; --k) {
    const char* ahead = base + sizeof(double) * size_t(L.px[k]) - kPrefetchBytes;
    for (; next > ahead && next > base; next -= 64) __builtin_prefetch(next - 64);
    backward_supernode(L, k, z, work);
  }
}
POLYDEC_SIMD_VARIANTS(forward_pass, (const SupernodalView& L, const int* list, int count, double* y, double* work),
                      (L, list, count, y, work), forward_pass_body)
POLYDEC_SIMD_VARIANTS(backward_pass, (const SupernodalView& L, int n_super, double* z, double* work),
                      (L, n_super, z, work), backward_pass_body)

// The same for m right-hand sides stored row by row (row v's m values at W + v m). Everything is
// one kernel, dst -= sum_t coef[t cs] src(t) over rows of m values (update_row): each output row
// is held in eight vector registers, 32 values at a time (64 with AVX-512, the registers' width
// `Bytes`), while the count source rows stream past, instead of being loaded and stored once per
// factor entry. With AVX-512 a 64-column block's row is one pass: each coefficient is read once
// and each source row in one go (FINE SPHERE, 64 sources: ~15% less time per call,
// docs/benchmarks.md).
template <int Bytes>
struct LanesOf {  // Bytes / 8 doubles, any address
  typedef double type __attribute__((vector_size(Bytes), aligned(8), may_alias));
};
using Lanes = LanesOf<32>::type;

// For R output rows at once (R = 1, 2): dst[r][q, q + 8 Bytes / 8) -= sum_t coef[r][t cs]
// src(t)[...] for every whole run of 8 registers of `Bytes`, from q on; returns where it stopped.
// The R rows' 8 R registers are held while the source rows stream past, each source vector loaded
// once for all R rows; each output value gets the same operations in the same order for any R.
template <int Bytes, int R, class Src>
[[gnu::always_inline]] inline int update_runs(double* const* dst, int q, int m, const double* const* coef, size_t cs,
                                              Src src, int count) {
  using V = typename LanesOf<Bytes>::type;
  constexpr int run = Bytes;  // 8 registers of Bytes / 8 doubles
  for (; q + run <= m; q += run) {
    V a[R][8];
#pragma GCC unroll 16
    for (int r = 0; r < R; ++r)
#pragma GCC unroll 8
      for (int i = 0; i < 8; ++i) a[r][i] = reinterpret_cast<const V*>(dst[r] + q)[i];
    for (int t = 0; t < count; ++t) {
      double l[R];
#pragma GCC unroll 2
      for (int r = 0; r < R; ++r) l[r] = coef[r][size_t(t) * cs];
      const V* x = reinterpret_cast<const V*>(src(t) + q);
#pragma GCC unroll 8
      for (int i = 0; i < 8; ++i) {
        const V y = x[i];
#pragma GCC unroll 2
        for (int r = 0; r < R; ++r) a[r][i] -= l[r] * y;
      }
    }
#pragma GCC unroll 16
    for (int r = 0; r < R; ++r)
#pragma GCC unroll 8
      for (int i = 0; i < 8; ++i) reinterpret_cast<V*>(dst[r] + q)[i] = a[r][i];
  }
  return q;
}

// update_row from column q on.
template <int Bytes, class Src>
[[gnu::always_inline]] inline void update_row_from(double* __restrict dst, int q, int m, const double* __restrict coef,
                                                   size_t cs, Src src, int count) {
  double* const rows[1] = {dst};
  const double* const coefs[1] = {coef};
  q = update_runs<Bytes, 1>(rows, q, m, coefs, cs, src, count);
  if constexpr (Bytes > 32) q = update_runs<32, 1>(rows, q, m, coefs, cs, src, count);
  for (; q + 4 <= m; q += 4) {
    Lanes* d = reinterpret_cast<Lanes*>(dst + q);
    Lanes a = *d;
    for (int t = 0; t < count; ++t) a -= coef[size_t(t) * cs] * *reinterpret_cast<const Lanes*>(src(t) + q);
    *d = a;
  }
  for (; q < m; ++q) {
    double a = dst[q];
    for (int t = 0; t < count; ++t) a -= coef[size_t(t) * cs] * src(t)[q];
    dst[q] = a;
  }
}

template <int Bytes, class Src>
[[gnu::always_inline]] inline void update_row(double* __restrict dst, int m, const double* __restrict coef, size_t cs,
                                              Src src, int count) {
  update_row_from<Bytes>(dst, 0, m, coef, cs, src, count);
}

// update_row for two output rows with their own coefficients and the same source rows. With
// AVX-512 (32 registers) both rows' 64 values are held at once, so each source vector is loaded
// once for both; the same operations in the same order as two update_row calls (the same bits).
template <int Bytes, class Src>
[[gnu::always_inline]] inline void update_row_pair(double* __restrict dst0, double* __restrict dst1, int m,
                                                   const double* __restrict coef0, const double* __restrict coef1,
                                                   size_t cs, Src src, int count) {
  int q = 0;
  if constexpr (Bytes == 64) {
    double* const dst[2] = {dst0, dst1};
    const double* const coef[2] = {coef0, coef1};
    q = update_runs<64, 2>(dst, 0, m, coef, cs, src, count);
  }
  update_row_from<Bytes>(dst0, q, m, coef0, cs, src, count);
  update_row_from<Bytes>(dst1, q, m, coef1, cs, src, count);
}

[[gnu::always_inline]] inline void scale_row(double* __restrict x, int m, double d) {
  for (int q = 0; q < m; ++q) x[q] *= d;
}

// L Y = Y for supernode k: its rows in order (row i less the earlier ones, times 1 / L_ii), then
// each row below less the supernode's rows.
template <int Bytes>
[[gnu::always_inline]] inline void forward_supernode_rows(const SupernodalView& L, int k, double* W, int m) {
  const int k1 = L.super[k], n_col = L.super[k + 1] - k1, n_row = L.pi[k + 1] - L.pi[k];
  const double* block = L.x + L.px[k];
  const int* r = L.s + L.pi[k];
  double* Y = W + size_t(k1) * m;
  auto own = [&](int t) { return Y + size_t(t) * m; };
  for (int i = 0; i < n_col; ++i) {
    update_row<Bytes>(Y + size_t(i) * m, m, block + i, size_t(n_row), own, i);
    scale_row(Y + size_t(i) * m, m, L.inv[k1 + i]);
  }
  int i = n_col;
  for (; i + 1 < n_row; i += 2)
    update_row_pair<Bytes>(W + size_t(r[i]) * m, W + size_t(r[i + 1]) * m, m, block + i, block + i + 1, size_t(n_row),
                           own, n_col);
  if (i < n_row) update_row<Bytes>(W + size_t(r[i]) * m, m, block + i, size_t(n_row), own, n_col);
}

// L^T Z = Z for supernode k: each of its rows less the rows below, then its rows from the last
// (row j less the later ones, times 1 / L_jj).
template <int Bytes>
[[gnu::always_inline]] inline void backward_supernode_rows(const SupernodalView& L, int k, double* W, int m) {
  const int k1 = L.super[k], n_col = L.super[k + 1] - k1, n_row = L.pi[k + 1] - L.pi[k];
  const double* block = L.x + L.px[k];
  const int* r = L.s + L.pi[k] + n_col;
  double* Z = W + size_t(k1) * m;
  auto below = [&](int t) { return W + size_t(r[t]) * m; };
  auto own = [&](int t) { return Z + size_t(t) * m; };
  int j = 0;
  for (; j + 1 < n_col; j += 2)
    update_row_pair<Bytes>(Z + size_t(j) * m, Z + size_t(j + 1) * m, m, block + size_t(j) * n_row + n_col,
                           block + size_t(j + 1) * n_row + n_col, 1, below, n_row - n_col);
  if (j < n_col) update_row<Bytes>(Z + size_t(j) * m, m, block + size_t(j) * n_row + n_col, 1, below, n_row - n_col);
  for (int j = n_col - 1; j >= 0; --j) {
    const double* c = block + size_t(j) * n_row;
    update_row<Bytes>(Z + size_t(j) * m, m, c + j + 1, 1, [&](int t) { return own(j + 1 + t); }, n_col - j - 1);
    scale_row(Z + size_t(j) * m, m, L.inv[k1 + j]);
  }
}

// Forward over the supernodes `list` names (all n_super when null), backward over all.
template <int Bytes>
[[gnu::always_inline]] inline void rows_solve_body(const SupernodalView& L, const int* list, int count, int n_super,
                                                   double* W, int m) {
  for (int q = 0; q < count; ++q) forward_supernode_rows<Bytes>(L, list ? list[q] : q, W, m);
  for (int k = n_super - 1; k >= 0; --k) backward_supernode_rows<Bytes>(L, k, W, m);
}
POLYDEC_SIMD_WIDE_VARIANTS(rows_solve,
                           (const SupernodalView& L, const int* list, int count, int n_super, double* W, int m),
                           (L, list, count, n_super, W, m), rows_solve_body)

// CHOLMOD allocates its factors, solutions and workspaces through SuiteSparse_config. With
// glibc's malloc and calloc there, blocks of 2 MB and more are advised onto transparent huge pages
// before their first write (dec/detail/huge_pages.h): a FINE SPHERE factor (42 MB) otherwise
// costs ~10 000 page faults of ~13 us here (docs/benchmarks.md), and the solves that stream it
// miss the TLB on 4 KB pages. Installed once, and only over
// glibc's own functions: a program that set its own allocator for SuiteSparse keeps it. The
// blocks are plain malloc/calloc blocks, so CHOLMOD's free (free) stays right for them.
void* malloc_on_huge_pages(size_t bytes) {
  void* p = std::malloc(bytes);
  if (p) advise_huge_pages(p, bytes);
  return p;
}
void* calloc_on_huge_pages(size_t count, size_t size) {
  // glibc's calloc takes large blocks fresh from the kernel, already zero and not yet touched.
  void* p = std::calloc(count, size);
  if (p && size != 0 && count <= std::numeric_limits<size_t>::max() / size) advise_huge_pages(p, count * size);
  return p;
}
// CHOLMOD 3 copies into its large supernodes on up to 4 OpenMP threads. With the BLAS policy at
// one thread (blas_threads()) those loops stay on the calling thread too: for the duration of a
// call, this thread's OpenMP max-active-levels is 0 (libgomp keeps it per thread, so other
// threads' OpenMP is untouched), restored afterwards. On a loaded 2-core machine the team of 4
// costs more than it saves (FINE SPHERE heat-method precomputation, medians of twelve
// constructions: ~1.26 -> ~1.07 s wall, docs/benchmarks.md). Nothing happens when CHOLMOD was built without OpenMP.
class CholmodOpenMPScope {
 public:
  CholmodOpenMPScope() {
    using Get = int (*)();
    using Set = void (*)(int);
    static const auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
    static const auto set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
    const BlasThreads b = blas_threads();
    if (!get || !set || !(b.threads == 1 || (b.threads < 0 && b.requested == 1))) return;
    set_ = set;
    saved_ = get();
    set_(0);
  }
  ~CholmodOpenMPScope() {
    if (set_) set_(saved_);
  }
  CholmodOpenMPScope(const CholmodOpenMPScope&) = delete;
  CholmodOpenMPScope& operator=(const CholmodOpenMPScope&) = delete;

 private:
  void (*set_)(int) = nullptr;
  int saved_ = 0;
};

void advise_cholmod_allocations() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (SuiteSparse_config.malloc_func == &std::malloc) SuiteSparse_config.malloc_func = &malloc_on_huge_pages;
    if (SuiteSparse_config.calloc_func == &std::calloc) SuiteSparse_config.calloc_func = &calloc_on_huge_pages;
  });
}
#endif

}  // namespace

struct SparseCholesky::Impl {
  bool use_cholmod = false;
  std::string ordering = "amd";
  double lnz = 0;              // non-zeros of L from the analysis
  std::uint64_t pattern = 0;   // lower_pattern_hash of the analysed matrix
  Eigen::SimplicialLDLT<SpMat> ldlt;
#ifdef POLYDEC_HAVE_CHOLMOD
  mutable cholmod_common c{};
  cholmod_factor* L = nullptr;
  // Solution and workspace of cholmod_solve2, kept between solves: allocating them per solve
  // (cholmod_solve) made one FINE SPHERE solve 17 instead of 14.5 ms (fresh pages each time). One
  // set for single columns and one for blocks, so that alternating the two does not reallocate
  // (CHOLMOD reallocates when the column count changes: 2 x 49 MB for 64 columns on FINE SPHERE).
  mutable cholmod_dense* X = nullptr;
  mutable cholmod_dense* Y = nullptr;
  mutable cholmod_dense* E = nullptr;
  mutable cholmod_dense* Xb = nullptr;
  mutable cholmod_dense* Yb = nullptr;
  mutable cholmod_dense* Eb = nullptr;
  // solve_sparse: the supernode of each column and the parent of each supernode (L's structure,
  // fixed by the analysis; made on the first call), the inverse permutation and the supernodes
  // of the current reach with their marks.
  mutable std::vector<int> super_of, super_parent, iperm, reach, mark;
  mutable int mark_now = 0;
  // One-column solves (forward_supernode, backward_supernode): the permuted vector and the
  // gather/scatter scratch of the largest supernode, made on the first call.
  mutable std::vector<double> w, work;
  // The reciprocals of L's diagonal in its column order, for the own solves; set by each
  // factorization.
  std::vector<double> inverse_diagonal;
  void set_inverse_diagonal() {
    inverse_diagonal.clear();
    if (!own_solve()) return;
    inverse_diagonal.resize(L->n);
    const int* super = static_cast<const int*>(L->super);
    const int* pi = static_cast<const int*>(L->pi);
    const int* px = static_cast<const int*>(L->px);
    const double* x = static_cast<const double*>(L->x);
    for (size_t k = 0; k < L->nsuper; ++k) {
      const int n_row = pi[k + 1] - pi[k];
      for (int j = 0; j < super[k + 1] - super[k]; ++j)
        inverse_diagonal[size_t(super[k] + j)] = 1.0 / x[px[k] + size_t(j) * size_t(n_row) + size_t(j)];
    }
  }
  // solve_rows: the permuted rows, on huge pages, kept for the next call of the same size.
  mutable std::unique_ptr<double[]> rows_block;
  mutable size_t rows_block_size = 0;
  bool own_solve() const { return L && L->is_super && L->is_ll && L->xtype == CHOLMOD_REAL; }
  void make_solve_buffers() const {
    if (!work.empty()) return;
    int widest = 1;
    const int* pi = static_cast<const int*>(L->pi);
    for (size_t k = 0; k < L->nsuper; ++k) widest = std::max(widest, pi[k + 1] - pi[k]);
    work.assign(2 * size_t(widest), 0.0);
    w.assign(L->n, 0.0);
  }
  // L y = w over the supernodes `forward` lists (all when null), L^T z = y over all of them, in
  // place in the permuted w; then x = P^T z.
  void supernodal_solve(const std::vector<int>* forward, double* x) const {
    const SupernodalView V(*L, inverse_diagonal);
    const int n_super = int(L->nsuper);
    forward_pass(V, forward ? forward->data() : nullptr, forward ? int(forward->size()) : n_super, w.data(),
                 work.data());
    backward_pass(V, n_super, w.data(), work.data());
    const int* perm = static_cast<const int*>(L->Perm);
    for (size_t k = 0; k < L->n; ++k) x[perm ? perm[k] : int(k)] = w[k];
  }
  // The supernodal elimination tree and the inverse permutation, made on the first call: a
  // supernode's parent holds the first row below its diagonal block; parents come after their
  // children.
  void make_tree() const {
    if (!super_of.empty()) return;
    const int n = int(L->n), n_super = int(L->nsuper);
    const int* super = static_cast<const int*>(L->super);
    const int* pi = static_cast<const int*>(L->pi);
    const int* s = static_cast<const int*>(L->s);
    const int* perm = static_cast<const int*>(L->Perm);
    super_of.resize(size_t(n));
    for (int k = 0; k < n_super; ++k) std::fill(super_of.begin() + super[k], super_of.begin() + super[k + 1], k);
    super_parent.assign(size_t(n_super), -1);
    for (int k = 0; k < n_super; ++k) {
      const int n_col = super[k + 1] - super[k];
      if (pi[k + 1] - pi[k] > n_col) super_parent[size_t(k)] = super_of[size_t(s[pi[k] + n_col])];
    }
    iperm.resize(size_t(n));
    for (int k = 0; k < n; ++k) iperm[size_t(perm ? perm[k] : k)] = k;
    mark.assign(size_t(n_super), 0);
  }
  // A fresh value of mark_now: the supernodes marked with it are those of the current call.
  void new_mark() const {
    if (++mark_now == std::numeric_limits<int>::max()) {
      std::fill(mark.begin(), mark.end(), 0);
      mark_now = 1;
    }
  }
  // The supernodes from those of the factor rows `rows` (in the factor's order) up to the root,
  // in elimination order, into `reach` (after make_tree).
  void find_reach(std::span<const int> rows) const {
    new_mark();
    reach.clear();
    for (const int p : rows)
      for (int j = super_of[size_t(p)]; j >= 0 && mark[size_t(j)] != mark_now; j = super_parent[size_t(j)]) {
        mark[size_t(j)] = mark_now;
        reach.push_back(j);
      }
    std::sort(reach.begin(), reach.end());
  }
  // The supernodes the forward solve of the permuted w changes, into `reach` in elimination order
  // (after make_tree; with find_reach's marks): those with a non-zero in their rows of w or below
  // them in the tree. The others stay zero, so skipping them gives the same solution: the
  // right-hand side of the Poisson step of heat geodesics is zero wherever the heat step
  // underflowed to zero (docs/benchmarks.md).
  void find_live_supernodes() const {
    const int n_super = int(L->nsuper);
    const int* super = static_cast<const int*>(L->super);
    new_mark();
    reach.clear();
    for (int k = 0; k < n_super; ++k) {
      bool any = mark[size_t(k)] == mark_now;  // a child is live
      for (int j = super[k]; j < super[k + 1] && !any; ++j) any = w[size_t(j)] != 0.0;
      if (!any) continue;
      reach.push_back(k);
      if (super_parent[size_t(k)] >= 0) mark[size_t(super_parent[size_t(k)])] = mark_now;
    }
  }
  bool started = false;
  ~Impl() {
    if (started) {
      if (X) cholmod_free_dense(&X, &c);
      if (Y) cholmod_free_dense(&Y, &c);
      if (E) cholmod_free_dense(&E, &c);
      if (Xb) cholmod_free_dense(&Xb, &c);
      if (Yb) cholmod_free_dense(&Yb, &c);
      if (Eb) cholmod_free_dense(&Eb, &c);
      if (L) cholmod_free_factor(&L, &c);
      cholmod_finish(&c);
    }
  }
#endif
};

SparseCholesky::SparseCholesky(const Eigen::SparseMatrix<double>& A_in, std::string name,
                               const CholeskyOptions& options)
    : impl_(std::make_unique<Impl>()), name_(std::move(name)), rows_(int(A_in.rows())) {
  if (A_in.rows() != A_in.cols()) throw SolverError("Cholesky of " + name_ + ": matrix is not square");
  // A 0 x 0 matrix (an empty mesh) goes to Eigen, which factors it trivially; CHOLMOD rejects it.
  const bool want_cholmod = rows_ > 0 && (options.backend == CholeskyBackend::Cholmod ||
                                          (options.backend == CholeskyBackend::Automatic && cholmod_available()));
  if (options.backend == CholeskyBackend::Cholmod && !cholmod_available())
    throw SolverError("Cholesky of " + name_ + ": the CHOLMOD backend is not compiled in");
  if (!want_cholmod) {
    impl_->pattern = lower_pattern_hash(A_in);
    impl_->ldlt.analyzePattern(A_in);
    impl_->ldlt.factorize(A_in);
    check_eigen(impl_->ldlt, name_);
    return;
  }
#ifdef POLYDEC_HAVE_CHOLMOD
  blas_threads();  // the thread policy, applied once before the first factorization
  advise_cholmod_allocations();
  impl_->use_cholmod = true;
  cholmod_common& c = impl_->c;
  cholmod_start(&c);
  impl_->started = true;
  c.print = 0;  // errors are reported through SolverError, not on stderr
  c.supernodal = CHOLMOD_SUPERNODAL;
  // Relaxed supernode amalgamation, 4x CHOLMOD's defaults: fewer, larger supernodes make the
  // dense BLAS-3 updates pay off. Measured on FINE SPHERE's M - 0.1 S with one BLAS thread:
  // numeric factorization 243 ms (defaults) -> 154 ms (AMD), vs 506 ms for Eigen SimplicialLLT.
  if (options.relaxed_supernodes) {
    c.nrelax[0] = 16;
    c.nrelax[1] = 64;
    c.nrelax[2] = 192;
    c.zrelax[0] = 0.8;
    c.zrelax[1] = 0.3;
    c.zrelax[2] = 0.15;
  }
  c.nmethods = 1;
  switch (options.ordering) {
    case CholeskyOrdering::Automatic:
    case CholeskyOrdering::Amd: c.method[0].ordering = CHOLMOD_AMD; break;
    case CholeskyOrdering::Metis:
      c.method[0].ordering = CHOLMOD_METIS;
      impl_->ordering = "metis";
      break;
    case CholeskyOrdering::NestedDissection:
      c.method[0].ordering = CHOLMOD_NESDIS;
      impl_->ordering = "nesdis";
      break;
    case CholeskyOrdering::BestFill:
      c.nmethods = 2;
      c.method[0].ordering = CHOLMOD_AMD;
      c.method[1].ordering = CHOLMOD_NESDIS;
      break;
  }
  const SpMat A = A_in.isCompressed() ? SpMat() : SpMat(A_in);
  const SpMat& Ac = A_in.isCompressed() ? A_in : A;
  cholmod_sparse s = view_lower(Ac);
  impl_->L = cholmod_analyze(&s, &c);
  if (!impl_->L || c.status < CHOLMOD_OK)
    throw SolverError("Cholesky analysis of " + name_ + " failed (CHOLMOD status " + std::to_string(c.status) + ")");
  if (options.ordering == CholeskyOrdering::BestFill)
    impl_->ordering = c.method[c.selected].ordering == CHOLMOD_NESDIS ? "nesdis" : "amd";
  impl_->lnz = c.lnz;
  impl_->pattern = lower_pattern_hash(Ac);
  refactor(Ac);
#endif
}

SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::refactor(const Eigen::SparseMatrix<double>& A_in) {
  if (A_in.rows() != rows_ || A_in.cols() != rows_)
    throw SolverError("Cholesky refactorization of " + name_ + ": matrix size changed");
  if (lower_pattern_hash(A_in) != impl_->pattern)
    throw SolverError("Cholesky refactorization of " + name_ + ": the matrix's pattern differs from the analysed one");
  if (!impl_->use_cholmod) {
    impl_->ldlt.factorize(A_in);
    check_eigen(impl_->ldlt, name_);
    return;
  }
#ifdef POLYDEC_HAVE_CHOLMOD
  const SpMat A = A_in.isCompressed() ? SpMat() : SpMat(A_in);
  cholmod_sparse s = view_lower(A_in.isCompressed() ? A_in : A);
  cholmod_common& c = impl_->c;
  const int ok = [&] {
    const CholmodOpenMPScope serial;
    return cholmod_factorize(&s, impl_->L, &c);
  }();
  if (!ok || c.status == CHOLMOD_NOT_POSDEF || c.status < CHOLMOD_OK)
    throw SolverError("Cholesky factorization of " + name_ + " failed: matrix is not positive definite" +
                      (c.status == CHOLMOD_NOT_POSDEF ? " (breakdown at column " + std::to_string(impl_->L->minor) + ")"
                                                      : std::string()));
  // Non-finite entries and singular matrices (a rounding-level last pivot) do not always stop
  // CHOLMOD: check the range of the pivots L_ii^2 as the Eigen backend does (rcond is
  // (min L_ii / max L_ii)^2 for an LL^T factor).
  constexpr double kSingularPivot = 1e-12;
  const double rc = cholmod_rcond(impl_->L, &c);
  if (!(rc > kSingularPivot) || !std::isfinite(rc))
    throw SolverError("Cholesky factorization of " + name_ + " failed: matrix is singular or not finite");
  impl_->set_inverse_diagonal();
#endif
}

SparseCholesky::SparseCholesky(std::string name, int rows)
    : impl_(std::make_unique<Impl>()), name_(std::move(name)), rows_(rows) {}

SparseCholesky SparseCholesky::with_values(const Eigen::SparseMatrix<double>& A_in, std::string name) const {
  if (A_in.rows() != rows_ || A_in.cols() != rows_)
    throw SolverError("Cholesky of " + name + ": its size differs from that of " + name_ + ", whose analysis it reuses");
  const SpMat A = A_in.isCompressed() ? SpMat() : SpMat(A_in);
  const SpMat& Ac = A_in.isCompressed() ? A_in : A;
  SparseCholesky out(std::move(name), rows_);
  out.impl_->ordering = impl_->ordering;
  out.impl_->lnz = impl_->lnz;
  out.impl_->pattern = lower_pattern_hash(Ac);
  if (!impl_->use_cholmod) {
    out.impl_->ldlt.analyzePattern(Ac);
    out.impl_->ldlt.factorize(Ac);
    check_eigen(out.impl_->ldlt, out.name_);
    return out;
  }
#ifdef POLYDEC_HAVE_CHOLMOD
  if (out.impl_->pattern != impl_->pattern)
    throw SolverError("Cholesky of " + out.name_ + ": its pattern differs from that of " + name_ +
                      ", whose analysis it reuses");
  out.impl_->use_cholmod = true;
  cholmod_common& c = out.impl_->c;
  cholmod_start(&c);
  out.impl_->started = true;
  c.print = 0;
  c.supernodal = CHOLMOD_SUPERNODAL;
  // The copy carries the symbolic analysis (and the old values, overwritten by the factorization).
  out.impl_->L = cholmod_copy_factor(impl_->L, &c);
  if (!out.impl_->L || c.status < CHOLMOD_OK)
    throw SolverError("Cholesky of " + out.name_ + ": copying the analysis failed (CHOLMOD status " +
                      std::to_string(c.status) + ")");
  out.refactor(Ac);
#endif
  return out;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) const {
  if (b.rows() != rows_) throw SolverError("solve with " + name_ + ": right-hand side has the wrong size");
  if (!impl_->use_cholmod) return impl_->ldlt.solve(b);
  Eigen::VectorXd x(b.size());
  solve(b.data(), x.data(), 1);
  return x;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  if (B.rows() != rows_) throw SolverError("solve with " + name_ + ": right-hand side has the wrong size");
  if (!impl_->use_cholmod) return impl_->ldlt.solve(B);
  Eigen::MatrixXd X(B.rows(), B.cols());
  solve(B.data(), X.data(), int(B.cols()));
  return X;
}

void SparseCholesky::solve(const double* B, double* X, int n_columns) const {
  if (!impl_->use_cholmod) {
    Eigen::Map<Eigen::MatrixXd>(X, rows_, n_columns) =
        impl_->ldlt.solve(Eigen::Map<const Eigen::MatrixXd>(B, rows_, n_columns));
    return;
  }
#ifdef POLYDEC_HAVE_CHOLMOD
  Impl& m = *impl_;
  const bool one = n_columns == 1;
  if (one && m.own_solve()) {
    m.make_solve_buffers();
    const int* perm = static_cast<const int*>(m.L->Perm);
    for (int k = 0; k < rows_; ++k) m.w[size_t(k)] = B[perm ? perm[k] : k];
    m.make_tree();
    m.find_live_supernodes();
    m.supernodal_solve(m.reach.size() == m.L->nsuper ? nullptr : &m.reach, X);
    return;
  }
  cholmod_dense b{};
  b.nrow = size_t(rows_);
  b.ncol = size_t(n_columns);
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = const_cast<double*>(B);
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_solve2(CHOLMOD_A, m.L, &b, nullptr, one ? &m.X : &m.Xb, nullptr, one ? &m.Y : &m.Yb,
                      one ? &m.E : &m.Eb, &m.c))
    throw SolverError("solve with " + name_ + " failed (CHOLMOD status " + std::to_string(m.c.status) + ")");
  std::copy_n(static_cast<const double*>((one ? m.X : m.Xb)->x), size_t(rows_) * n_columns, X);
#endif
}

void SparseCholesky::solve_rows(double* X, int n_columns) const {
  if (n_columns < 1) return;
  const size_t n = size_t(rows_), m = size_t(n_columns);
#ifdef POLYDEC_HAVE_CHOLMOD
  Impl& im = *impl_;
  if (im.use_cholmod && im.own_solve()) {
    if (im.rows_block_size != n * m) {
      im.rows_block.reset();
      im.rows_block = uninitialized_on_huge_pages<double>(n * m);
      im.rows_block_size = n * m;
    }
    double* W = im.rows_block.get();
    const int* perm = static_cast<const int*>(im.L->Perm);
    for (size_t k = 0; k < n; ++k) std::copy_n(X + size_t(perm ? perm[k] : int(k)) * m, m, W + k * m);
    solve_rows_in_factor_order(W, n_columns, {});
    for (size_t k = 0; k < n; ++k) std::copy_n(W + k * m, m, X + size_t(perm ? perm[k] : int(k)) * m);
    return;
  }
#endif
  // Column-major through solve().
  Eigen::MatrixXd B = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      X, rows_, n_columns);
  solve(B.data(), B.data(), n_columns);
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(X, rows_, n_columns) = B;
}

std::span<const int> SparseCholesky::factor_order() const {
#ifdef POLYDEC_HAVE_CHOLMOD
  if (impl_->use_cholmod && impl_->own_solve() && impl_->L->Perm)
    return {static_cast<const int*>(impl_->L->Perm), size_t(rows_)};
#endif
  return {};
}

void SparseCholesky::solve_rows_in_factor_order(double* X, int n_columns, std::span<const int> nonzero_rows) const {
  if (n_columns < 1) return;
#ifdef POLYDEC_HAVE_CHOLMOD
  const Impl& im = *impl_;
  if (im.use_cholmod && im.own_solve()) {
    const SupernodalView V(*im.L, im.inverse_diagonal);
    const int n_super = int(im.L->nsuper);
    if (nonzero_rows.empty()) {
      rows_solve(V, nullptr, n_super, n_super, X, n_columns);
      return;
    }
    for (const int p : nonzero_rows)
      if (p < 0 || p >= rows_)
        throw std::invalid_argument("solve_rows_in_factor_order with " + name_ + ": row " + std::to_string(p) +
                                    " out of range");
    im.make_tree();
    im.find_reach(nonzero_rows);
    rows_solve(V, im.reach.data(), int(im.reach.size()), n_super, X, n_columns);
    return;
  }
#endif
  solve_rows(X, n_columns);  // no order of its own: A's
}

Eigen::VectorXd SparseCholesky::solve_sparse(std::span<const int> rows, std::span<const double> values) const {
  Eigen::VectorXd x(rows_);
  solve_sparse(rows, values, x.data());
  return x;
}

void SparseCholesky::solve_sparse(std::span<const int> rows, std::span<const double> values, double* x) const {
  if (rows.size() != values.size())
    throw std::invalid_argument("solve_sparse with " + name_ + ": rows and values differ in length");
  for (size_t k = 0; k < rows.size(); ++k)
    if (rows[k] < 0 || rows[k] >= rows_)
      throw std::invalid_argument("solve_sparse with " + name_ + ": row " + std::to_string(rows[k]) + " out of range");
  {
    std::vector<int> sorted(rows.begin(), rows.end());
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw std::invalid_argument("solve_sparse with " + name_ + ": row " +
                                  std::to_string(*std::adjacent_find(sorted.begin(), sorted.end())) + " repeated");
  }
  if (!impl_->use_cholmod || rows.empty()) {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(rows_);
    for (size_t k = 0; k < rows.size(); ++k) b[rows[k]] = values[k];
    solve(b.data(), x, 1);
    return;
  }
#ifdef POLYDEC_HAVE_CHOLMOD
  Impl& m = *impl_;
  if (!m.own_solve())
    throw SolverError("sparse solve with " + name_ + ": the factor is not a real supernodal LL^T one");
  m.make_solve_buffers();
  m.make_tree();
  double* y = m.w.data();
  std::fill(y, y + rows_, 0.0);
  std::vector<int> factor_rows(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    factor_rows[k] = m.iperm[size_t(rows[k])];
    y[factor_rows[k]] = values[k];
  }
  m.find_reach(factor_rows);
  // L y = P b over the reach; L^T z = y over the whole factor; x = P^T z.
  m.supernodal_solve(&m.reach, x);
#endif
}

std::string SparseCholesky::backend() const {
  return impl_->use_cholmod ? "cholmod-supernodal" : "eigen-simplicial-ldlt";
}

double SparseCholesky::factor_nonzeros() const {
#ifdef POLYDEC_HAVE_CHOLMOD
  if (impl_->use_cholmod) return impl_->lnz;
#endif
  return double(impl_->ldlt.matrixL().nestedExpression().nonZeros());
}

std::string SparseCholesky::ordering() const { return impl_->ordering; }

namespace blas_thread_detail {

std::mutex& policy_mutex() {
  static std::mutex m;
  return m;
}
BlasThreads& recorded() {
  static BlasThreads b;
  return b;
}

// OpenBLAS's thread count when OpenBLAS is mapped, else -1.
int openblas_threads() {
  using Get = int (*)();
  auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return get ? get() : -1;
}

// Calls openblas_set_num_threads(n) (n = 0: one per hardware thread); false when not mapped.
bool openblas_set(int n) {
  using Set = void (*)(int);
  auto set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (!set) return false;
  set(n > 0 ? n : std::max(1, int(std::thread::hardware_concurrency())));
  return true;
}

int parse_count(const char* name, const char* value) {
  const std::string_view v(value);
  int n = -1;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
  if (v.empty() || r.ec != std::errc() || r.ptr != v.data() + v.size() || n < 0 || n > 1024)
    throw std::invalid_argument(std::string(name) + "='" + std::string(v.substr(0, 40)) +
                                "' is not a thread count from 0 to 1024");
  return n;
}

// Applies `requested` from `source` and records it; the caller holds the mutex.
BlasThreads apply(int requested, std::string source, bool set_it) {
  BlasThreads b;
  b.requested = requested;
  b.source = std::move(source);
  b.applied = set_it && openblas_set(requested);
  b.threads = openblas_threads();
  recorded() = b;
  return b;
}

}  // namespace blas_thread_detail

BlasThreads blas_threads() {
  using namespace blas_thread_detail;
  std::lock_guard lock(policy_mutex());
  if (!recorded().source.empty()) {
    recorded().threads = openblas_threads();
    return recorded();
  }
  if (const char* v = std::getenv("POLYDEC_BLAS_THREADS"))
    return apply(parse_count("POLYDEC_BLAS_THREADS", v), "POLYDEC_BLAS_THREADS", true);
  for (const char* name : {"OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"})
    if (const char* v = std::getenv(name); v && *v) {
      const int t = openblas_threads();
      return apply(t > 0 ? t : 0, name, false);  // OpenBLAS read it at load time
    }
  return apply(1, "default", true);
}

BlasThreads set_blas_threads(int n) {
  using namespace blas_thread_detail;
  if (n < 0 || n > 1024)
    throw std::invalid_argument("BLAS threads must be from 0 to 1024, got " + std::to_string(n));
  std::lock_guard lock(policy_mutex());
  return apply(n, "set_blas_threads", true);
}

bool SparseCholesky::cholmod_available() {
#ifdef POLYDEC_HAVE_CHOLMOD
  return true;
#else
  return false;
#endif
}

Eigen::SparseMatrix<double> pin_to_identity(const Eigen::SparseMatrix<double>& A, const std::vector<unsigned char>& pinned,
                                            bool keep_pattern) {
  using SparseMatrix = Eigen::SparseMatrix<double>;
  const int n = int(A.cols());
  auto has_diagonal = [&](int j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() == j) return true;
    return false;
  };
  SparseMatrix B(A.rows(), A.cols());
  int* outer = B.outerIndexPtr();
  for (int j = 0; j < n; ++j) {
    int count = 1;
    if (keep_pattern) {
      count = int(A.outerIndexPtr()[j + 1] - A.outerIndexPtr()[j]) + (has_diagonal(j) ? 0 : 1);
    } else if (!pinned[j]) {
      count = 0;
      for (SparseMatrix::InnerIterator it(A, j); it; ++it) count += !pinned[it.row()];
    }
    outer[j + 1] = outer[j] + count;
  }
  B.resizeNonZeros(outer[n]);
  advise_huge_pages(B.valuePtr(), sizeof(double) * size_t(outer[n]));
  advise_huge_pages(B.innerIndexPtr(), sizeof(int) * size_t(outer[n]));
  int* inner = B.innerIndexPtr();
  double* value = B.valuePtr();
  for (int j = 0; j < n; ++j) {
    int at = outer[j];
    if (keep_pattern) {
      // A's entries in order, the diagonal inserted where it is missing; pinned rows and
      // columns zero off the diagonal, one on it.
      bool diagonal_done = false;
      auto put = [&](int row, double v) {
        inner[at] = row;
        value[at++] = (pinned[j] || pinned[row]) ? (row == j ? 1.0 : 0.0) : v;
      };
      for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
        if (!diagonal_done && it.row() >= j) {
          if (it.row() > j) put(j, 0.0);
          diagonal_done = true;
        }
        put(int(it.row()), it.value());
      }
      if (!diagonal_done) put(j, 0.0);
      continue;
    }
    if (pinned[j]) {
      inner[at] = j;
      value[at] = 1.0;
      continue;
    }
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (!pinned[it.row()]) {
        inner[at] = int(it.row());
        value[at++] = it.value();
      }
  }
  return B;
}

Eigen::SparseMatrix<double> principal_submatrix(const Eigen::SparseMatrix<double>& A, const std::vector<int>& index) {
  using SparseMatrix = Eigen::SparseMatrix<double>;
  const int n = int(std::count_if(index.begin(), index.end(), [](int i) { return i >= 0; }));
  SparseMatrix B(n, n);
  int* outer = B.outerIndexPtr();
  for (int j = 0; j < int(A.cols()); ++j)
    if (index[size_t(j)] >= 0) {
      int count = 0;
      for (SparseMatrix::InnerIterator it(A, j); it; ++it) count += index[size_t(it.row())] >= 0;
      outer[index[size_t(j)] + 1] = count;
    }
  for (int c = 0; c < n; ++c) outer[c + 1] += outer[c];
  B.resizeNonZeros(outer[n]);
  advise_huge_pages(B.valuePtr(), sizeof(double) * size_t(outer[n]));
  advise_huge_pages(B.innerIndexPtr(), sizeof(int) * size_t(outer[n]));
  for (int j = 0; j < int(A.cols()); ++j) {
    if (index[size_t(j)] < 0) continue;
    int at = outer[index[size_t(j)]];
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (index[size_t(it.row())] >= 0) {
        B.innerIndexPtr()[at] = index[size_t(it.row())];
        B.valuePtr()[at++] = it.value();
      }
  }
  return B;
}

}  // namespace polydec
