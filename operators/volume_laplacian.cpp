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
  std::vector<double> values(inner.size(), 0.0);
  return Eigen::Map<const SparseMatrix>(nV, nV, long(inner.size()), outer.data(), inner.data(),
                                        values.data());
}

namespace volume_laplacian_detail {
namespace {

// Reused buffers of the cell kernel (no allocation per cell once they have grown).
struct CellWorkspace {
  Eigen::Matrix3Xd X;           // the cell's vertex positions (columns), gathered once
  std::vector<int> face_local;  // a face's corners as indices into cell_vertices(c)
  std::vector<double> Fs, Fm;   // per face: fine (n + 2)^2 matrices over [corners, face point, cell point]
  std::vector<double> hs, hm;   // per cell: couplings of the vertices with the cell point
};

// Folds the face point (index n of the (n + 2)^2 column-major F, weights w over the corners) into
// the corners and adds the corner block to the coarse m x m matrix C; the cell point's couplings
// (index n + 1) go to h (per cell vertex) and alpha.
void fold_face(const std::vector<double>& F, int n, std::span<const double> w, const std::vector<int>& local,
               Eigen::MatrixXd& C, std::vector<double>& h, double& alpha) {
  const int p = n + 2;
  const double* fn = F.data() + n * p;  // column of the face point
  const double* fc = F.data() + (n + 1) * p;  // column of the cell point
  const double ff = fn[n];
  for (int b = 0; b < n; ++b) {
    const double* col = F.data() + b * p;
    const double tb = fn[b] + w[b] * ff;  // (F P)(face point, b) with the face point folded
    double* out = C.data() + long(local[b]) * C.rows();
    for (int a = 0; a < n; ++a) out[local[a]] += col[a] + w[a] * tb + fn[a] * w[b];
    h[local[b]] += fc[b] + w[b] * fc[n];
  }
  alpha += fc[n + 1];
}

// C += h w^T + w h^T + alpha w w^T: the cell point's row of P_c is w, so the fine couplings h (vertex,
// cell point) and alpha (cell point, cell point) become coarse ones.
void add_cell_point(const std::vector<double>& h, double alpha, std::span<const double> w, Eigen::MatrixXd& C) {
  const long m = C.rows();
  for (long j = 0; j < m; ++j) {
    double* col = C.data() + j * m;
    const double hj = h[j], wj = w[j], awj = alpha * wj;
    for (long i = 0; i < m; ++i) col[i] += h[i] * wj + w[i] * hj + w[i] * awj;
  }
}

// P_c^T S^tet P_c and P_c^T M^tet P_c without the cell's fine matrices: per face, the
// sub-tetrahedra's 4 x 4 stiffness and mass over [face corners, face point, cell point]; the face
// point is folded into the corners by its weights once per face and the corner block added to the
// m x m result, the cell point's couplings (row w of P_c) once per cell.
void cell_kernel(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c, Eigen::MatrixXd* S,
                 Eigen::MatrixXd* M, CellWorkspace& ws) {
  const auto verts = mesh.cell_vertices(c);
  const auto cell = mesh.cell(c);
  const int m = int(verts.size()), nf = int(cell.size());
  ws.X.resize(3, m);
  for (int i = 0; i < m; ++i) ws.X.col(i) = mesh.positions().row(verts[i]).transpose();
  double alpha_s = 0, alpha_m = 0;
  if (S) {
    S->setZero(m, m);
    ws.hs.assign(m, 0.0);
  }
  if (M) {
    M->setZero(m, m);
    ws.hm.assign(m, 0.0);
  }
  const Eigen::Vector3d xc = refinement.cell_points.row(c).transpose();
  int t = refinement.tet_offsets[c];
  for (int k = 0; k < nf; ++k) {
    const int hf = cell[k], f = hf / 2;
    const auto face = mesh.face(f);
    const int n = int(face.size()), p = n + 2;
    const auto wf = refinement.weights_of_face(mesh, f);
    ws.face_local.resize(n);
    for (int i = 0; i < n; ++i) ws.face_local[i] = local_index(verts, face[i]);
    if (S) ws.Fs.assign(size_t(p) * p, 0.0);
    if (M) ws.Fm.assign(size_t(p) * p, 0.0);
    const Eigen::Vector3d xf = refinement.face_points.row(f).transpose();
    for (int i = 0; i < n; ++i, ++t) {
      // Outward order: half-face 2f runs along the face, 2f+1 against it.
      int ia = i, ib = (i + 1) % n;
      if (hf & 1) std::swap(ia, ib);
      const int loc[4] = {ia, ib, n, n + 1};
      const Eigen::Vector3d pa = ws.X.col(ws.face_local[ia]);
      const Eigen::Vector3d e1 = ws.X.col(ws.face_local[ib]) - pa, e2 = xf - pa, e3 = xc - pa;
      const Eigen::Vector3d c23 = e2.cross(e3), c31 = e3.cross(e1), c12 = e1.cross(e2);
      const double det = e1.dot(c23), vol = std::abs(det) / 6.0;
      if (M) {
        const double d = vol / 20.0;
        for (int b = 0; b < 4; ++b)
          for (int a = 0; a < 4; ++a) ws.Fm[loc[a] + loc[b] * p] += a == b ? 2 * d : d;
      }
      if (S && refinement.tets[t] != SubTet::Degenerate) {
        // Hat gradients: rows of [e1 e2 e3]^-1 (tet_hat_gradients), scaled by det.
        const Eigen::Vector3d G[4] = {-(c23 + c31 + c12), c23, c31, c12};
        const double coef = -vol / (det * det);
        for (int b = 0; b < 4; ++b) {
          ws.Fs[loc[b] * (p + 1)] += coef * G[b].squaredNorm();
          for (int a = 0; a < b; ++a) {
            const double v = coef * G[a].dot(G[b]);
            ws.Fs[loc[a] + loc[b] * p] += v;
            ws.Fs[loc[b] + loc[a] * p] += v;
          }
        }
      }
    }
    if (S) fold_face(ws.Fs, n, wf, ws.face_local, *S, ws.hs, alpha_s);
    if (M) fold_face(ws.Fm, n, wf, ws.face_local, *M, ws.hm, alpha_m);
  }
  const auto wc = refinement.weights_of_cell(c);
  if (S) add_cell_point(ws.hs, alpha_s, wc, *S);
  if (M) add_cell_point(ws.hm, alpha_m, wc, *M);
}

}  // namespace
}  // namespace volume_laplacian_detail

void cell_matrices(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c, Eigen::MatrixXd* S,
                   Eigen::MatrixXd* M) {
  volume_laplacian_detail::CellWorkspace ws;
  volume_laplacian_detail::cell_kernel(mesh, refinement, c, S, M, ws);
}

VolumeLaplacian assemble_volume_laplacian(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                          const SparseMatrix* pattern, int threads) {
  using namespace volume_laplacian_detail;
  VolumeLaplacian L;
  L.quality = refinement.quality;
  L.S = pattern ? *pattern : cell_pattern(mesh);
  L.S.coeffs().setZero();
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
      cell_kernel(mesh, refinement, c, &Sc, &Mc, ws);
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
          cell_kernel(mesh, refinement, c, &Sc, &Mc, ws[t]);
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
