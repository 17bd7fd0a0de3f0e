// operators/volume/laplacian.cpp — cell-by-cell assembly of the polyhedral stiffness and mass.
#include "polydec/operators/volume/laplacian.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "polydec/dec/detail/element_pattern.h"
#include "polydec/dec/detail/element_pattern_threads.h"
#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/detail/scale.h"
#include "polydec/dec/detail/threads.h"

namespace polydec {

SparseMatrix cell_pattern(const VolumeMesh& mesh) {
  detail::ElementPattern ep =
      detail::element_pattern<detail::SlotKind::none>(mesh.n_vertices(), mesh.n_cells(), [&](int c) { return mesh.cell_vertices(c); });
  SparseMatrix pattern;
  pattern.swap(ep.pattern);  // Eigen 3.4's SparseMatrix has no move constructor
  return pattern;
}

namespace volume_laplacian_detail {
namespace {

// Reused buffers of the cell kernel (no allocation per cell once they have grown).
struct CellWorkspace {
  std::vector<double> p;       // 3m: the cell's vertices relative to its cell point
  std::vector<int> corner;     // a face's corners in outward order, as indices into cell_vertices(c)
  std::vector<double> weight;  // the face weights in the same order
  std::vector<double> fine;    // a face's fine stiffness when it has more corners than the fixed sizes
  std::vector<double> hs, hm;  // couplings of the cell's vertices with the cell point
  std::vector<int> local;      // |V|: a vertex's index in the current cell's vertices
};

inline void cross(const double* a, const double* b, double* out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
inline double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// One face's fine stiffness over [corners, face point, cell point]: the corner diagonal `diag`, the
// couplings `next` (corner i with i + 1), `fq` (corner, face point), `fc` (corner, cell point), and
// qq, qc, cc. The fine mass needs only the sub-tetrahedra's volumes / 20, `mv`.
struct FaceFine {
  double *diag, *next, *fq, *fc, *mv;
  double qq = 0, qc = 0, cc = 0;
};

// Folds the face point (row w of P) of both fine face matrices into the corners and adds them to
// the coarse cell matrices S, M (upper triangles, m x m column-major) and the cell-point
// couplings: F + w t^T + t w^T with t = fq + qq w / 2. The mass comes from the volumes: the linear
// tetrahedron's is vol/20 (I + 1 1^T), and corner i lies in sub-tetrahedra i - 1 and i. ts, tm:
// n entries of scratch each. N > 0: n at compile time.
template <int N>
inline void fold_face(int n_dyn, const int* o, const double* w, const FaceFine& F, long m, double* __restrict S,
                      double* __restrict M, double* __restrict hs, double* __restrict hm, double& as, double& am,
                      double* __restrict ts, double* __restrict tm) {
  const int n = N > 0 ? N : n_dyn;
  double total = 0;
  for (int i = 0; i < n; ++i) total += F.mv[i];
  for (int i = 0; i < n; ++i) {
    const double si = F.mv[i == 0 ? n - 1 : i - 1] + F.mv[i];  // mass couplings of corner i: diag 2 si
    ts[i] = F.fq[i] + 0.5 * F.qq * w[i];
    tm[i] = si + total * w[i];
    const long oi = o[i];
    S[oi + oi * m] += F.diag[i] + 2 * w[i] * ts[i];
    M[oi + oi * m] += 2 * si + 2 * w[i] * tm[i];
    hs[oi] += F.fc[i] + w[i] * F.qc;
    hm[oi] += si + w[i] * total;
  }
  // Corner pairs (i, j): the face's edges carry their own couplings, the other pairs only the fold's.
  auto add_pair = [&](int i, int j, double es, double em) {
    const long oi = o[i], oj = o[j], k = oi < oj ? oi + oj * m : oj + oi * m;
    S[k] += w[i] * ts[j] + w[j] * ts[i] + es;
    M[k] += w[i] * tm[j] + w[j] * tm[i] + em;
  };
  for (int i = 0; i < n; ++i) add_pair(i, i + 1 == n ? 0 : i + 1, F.next[i], F.mv[i]);
  for (int i = 0; i < n; ++i)
    for (int j = i + 2; j < (i == 0 ? n - 1 : n); ++j) add_pair(i, j, 0.0, 0.0);
  as += F.cc;
  am += 2 * total;
}

// One face of the cell: corners o (outward order, indices into the cell's vertices p, which are
// relative to the cell point) with weights w, face point q (relative to the cell point), its
// sub-tetrahedra's flags from `flags` on (tetrahedron i: corners i, i + 1, face point, cell point,
// the order of VolumeRefinement::tets). With the cell point at the origin the hat gradients of
// tetrahedron i are D_{i+1}, -D_i, E_i and minus their sum, over det = p_i . D_{i+1}, with
// D_i = p_i x q and E_i = p_i x p_{i+1}: two cross products per tetrahedron (D_{i+1} is the next
// one's D_i) and five dot products give its six couplings, the zero row sums the rest. Both fine
// face matrices are folded into S, M (upper triangles) and the cell-point couplings.
template <int N>
void add_face(const SubTet* flags, int n_dyn, const int* o, const double* w, const double* p, const double* q,
              long m, double* S, double* M, CellWorkspace& ws, double& as, double& am) {
  const int n = N > 0 ? N : n_dyn;
  double stack[N > 0 ? 7 * N : 1];
  double* buffer = stack;
  if constexpr (N == 0) {
    if (ws.fine.size() < 7 * size_t(n)) ws.fine.resize(7 * size_t(n));
    buffer = ws.fine.data();
  }
  FaceFine F{buffer, buffer + n, buffer + 2 * n, buffer + 3 * n, buffer + 4 * n};
  double qq = 0, qc = 0, cc = 0;
  // Corner i's couplings come from tetrahedra i - 1 (as its second corner, carried in pd, pq, pc)
  // and i (as its first); corner 0's from tetrahedron 0 wait in d0, q0, c0 for the last one.
  double pd = 0, pq = 0, pc = 0, d0 = 0, q0 = 0, c0 = 0;
  const double* pa = p + 3 * o[0];
  double D0[3], Dp[3], Dn[3], E[3];
  cross(pa, q, D0);
  const double D02 = dot(D0, D0);
  std::copy(D0, D0 + 3, Dp);
  double Dp2 = D02;
  for (int i = 0; i < n; ++i) {
    const int b = i + 1 == n ? 0 : i + 1;
    const double* pb = p + 3 * o[b];
    double Dn2;
    if (b == 0) {
      std::copy(D0, D0 + 3, Dn);
      Dn2 = D02;
    } else {
      cross(pb, q, Dn);
      Dn2 = dot(Dn, Dn);
    }
    const double vol6 = std::abs(dot(pa, Dn));
    F.mv[i] = vol6 * (1.0 / 120.0);
    double kaa = 0, kab = 0, kaq = 0, kac = 0, kbb = 0, kbq = 0, kbc = 0;
    if (flags[i] != SubTet::Degenerate && vol6 > 0) {
      cross(pa, pb, E);
      const double s = -1.0 / (6.0 * vol6);
      kab = -s * dot(Dn, Dp), kaq = s * dot(Dn, E), kbq = -s * dot(Dp, E);
      kaa = s * Dn2, kbb = s * Dp2;
      const double kqq = s * dot(E, E);
      kac = -(kaa + kab + kaq), kbc = -(kab + kbb + kbq);
      const double kqc = -(kaq + kbq + kqq);
      qq += kqq, qc += kqc, cc -= kac + kbc + kqc;
    }
    if (i == 0) {
      d0 = kaa, q0 = kaq, c0 = kac;
    } else {
      F.diag[i] = pd + kaa, F.fq[i] = pq + kaq, F.fc[i] = pc + kac;
    }
    F.next[i] = kab;
    pd = kbb, pq = kbq, pc = kbc;
    std::copy(Dn, Dn + 3, Dp);
    Dp2 = Dn2;
    pa = pb;
  }
  F.diag[0] = d0 + pd, F.fq[0] = q0 + pq, F.fc[0] = c0 + pc;
  F.qq = qq, F.qc = qc, F.cc = cc;
  fold_face<N>(n, o, w, F, m, S, M, ws.hs.data(), ws.hm.data(), as, am, buffer + 5 * n, buffer + 6 * n);
}

// C += h w^T + w h^T + alpha w w^T on the upper triangle of C = S and C = M: the cell point's row
// of P_c is w, so the fine couplings h (vertex, cell point) and alpha (cell point, cell point)
// become coarse ones.
void add_cell_point(const double* hs, double as, const double* hm, double am, std::span<const double> w, long m,
                    double* __restrict S, double* __restrict M) {
  for (long j = 0; j < m; ++j) {
    double *cs = S + j * m, *cm = M + j * m;
    const double wj = w[j], sj = hs[j] + as * wj, mj = hm[j] + am * wj;
    for (long i = 0; i <= j; ++i) {
      cs[i] += hs[i] * wj + w[i] * sj;
      cm[i] += hm[i] * wj + w[i] * mj;
    }
  }
}

// The lower triangle of the m x m column-major C from its upper one.
void mirror_upper(long m, double* C) {
  for (long j = 0; j < m; ++j)
    for (long i = j + 1; i < m; ++i) C[i + j * m] = C[j + i * m];
}

// P_c^T S^tet P_c and P_c^T M^tet P_c without the cell's fine matrices: per face, the
// sub-tetrahedra's stiffness and mass over [face corners, face point, cell point] (add_face()),
// the face point folded into the corners by its weights once per face, the cell point's
// couplings (row w of P_c) once per cell; coordinates relative to the cell point. Only the upper
// triangles of S and M are written.
void cell_kernel(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c, Eigen::MatrixXd& S,
                 Eigen::MatrixXd& M, CellWorkspace& ws) {
  const auto verts = mesh.cell_vertices(c);
  const auto cell = mesh.cell(c);
  const int m = int(verts.size());
  const auto& X = mesh.positions();
  const double xc[3] = {refinement.cell_points(c, 0), refinement.cell_points(c, 1), refinement.cell_points(c, 2)};
  // Buffers only grow (no resizing per cell or face).
  if (ws.p.size() < 3 * size_t(m)) ws.p.resize(3 * size_t(m)), ws.hs.resize(m), ws.hm.resize(m);
  if (ws.local.size() < size_t(mesh.n_vertices())) ws.local.resize(size_t(mesh.n_vertices()));
  double* p = ws.p.data();
  for (int k = 0; k < m; ++k) {
    ws.local[verts[k]] = k;
    for (int d = 0; d < 3; ++d) p[3 * k + d] = X(verts[k], d) - xc[d];
  }
  // A cell far outside the ordinary sizes is computed in units of 2^e (dec/detail/scale.h) and its
  // matrices scaled back at the end: S by 2^e, M by 2^3e (e = 0, the usual case: nothing changes).
  const int e = detail::normalizing_exponent(detail::max_abs(p, 3 * m));
  const double inv = std::ldexp(1.0, -e);
  if (e != 0)
    for (int k = 0; k < 3 * m; ++k) p[k] *= inv;
  S.setZero(m, m);
  M.setZero(m, m);
  std::fill_n(ws.hs.data(), m, 0.0);
  std::fill_n(ws.hm.data(), m, 0.0);
  double as = 0, am = 0;
  const SubTet* flags = refinement.tets.data() + refinement.tet_offsets[c];
  for (const int hf : cell) {
    const int f = hf / 2;
    const auto face = mesh.face(f);
    const int n = int(face.size());
    const double* wf = refinement.weights_of_face(mesh, f).data();
    if (ws.corner.size() < size_t(n)) ws.corner.resize(n), ws.weight.resize(n);
    // Half-face 2f + 1 runs against the face: its i-th corner is face[n - 1 - i].
    for (int i = 0; i < n; ++i) {
      const int k = hf & 1 ? n - 1 - i : i;
      ws.corner[i] = ws.local[face[k]];
      ws.weight[i] = wf[k];
    }
    const double q[3] = {(refinement.face_points(f, 0) - xc[0]) * inv, (refinement.face_points(f, 1) - xc[1]) * inv,
                         (refinement.face_points(f, 2) - xc[2]) * inv};
    if (n == 4)
      add_face<4>(flags, n, ws.corner.data(), ws.weight.data(), p, q, m, S.data(), M.data(), ws, as, am);
    else if (n == 3)
      add_face<3>(flags, n, ws.corner.data(), ws.weight.data(), p, q, m, S.data(), M.data(), ws, as, am);
    else
      add_face<0>(flags, n, ws.corner.data(), ws.weight.data(), p, q, m, S.data(), M.data(), ws, as, am);
    flags += n;
  }
  const auto w = refinement.weights_of_cell(c);
  add_cell_point(ws.hs.data(), as, ws.hm.data(), am, w, m, S.data(), M.data());
  if (e != 0)
    for (long k = 0; k < long(m) * m; ++k) S.data()[k] = std::ldexp(S.data()[k], e), M.data()[k] = std::ldexp(M.data()[k], 3 * e);
}

}  // namespace
}  // namespace volume_laplacian_detail

void cell_matrices(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c, Eigen::MatrixXd* S,
                   Eigen::MatrixXd* M) {
  check_refinement_cell(mesh, refinement, c, "cell_matrices");
  volume_laplacian_detail::CellWorkspace ws;
  Eigen::MatrixXd Sc, Mc;
  volume_laplacian_detail::cell_kernel(mesh, refinement, c, Sc, Mc, ws);
  volume_laplacian_detail::mirror_upper(Sc.rows(), Sc.data());
  volume_laplacian_detail::mirror_upper(Mc.rows(), Mc.data());
  if (S) *S = std::move(Sc);
  if (M) *M = std::move(Mc);
}

namespace volume_laplacian_detail {
namespace {

// The cells cut into R contiguous ranges (part_of). A vertex all of whose cells lie in range r is
// owned by r; one whose cells lie in several ranges is a seam vertex, in the seam group g of the
// lowest of them. seam_cells[g]: the cells with a vertex of group g, ascending.
struct Owners {
  std::vector<int> owner;  // r >= 0 for range r, -2 - g for seam group g
  std::vector<std::vector<int>> seam_cells;
  long seam_work = 0;  // cells in all the groups' lists (a cell may be in several)
};

Owners owners(const VolumeMesh& mesh, int R) {
  const int nC = mesh.n_cells();
  constexpr int kNone = -1;
  Owners out;
  out.owner.assign(size_t(mesh.n_vertices()), kNone);
  // Ranges ascending: a vertex first met in range o and now in r > o joins group o.
  for (int r = 0; r < R; ++r) {
    const auto [lo, hi] = part_of(nC, r, R);
    for (long c = lo; c < hi; ++c)
      for (const int v : mesh.cell_vertices(int(c))) {
        int& o = out.owner[size_t(v)];
        if (o == kNone) o = r;
        else if (o >= 0 && o != r) o = -2 - o;
      }
  }
  out.seam_cells.resize(size_t(std::max(0, R - 1)));
  for (int c = 0; c < nC; ++c)
    for (const int v : mesh.cell_vertices(c))
      if (const int o = out.owner[size_t(v)]; o < kNone) {
        std::vector<int>& list = out.seam_cells[size_t(-2 - o)];
        if (list.empty() || list.back() != c) list.push_back(c), ++out.seam_work;
      }
  return out;
}

}  // namespace
}  // namespace volume_laplacian_detail

VolumeLaplacian assemble_volume_laplacian(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                          const SparseMatrix* pattern, int threads) {
  check_refinement(mesh, refinement, "assemble_volume_laplacian");
  check_length_powers(mesh, {{1, "the stiffness matrix's entries"}, {3, "the mass matrix's entries"}});
  using namespace volume_laplacian_detail;
  VolumeLaplacian L;
  L.quality = refinement.quality;
  const int nC = mesh.n_cells(), nV = mesh.n_vertices();
  // Where each cell's local entries go: slot a m + b of cell c (rows and columns in the order of
  // cell_vertices(c)) is row verts[a] of column verts[b], that many entries past the column's
  // start, so the assembly adds without searching the column (2 bytes per slot).
  // With several threads, every large array is also first written by all of them (page faults
  // and the kernel's zeroing of fresh pages cost as much as the arithmetic on large meshes).
  const int T = std::min(resolve_threads(threads), std::max(1, nC / 2048));
  detail::ElementPattern slots;
  auto cells = [&](int c) { return mesh.cell_vertices(c); };
  if (pattern) {
    L.S = *pattern;
    L.S.coeffs().setZero();
  } else {
    slots = T > 1 ? detail::element_pattern_threaded<detail::SlotKind::column_relative>(nV, nC, cells, T)
                  : detail::element_pattern<detail::SlotKind::column_relative>(nV, nC, cells);
    L.S.swap(slots.pattern);  // values already zero
  }
  // M: S's pattern, zero values (a copy by hand, so that its arrays take huge pages too).
  const long nnz = L.S.nonZeros();
  L.M.resize(L.S.rows(), L.S.cols());
  L.M.resizeNonZeros(nnz);
  advise_huge_pages(L.M.innerIndexPtr(), sizeof(int) * size_t(nnz));
  advise_huge_pages(L.M.valuePtr(), sizeof(double) * size_t(nnz));
  std::copy_n(L.S.outerIndexPtr(), L.S.outerSize() + 1, L.M.outerIndexPtr());
  run_on_threads(T, [&](int t) {
    const auto [lo, hi] = part_of(nnz, t, T);
    std::copy(L.S.innerIndexPtr() + lo, L.S.innerIndexPtr() + hi, L.M.innerIndexPtr() + lo);
    std::fill(L.M.valuePtr() + lo, L.M.valuePtr() + hi, 0.0);
  });
  const int* outer = L.S.outerIndexPtr();
  const int* inner = L.S.innerIndexPtr();
  double* sv = L.S.valuePtr();
  double* mv = L.M.valuePtr();
  // Adds cell c's local matrices (column-major m x m, upper triangles) to the columns v with keep(v):
  // by the cells' slots, or (a pattern given by the caller) by one forward walk per column, the
  // cell's vertices being ascending, as are a column's rows.
  const bool by_slots = slots.relative_slots != nullptr;
  auto scatter = [&](int c, const double* Sc, const double* Mc, auto keep) {
    const auto verts = mesh.cell_vertices(c);
    const int m = int(verts.size());
    if (by_slots) {
      const std::uint16_t* slot = slots.relative_slots.get() + slots.offsets[c];
      for (int b = 0; b < m; ++b) {
        if (!keep(verts[b])) continue;
        double *cs = sv + outer[verts[b]], *cm = mv + outer[verts[b]];
        const std::uint16_t* s = slot + b;  // slot (a, b) at s[a m]
        for (int a = 0; a <= b; ++a) cs[s[a * m]] += Sc[a + long(b) * m], cm[s[a * m]] += Mc[a + long(b) * m];
        for (int a = b + 1; a < m; ++a) cs[s[a * m]] += Sc[b + long(a) * m], cm[s[a * m]] += Mc[b + long(a) * m];
      }
      return;
    }
    for (int b = 0; b < m; ++b) {
      if (!keep(verts[b])) continue;
      int pos = outer[verts[b]];
      for (int a = 0; a < m; ++a) {
        while (inner[pos] != verts[a]) ++pos;
        const long k = a <= b ? a + long(b) * m : b + long(a) * m;
        sv[pos] += Sc[k];
        mv[pos] += Mc[k];
      }
    }
  };
  if (T == 1) {
    Eigen::MatrixXd Sc, Mc;
    CellWorkspace ws;
    for (int c = 0; c < nC; ++c) {
      cell_kernel(mesh, refinement, c, Sc, Mc, ws);
      scatter(c, Sc.data(), Mc.data(), [](int) { return true; });
    }
  } else if (const Owners own = owners(mesh, T); own.seam_work * 8 <= nC) {
    // Thread t computes the cells of range t and adds them to the columns the range owns, then
    // takes seam groups as they come free and adds the cells of each group's list to its columns.
    // Owned and seam columns are disjoint, so a thread starts on the seams while others still work
    // on their ranges. Either way each column receives its terms in cell order (bitwise as one
    // thread). More ranges than threads, taken as threads come free, were measured slower on the
    // 1M-cell grid (docs/benchmarks.md): each range boundary puts 2% of its cells on a seam.
    std::atomic<long> next_group{0};
    run_on_threads(T, [&](int t) {
      Eigen::MatrixXd Sc, Mc;
      CellWorkspace ws;
      const auto [lo, hi] = part_of(nC, t, T);
      for (long c = lo; c < hi; ++c) {
        cell_kernel(mesh, refinement, int(c), Sc, Mc, ws);
        scatter(int(c), Sc.data(), Mc.data(), [&](int v) { return own.owner[size_t(v)] == t; });
      }
      take_chunks(next_group, T - 1, 1, [&](long g) {
        for (const int c : own.seam_cells[size_t(g)]) {
          cell_kernel(mesh, refinement, c, Sc, Mc, ws);
          scatter(c, Sc.data(), Mc.data(), [&](int v) { return own.owner[size_t(v)] == -2 - g; });
        }
      });
    });
  } else {
    // Cell order without spatial coherence (more than 1/8 of the cells on seams): blocks of cells.
    // The threads compute the block's local matrices (cells split in ranges),
    // then add them with each thread owning a range of columns, visiting the cells in order: every
    // entry receives its terms in cell order, as with one thread (bitwise identical results).
    const int block = 4096;
    std::vector<size_t> offset(size_t(block) + 1);
    // The blocks' local matrices (1 KB per hexahedron, 4 MB per block of hexahedra): one buffer of
    // the largest block's size, allocated once and advised for huge pages.
    size_t largest = 0;
    for (int c0 = 0; c0 < nC; c0 += block) {
      size_t size = 0;
      for (int c = c0; c < std::min(nC, c0 + block); ++c) {
        const size_t m = mesh.cell_vertices(c).size();
        size += 2 * m * m;
      }
      largest = std::max(largest, size);
    }
    std::vector<double> local;
    assign_on_huge_pages(local, largest);
    std::vector<CellWorkspace> ws(T);
    for (int c0 = 0; c0 < nC; c0 += block) {
      const int c1 = std::min(nC, c0 + block);
      // The block's vertex range, which the threads split for the scatter: splitting all of
      // [0, nV) would hand a block of neighbouring cells (vertices of nearby numbers) to one thread.
      int vlo = nV, vhi = 0;
      for (int c = c0; c < c1; ++c) {
        const auto verts = mesh.cell_vertices(c);
        const size_t m = verts.size();
        offset[c - c0 + 1] = offset[c - c0] + 2 * m * m;
        for (int v : verts) vlo = std::min(vlo, v), vhi = std::max(vhi, v + 1);
      }
      run_on_threads(T, [&](int t) {
        Eigen::MatrixXd Sc, Mc;
        const auto [lo, hi] = part_of(c1 - c0, t, T);
        for (int c = c0 + int(lo); c < c0 + int(hi); ++c) {
          cell_kernel(mesh, refinement, c, Sc, Mc, ws[t]);
          double* out = local.data() + offset[c - c0];
          std::copy(Sc.data(), Sc.data() + Sc.size(), out);
          std::copy(Mc.data(), Mc.data() + Mc.size(), out + Sc.size());
        }
      });
      run_on_threads(T, [&](int t) {
        const auto [lo, hi] = part_of(vhi - vlo, t, T);
        const int v0 = vlo + int(lo), v1 = vlo + int(hi);
        for (int c = c0; c < c1; ++c) {
          const size_t m = mesh.cell_vertices(c).size();
          const double* in = local.data() + offset[c - c0];
          scatter(c, in, in + m * m, [&](int v) { return v >= v0 && v < v1; });
        }
      });
    }
  }
  // Row sums of M as its column sums (M is bitwise symmetric: both triangles get the same local
  // values, so this is the sum M 1 in the same order), one pass over the values.
  L.M_lumped.resize(nV);
  advise_huge_pages(L.M_lumped.data(), sizeof(double) * size_t(nV));
  run_on_threads(T, [&](int t) {
    const auto [lo, hi] = part_of(nV, t, T);
    for (long v = lo; v < hi; ++v) {
      double sum = 0;
      for (int k = outer[v]; k < outer[v + 1]; ++k) sum += mv[k];
      L.M_lumped[v] = sum;
    }
  });
  return L;
}

}  // namespace polydec
