// operators/volume_laplacian.cpp — cell-by-cell assembly of the polyhedral stiffness and mass.
#include "polydec/operators/volume_laplacian.h"

#include <algorithm>
#include <vector>

#include "polydec/dec/threads.h"


namespace polydec {

namespace volume_laplacian_detail {
namespace {

int local_index(std::span<const int> verts, int v) {
  return int(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin());
}

}  // namespace
}  // namespace volume_laplacian_detail

SparseMatrix volume_prolongation(const VolumeMesh& mesh, const VolumeRefinement& refinement) {
  const int nV = mesh.n_vertices(), nF = mesh.n_faces(), nC = mesh.n_cells();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(size_t(nV) + mesh.face_indices().size() + refinement.cell_weights.size());
  for (int v = 0; v < nV; ++v) t.emplace_back(v, v, 1.0);
  for (int f = 0; f < nF; ++f) {
    const auto face = mesh.face(f);
    const auto w = refinement.weights_of_face(mesh, f);
    for (size_t k = 0; k < face.size(); ++k) t.emplace_back(nV + f, face[k], w[k]);
  }
  for (int c = 0; c < nC; ++c) {
    const auto verts = mesh.cell_vertices(c);
    const auto w = refinement.weights_of_cell(c);
    for (size_t k = 0; k < verts.size(); ++k) t.emplace_back(nV + nF + c, verts[k], w[k]);
  }
  SparseMatrix P(nV + nF + nC, nV);
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

SparseMatrix cell_pattern(const VolumeMesh& mesh) {
  const int nV = mesh.n_vertices(), nC = mesh.n_cells();
  std::vector<int> count(nV + 1, 0);
  for (int c = 0; c < nC; ++c)
    for (int v : mesh.cell_vertices(c)) ++count[v + 1];
  for (int v = 0; v < nV; ++v) count[v + 1] += count[v];
  std::vector<int> cells(count[nV]), fill(count.begin(), count.end() - 1);
  for (int c = 0; c < nC; ++c)
    for (int v : mesh.cell_vertices(c)) cells[fill[v]++] = c;
  // Column v: the vertices of v's cells, each once (marked with v), sorted.
  std::vector<int> outer(nV + 1, 0), inner, mark(nV, -1);
  inner.reserve(size_t(count[nV]) * 4);
  for (int v = 0; v < nV; ++v) {
    const size_t begin = inner.size();
    for (int k = count[v]; k < count[v + 1]; ++k)
      for (int u : mesh.cell_vertices(cells[k]))
        if (mark[u] != v) {
          mark[u] = v;
          inner.push_back(u);
        }
    std::sort(inner.begin() + long(begin), inner.end());
    outer[v + 1] = int(inner.size());
  }
  SparseMatrix pattern(nV, nV);
  pattern.resizeNonZeros(long(inner.size()));
  std::copy(outer.begin(), outer.end(), pattern.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), pattern.innerIndexPtr());
  std::fill(pattern.valuePtr(), pattern.valuePtr() + inner.size(), 0.0);
  return pattern;
}

namespace volume_laplacian_detail {
namespace {

// One face's fine matrix over [corners, face point, cell point] (symmetric): its sub-tetrahedra
// (a, b, face point, cell point) couple only a corner with itself, with its next corner, with the
// face point and with the cell point, and the two points with each other.
struct FaceMatrix {
  double *diag, *next, *face, *cell;  // n entries each: (i, i), (i, i + 1 mod n), (i, face point), (i, cell point)
  double ff = 0, fc = 0, cc = 0;      // (face, face), (face, cell), (cell, cell)
  // The four arrays in the 4n entries at p.
  FaceMatrix(double* p, int n) : diag(p), next(p + n), face(p + 2 * n), cell(p + 3 * n) {}
};

// Reused buffers of the cell kernel (no allocation per cell once they have grown).
struct CellWorkspace {
  Eigen::Matrix3Xd X;                // the cell's vertex positions (columns), gathered once
  std::vector<int> face_local;       // a face's corners as indices into cell_vertices(c)
  std::vector<double> face_buffer;   // fine stiffness and mass of a face with more corners than the fixed sizes
  std::vector<double> hs, hm;        // per cell: couplings of the vertices with the cell point
};

// The fine mass of one face from its sub-tetrahedra's volumes, F.next[i] = vol_i / 20 on entry:
// the linear tetrahedron's mass is vol/20 (I + 1 1^T), and the tetrahedron of face edge i couples
// corners i and i + 1. N > 0: the corner count n at compile time.
template <int N>
void face_mass(int n_dyn, FaceMatrix& F) {
  const int n = N > 0 ? N : n_dyn;
  const double* d = F.next;
  double total = 0;
  for (int i = 0; i < n; ++i) {
    const double s = d[i == 0 ? n - 1 : i - 1] + d[i];  // the corner's two sub-tetrahedra
    F.diag[i] = 2 * s, F.face[i] = s, F.cell[i] = s;
    total += d[i];
  }
  F.ff = 2 * total, F.fc = total, F.cc = 2 * total;
}

// Folds the face point (weights w over the corners) into the corners of the fine stiffness Fs and
// mass Fm and adds the corner blocks to the coarse m x m matrices S and M (column-major); the cell
// point's couplings go to hs, hm (per cell vertex) and as, am. N > 0: n at compile time.
template <int N>
void fold_face(const FaceMatrix& Fs, const FaceMatrix& Fm, const double* w, const int* local, int n_dyn, long m,
               double* S, double* M, double* hs, double* hm, double& as, double& am) {
  const int n = N > 0 ? N : n_dyn;
  for (int b = 0; b < n; ++b) {
    const double wb = w[b];
    const double ts = Fs.face[b] + wb * Fs.ff, tm = Fm.face[b] + wb * Fm.ff;  // (F P)(face point, b)
    const long col = long(local[b]) * m;
    double *os = S + col, *om = M + col;
    for (int a = 0; a < n; ++a) {
      const int la = local[a];
      os[la] += w[a] * ts + Fs.face[a] * wb;
      om[la] += w[a] * tm + Fm.face[a] * wb;
    }
    os[local[b]] += Fs.diag[b];
    om[local[b]] += Fm.diag[b];
    const int b1 = b + 1 == n ? 0 : b + 1;
    os[local[b1]] += Fs.next[b];
    om[local[b1]] += Fm.next[b];
    S[local[b] + long(local[b1]) * m] += Fs.next[b];
    M[local[b] + long(local[b1]) * m] += Fm.next[b];
    hs[local[b]] += Fs.cell[b] + wb * Fs.fc;
    hm[local[b]] += Fm.cell[b] + wb * Fm.fc;
  }
  as += Fs.cc;
  am += Fm.cc;
}

// C += h w^T + w h^T + alpha w w^T for C = S and C = M: the cell point's row of P_c is w, so the
// fine couplings h (vertex, cell point) and alpha (cell point, cell point) become coarse ones.
void add_cell_point(const double* hs, double as, const double* hm, double am, std::span<const double> w,
                    long m, double* S, double* M) {
  for (long j = 0; j < m; ++j) {
    double *cs = S + j * m, *cm = M + j * m;
    const double wj = w[j], hsj = hs[j], hmj = hm[j], asj = as * wj, amj = am * wj;
    for (long i = 0; i < m; ++i) {
      cs[i] += hs[i] * wj + w[i] * hsj + w[i] * asj;
      cm[i] += hm[i] * wj + w[i] * hmj + w[i] * amj;
    }
  }
}

// One face of the cell, half-face hf with corners `local` (indices into the cell's vertices X)
// and face point xf, its sub-tetrahedra from t on: their 4 x 4 stiffness and mass accumulated into
// the face's fine matrices, which are folded into S, M (m x m) and the cell-point couplings hs, hm,
// as, am. Per sub-tetrahedron the six gradient products (scaled hat gradients by cross products)
// give the off-diagonal stiffness and the zero row sums its diagonal; the mass needs only the
// volume. N > 0: n at compile time, the fine matrices on the stack.
template <int N>
void add_face(const VolumeRefinement& refinement, int hf, int n_dyn, const int* local, const Eigen::Matrix3Xd& X,
              const Eigen::Vector3d& xf, const Eigen::Vector3d& xc, int t, const double* w, long m, double* S,
              double* M, CellWorkspace& ws, double& as, double& am) {
  const int n = N > 0 ? N : n_dyn;
  double stack[N > 0 ? 8 * N : 1];
  double* buffer = stack;
  if constexpr (N == 0) {
    if (ws.face_buffer.size() < 8 * size_t(n)) ws.face_buffer.resize(8 * size_t(n));
    buffer = ws.face_buffer.data();
  }
  FaceMatrix Fs(buffer, n), Fm(buffer + 4 * n, n);
  std::fill(buffer, buffer + 4 * n, 0.0);  // Fs accumulates; face_mass() writes every entry of Fm
  double *diag = Fs.diag, *next = Fs.next, *fp = Fs.face, *cp = Fs.cell;
  double ff = 0, fc = 0, cc = 0;
  for (int i = 0; i < n; ++i, ++t) {
    // Outward order: half-face 2f runs along the face, 2f+1 against it.
    int ia = i, ib = i + 1 == n ? 0 : i + 1;
    if (hf & 1) std::swap(ia, ib);
    const Eigen::Vector3d pa = X.col(local[ia]);
    const Eigen::Vector3d e1 = X.col(local[ib]) - pa, e2 = xf - pa, e3 = xc - pa;
    const Eigen::Vector3d c23 = e2.cross(e3), c31 = e3.cross(e1), c12 = e1.cross(e2);
    const double det = e1.dot(c23), vol = std::abs(det) / 6.0;
    Fm.next[i] = vol / 20.0;
    if (refinement.tets[t] == SubTet::Degenerate) continue;
    // Hat gradients: rows of [e1 e2 e3]^-1 (tet_hat_gradients), scaled by det; K = s G G^T.
    const Eigen::Vector3d g0 = -(c23 + c31 + c12);
    const double s = -vol / (det * det);
    const double k01 = s * g0.dot(c23), k02 = s * g0.dot(c31), k03 = s * g0.dot(c12);
    const double k12 = s * c23.dot(c31), k13 = s * c23.dot(c12), k23 = s * c31.dot(c12);
    diag[ia] -= k01 + k02 + k03, diag[ib] -= k01 + k12 + k13, next[i] += k01;
    fp[ia] += k02, fp[ib] += k12, cp[ia] += k03, cp[ib] += k13;
    ff -= k02 + k12 + k23, fc += k23, cc -= k03 + k13 + k23;
  }
  Fs.ff = ff, Fs.fc = fc, Fs.cc = cc;
  face_mass<N>(n, Fm);
  fold_face<N>(Fs, Fm, w, local, n, m, S, M, ws.hs.data(), ws.hm.data(), as, am);
}

// P_c^T S^tet P_c and P_c^T M^tet P_c without the cell's fine matrices: per face, the
// sub-tetrahedra's 4 x 4 stiffness and mass over [face corners, face point, cell point]
// (add_face()); the face point is folded into the corners by its weights once per face and the
// corner block added to the m x m result, the cell point's couplings (row w of P_c) once per cell.
void cell_kernel(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c, Eigen::MatrixXd& S,
                 Eigen::MatrixXd& M, CellWorkspace& ws) {
  const auto verts = mesh.cell_vertices(c);
  const auto cell = mesh.cell(c);
  const int m = int(verts.size()), nf = int(cell.size());
  ws.X.resize(3, m);
  for (int i = 0; i < m; ++i) ws.X.col(i) = mesh.positions().row(verts[i]).transpose();
  S.setZero(m, m);
  M.setZero(m, m);
  ws.hs.assign(m, 0.0);
  ws.hm.assign(m, 0.0);
  double alpha_s = 0, alpha_m = 0;
  const Eigen::Vector3d xc = refinement.cell_points.row(c).transpose();
  int t = refinement.tet_offsets[c];
  for (int k = 0; k < nf; ++k) {
    const int hf = cell[k], f = hf / 2;
    const auto face = mesh.face(f);
    const int n = int(face.size());
    ws.face_local.resize(n);
    for (int i = 0; i < n; ++i) ws.face_local[i] = local_index(verts, face[i]);
    const Eigen::Vector3d xf = refinement.face_points.row(f).transpose();
    const double* w = refinement.weights_of_face(mesh, f).data();
    if (n == 4)
      add_face<4>(refinement, hf, n, ws.face_local.data(), ws.X, xf, xc, t, w, m, S.data(), M.data(), ws, alpha_s, alpha_m);
    else if (n == 3)
      add_face<3>(refinement, hf, n, ws.face_local.data(), ws.X, xf, xc, t, w, m, S.data(), M.data(), ws, alpha_s, alpha_m);
    else
      add_face<0>(refinement, hf, n, ws.face_local.data(), ws.X, xf, xc, t, w, m, S.data(), M.data(), ws, alpha_s, alpha_m);
    t += n;
  }
  add_cell_point(ws.hs.data(), alpha_s, ws.hm.data(), alpha_m, refinement.weights_of_cell(c), m, S.data(), M.data());
}

}  // namespace
}  // namespace volume_laplacian_detail

void cell_matrices(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c, Eigen::MatrixXd* S,
                   Eigen::MatrixXd* M) {
  volume_laplacian_detail::CellWorkspace ws;
  Eigen::MatrixXd Sc, Mc;
  volume_laplacian_detail::cell_kernel(mesh, refinement, c, Sc, Mc, ws);
  if (S) *S = std::move(Sc);
  if (M) *M = std::move(Mc);
}

VolumeLaplacian assemble_volume_laplacian(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                          const SparseMatrix* pattern, int threads) {
  using namespace volume_laplacian_detail;
  VolumeLaplacian L;
  L.quality = refinement.quality;
  if (pattern) {
    L.S = *pattern;
    L.S.coeffs().setZero();
  } else {
    L.S = cell_pattern(mesh);  // values already zero
  }
  L.M = L.S;
  const int nC = mesh.n_cells(), nV = mesh.n_vertices();
  const int* outer = L.S.outerIndexPtr();
  const int* inner = L.S.innerIndexPtr();
  double* sv = L.S.valuePtr();
  double* mv = L.M.valuePtr();
  // Adds cell c's local matrices (column-major m x m) to the columns v0 <= v < v1. The cell's
  // vertices are ascending, as are a column's rows: one forward walk per column.
  auto scatter = [&](int c, const double* Sc, const double* Mc, int v0, int v1) {
    const auto verts = mesh.cell_vertices(c);
    const int m = int(verts.size());
    for (int b = 0; b < m; ++b) {
      if (verts[b] < v0 || verts[b] >= v1) continue;
      int pos = outer[verts[b]];
      for (int a = 0; a < m; ++a) {
        while (inner[pos] != verts[a]) ++pos;
        sv[pos] += Sc[a + b * m];
        mv[pos] += Mc[a + b * m];
      }
    }
  };
  const int T = std::min(resolve_threads(threads), std::max(1, nC / 2048));
  if (T == 1) {
    Eigen::MatrixXd Sc, Mc;
    CellWorkspace ws;
    for (int c = 0; c < nC; ++c) {
      cell_kernel(mesh, refinement, c, Sc, Mc, ws);
      scatter(c, Sc.data(), Mc.data(), 0, nV);
    }
  } else {
    // Blocks of cells: the threads compute the block's local matrices (cells split in ranges),
    // then add them with each thread owning a range of columns, visiting the cells in order: every
    // entry receives its terms in cell order, as with one thread (bitwise identical results).
    const int block = 4096;
    std::vector<size_t> offset(size_t(block) + 1);
    std::vector<double> local;
    std::vector<CellWorkspace> ws(T);
    for (int c0 = 0; c0 < nC; c0 += block) {
      const int c1 = std::min(nC, c0 + block);
      for (int c = c0; c < c1; ++c) {
        const size_t m = mesh.cell_vertices(c).size();
        offset[c - c0 + 1] = offset[c - c0] + 2 * m * m;
      }
      local.resize(offset[c1 - c0]);
      run_on_threads(T, [&](int t) {
        Eigen::MatrixXd Sc, Mc;
        for (int c = c0 + (c1 - c0) * t / T; c < c0 + (c1 - c0) * (t + 1) / T; ++c) {
          cell_kernel(mesh, refinement, c, Sc, Mc, ws[t]);
          double* out = local.data() + offset[c - c0];
          std::copy(Sc.data(), Sc.data() + Sc.size(), out);
          std::copy(Mc.data(), Mc.data() + Mc.size(), out + Sc.size());
        }
      });
      run_on_threads(T, [&](int t) {
        const int v0 = int(long(nV) * t / T), v1 = int(long(nV) * (t + 1) / T);
        for (int c = c0; c < c1; ++c) {
          const size_t m = mesh.cell_vertices(c).size();
          const double* in = local.data() + offset[c - c0];
          scatter(c, in, in + m * m, v0, v1);
        }
      });
    }
  }
  L.M_lumped = L.M * Eigen::VectorXd::Ones(nV);
  return L;
}

}  // namespace polydec
