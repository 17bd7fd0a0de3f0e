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

// One face's fine matrix over [corners, face point, cell point] (symmetric): its sub-tetrahedra
// (a, b, face point, cell point) couple only a corner with itself, with its next corner, with the
// face point and with the cell point, and the two points with each other.
struct FaceMatrix {
  std::vector<double> diag, next, face, cell;  // (i, i), (i, i + 1 mod n), (i, face point), (i, cell point)
  double ff = 0, fc = 0, cc = 0;               // (face, face), (face, cell), (cell, cell)
  void reset(int n) {
    diag.assign(n, 0.0), next.assign(n, 0.0), face.assign(n, 0.0), cell.assign(n, 0.0);
    ff = fc = cc = 0;
  }
  // Adds the symmetric 4 x 4 K (upper triangle k01..k33) of the tetrahedron (corner ia, corner ib,
  // face point, cell point); e is the edge's index (ib = e + 1 mod n or the reverse).
  void add(int ia, int ib, int e, double k00, double k01, double k02, double k03, double k11, double k12,
           double k13, double k22, double k23, double k33) {
    diag[ia] += k00, diag[ib] += k11, next[e] += k01;
    face[ia] += k02, face[ib] += k12, cell[ia] += k03, cell[ib] += k13;
    ff += k22, fc += k23, cc += k33;
  }
};

// Reused buffers of the cell kernel (no allocation per cell once they have grown).
struct CellWorkspace {
  Eigen::Matrix3Xd X;           // the cell's vertex positions (columns), gathered once
  std::vector<int> face_local;  // a face's corners as indices into cell_vertices(c)
  FaceMatrix Fs, Fm;            // per face: fine stiffness and mass
  std::vector<double> hs, hm;   // per cell: couplings of the vertices with the cell point
};

// Folds the face point (weights w over the corners) into the corners and adds the corner block
// to the coarse m x m matrix C; the cell point's couplings go to h (per cell vertex) and alpha.
void fold_face(const FaceMatrix& F, std::span<const double> w, const std::vector<int>& local, Eigen::MatrixXd& C,
               std::vector<double>& h, double& alpha) {
  const int n = int(local.size());
  const long m = C.rows();
  double* c = C.data();
  for (int b = 0; b < n; ++b) {
    const double tb = F.face[b] + w[b] * F.ff;  // (F P)(face point, b) with the face point folded
    double* out = c + long(local[b]) * m;
    for (int a = 0; a < n; ++a) out[local[a]] += w[a] * tb + F.face[a] * w[b];
    out[local[b]] += F.diag[b];
    const int b1 = b + 1 == n ? 0 : b + 1;
    out[local[b1]] += F.next[b];
    c[local[b] + long(local[b1]) * m] += F.next[b];
    h[local[b]] += F.cell[b] + w[b] * F.fc;
  }
  alpha += F.cc;
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
    const int n = int(face.size());
    const auto wf = refinement.weights_of_face(mesh, f);
    ws.face_local.resize(n);
    for (int i = 0; i < n; ++i) ws.face_local[i] = local_index(verts, face[i]);
    if (S) ws.Fs.reset(n);
    if (M) ws.Fm.reset(n);
    const Eigen::Vector3d xf = refinement.face_points.row(f).transpose();
    for (int i = 0; i < n; ++i, ++t) {
      // Outward order: half-face 2f runs along the face, 2f+1 against it.
      int ia = i, ib = i + 1 == n ? 0 : i + 1;
      if (hf & 1) std::swap(ia, ib);
      const Eigen::Vector3d pa = ws.X.col(ws.face_local[ia]);
      const Eigen::Vector3d e1 = ws.X.col(ws.face_local[ib]) - pa, e2 = xf - pa, e3 = xc - pa;
      const Eigen::Vector3d c23 = e2.cross(e3), c31 = e3.cross(e1), c12 = e1.cross(e2);
      const double det = e1.dot(c23), vol = std::abs(det) / 6.0;
      if (M) {
        const double d = vol / 20.0, d2 = 2 * d;  // vol/20 (I + 1 1^T)
        ws.Fm.add(ia, ib, i, d2, d, d, d, d2, d, d, d2, d, d2);
      }
      if (S && refinement.tets[t] != SubTet::Degenerate) {
        // Hat gradients: rows of [e1 e2 e3]^-1 (tet_hat_gradients), scaled by det.
        const Eigen::Vector3d g0 = -(c23 + c31 + c12);
        const double s = -vol / (det * det);
        ws.Fs.add(ia, ib, i, s * g0.squaredNorm(), s * g0.dot(c23), s * g0.dot(c31), s * g0.dot(c12),
                  s * c23.squaredNorm(), s * c23.dot(c31), s * c23.dot(c12), s * c31.squaredNorm(),
                  s * c31.dot(c12), s * c12.squaredNorm());
      }
    }
    if (S) fold_face(ws.Fs, wf, ws.face_local, *S, ws.hs, alpha_s);
    if (M) fold_face(ws.Fm, wf, ws.face_local, *M, ws.hm, alpha_m);
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
