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
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct CellWorkspace {
  RowMatrix W;             // (nf + 1) x m: face rows and the cell row of the local prolongation
  Eigen::Matrix3Xd X;      // the cell's vertex positions (columns), gathered once
  Eigen::MatrixXd As, Am;  // r x r fine matrices over [cell vertices, face points, cell point]
  Eigen::MatrixXd T;       // r x m
  std::vector<int> face_local;
};

// P_c^T A P_c with P_c = [I_m; W]: T = A [I; W], result = T_top + W^T T_bottom, by loops over
// the non-zero weights (a face row has only the face's corners; the sizes are too small for GEMM).
void coarsen(const Eigen::MatrixXd& A, const RowMatrix& W, Eigen::MatrixXd& T, Eigen::MatrixXd& out) {
  const long m = W.cols(), k = W.rows(), r = A.rows();
  T = A.leftCols(m);
  for (long q = 0; q < k; ++q)
    for (long j = 0; j < m; ++j) {
      const double w = W(q, j);
      if (w == 0) continue;
      const double* a = A.data() + (m + q) * r;
      double* t = T.data() + j * r;
      for (long i = 0; i < r; ++i) t[i] += w * a[i];
    }
  out = T.topRows(m);
  for (long b = 0; b < m; ++b) {
    const double* t = T.data() + b * r + m;
    double* o = out.data() + b * m;
    for (long q = 0; q < k; ++q) {
      const double tb = t[q];
      const double* wq = W.data() + q * m;
      for (long a = 0; a < m; ++a) o[a] += wq[a] * tb;
    }
  }
}

void cell_kernel(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c, Eigen::MatrixXd* S,
                 Eigen::MatrixXd* M, CellWorkspace& ws) {
  const auto verts = mesh.cell_vertices(c);
  const auto cell = mesh.cell(c);
  const int m = int(verts.size()), nf = int(cell.size()), r = m + nf + 1;
  ws.W.setZero(nf + 1, m);
  ws.X.resize(3, m);
  for (int i = 0; i < m; ++i) ws.X.col(i) = mesh.positions().row(verts[i]).transpose();
  const auto wc = refinement.weights_of_cell(c);
  for (int i = 0; i < m; ++i) ws.W(nf, i) = wc[i];
  if (S) ws.As.setZero(r, r);
  if (M) ws.Am.setZero(r, r);
  const Eigen::Vector3d xc = refinement.cell_points.row(c).transpose();
  int t = refinement.tet_offsets[c];
  for (int k = 0; k < nf; ++k) {
    const int hf = cell[k], f = hf / 2;
    const auto face = mesh.face(f);
    const int n = int(face.size());
    const auto wf = refinement.weights_of_face(mesh, f);
    ws.face_local.resize(n);
    for (int i = 0; i < n; ++i) {
      ws.face_local[i] = local_index(verts, face[i]);
      ws.W(k, ws.face_local[i]) = wf[i];
    }
    const Eigen::Vector3d xf = refinement.face_points.row(f).transpose();
    for (int i = 0; i < n; ++i, ++t) {
      // Outward order: half-face 2f runs along the face, 2f+1 against it.
      int ia = i, ib = (i + 1) % n;
      if (hf & 1) std::swap(ia, ib);
      const int loc[4] = {ws.face_local[ia], ws.face_local[ib], m + k, m + nf};
      const Eigen::Vector3d pa = ws.X.col(loc[0]);
      const Eigen::Vector3d e1 = ws.X.col(loc[1]) - pa, e2 = xf - pa, e3 = xc - pa;
      const Eigen::Vector3d c23 = e2.cross(e3), c31 = e3.cross(e1), c12 = e1.cross(e2);
      const double det = e1.dot(c23), vol = std::abs(det) / 6.0;
      if (M) {
        const double d = vol / 20.0;
        for (int p = 0; p < 4; ++p)
          for (int q = 0; q < 4; ++q) ws.Am(loc[p], loc[q]) += p == q ? 2 * d : d;
      }
      if (S && refinement.tets[t] != SubTet::Degenerate) {
        // Hat gradients: rows of [e1 e2 e3]^-1 (tet_hat_gradients), scaled by det.
        Eigen::Matrix<double, 3, 4> G;
        G.col(1) = c23;
        G.col(2) = c31;
        G.col(3) = c12;
        G.col(0) = -(c23 + c31 + c12);
        const Eigen::Matrix4d K = (-vol / (det * det)) * (G.transpose() * G);
        for (int p = 0; p < 4; ++p)
          for (int q = 0; q < 4; ++q) ws.As(loc[p], loc[q]) += K(p, q);
      }
    }
  }
  if (S) coarsen(ws.As, ws.W, ws.T, *S);
  if (M) coarsen(ws.Am, ws.W, ws.T, *M);
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
