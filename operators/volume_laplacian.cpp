// operators/volume_laplacian.cpp — cell-by-cell assembly of the polyhedral stiffness and mass.
#include "polydec/operators/volume_laplacian.h"

#include <algorithm>
#include <vector>

#include "polydec/dec/volume_whitney.h"

namespace polydec {

namespace volume_laplacian_detail {
namespace {

int local_index(std::span<const int> verts, int v) {
  return int(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin());
}

// Adds `value` at (row, col) of a matrix whose pattern contains it.
void add_to(SparseMatrix& A, int row, int col, double value) {
  const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[col];
  const int* end = A.innerIndexPtr() + A.outerIndexPtr()[col + 1];
  A.valuePtr()[std::lower_bound(begin, end, row) - A.innerIndexPtr()] += value;
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
  std::vector<int> outer(nV + 1, 0), inner, column;
  for (int v = 0; v < nV; ++v) {
    column.clear();
    for (int k = count[v]; k < count[v + 1]; ++k) {
      const auto cv = mesh.cell_vertices(cells[k]);
      column.insert(column.end(), cv.begin(), cv.end());
    }
    std::sort(column.begin(), column.end());
    column.erase(std::unique(column.begin(), column.end()), column.end());
    inner.insert(inner.end(), column.begin(), column.end());
    outer[v + 1] = int(inner.size());
  }
  std::vector<double> values(inner.size(), 0.0);
  return Eigen::Map<const SparseMatrix>(nV, nV, long(inner.size()), outer.data(), inner.data(),
                                        values.data());
}

void cell_matrices(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c, Eigen::MatrixXd* S,
                   Eigen::MatrixXd* M) {
  using namespace volume_laplacian_detail;
  const auto verts = mesh.cell_vertices(c);
  const auto cell = mesh.cell(c);
  const int m = int(verts.size()), nf = int(cell.size()), r = m + nf + 1;
  // Local prolongation: cell vertices, then the cell's face points (half-face order), then the cell point.
  Eigen::MatrixXd Pc = Eigen::MatrixXd::Zero(r, m);
  Pc.topRows(m).setIdentity();
  for (int k = 0; k < nf; ++k) {
    const int f = cell[k] / 2;
    const auto face = mesh.face(f);
    const auto w = refinement.weights_of_face(mesh, f);
    for (size_t i = 0; i < face.size(); ++i) Pc(m + k, local_index(verts, face[i])) = w[i];
  }
  const auto wc = refinement.weights_of_cell(c);
  for (int i = 0; i < m; ++i) Pc(m + nf, i) = wc[i];

  Eigen::MatrixXd As = Eigen::MatrixXd::Zero(r, r), Am = Eigen::MatrixXd::Zero(r, r);
  const Eigen::Vector3d xc = refinement.cell_points.row(c).transpose();
  int t = refinement.tet_offsets[c];
  for (int k = 0; k < nf; ++k) {
    const int hf = cell[k];
    const auto face = mesh.face(hf / 2);
    const int n = int(face.size());
    const Eigen::Vector3d xf = refinement.face_points.row(hf / 2).transpose();
    for (int i = 0; i < n; ++i, ++t) {
      // Outward order: half-face 2f runs along the face, 2f+1 against it.
      int a = face[i], b = face[(i + 1) % n];
      if (hf & 1) std::swap(a, b);
      const int loc[4] = {local_index(verts, a), local_index(verts, b), m + k, m + nf};
      const Eigen::Vector3d pa = mesh.position(a), pb = mesh.position(b);
      if (S && refinement.tets[t] != SubTet::Degenerate) {
        const Eigen::Matrix4d K = tet_stiffness(pa, pb, xf, xc);
        for (int p = 0; p < 4; ++p)
          for (int q = 0; q < 4; ++q) As(loc[p], loc[q]) += K(p, q);
      }
      if (M) {
        const Eigen::Matrix4d K = tet_whitney0_mass(pa, pb, xf, xc);
        for (int p = 0; p < 4; ++p)
          for (int q = 0; q < 4; ++q) Am(loc[p], loc[q]) += K(p, q);
      }
    }
  }
  if (S) *S = Pc.transpose() * As * Pc;
  if (M) *M = Pc.transpose() * Am * Pc;
}

VolumeLaplacian assemble_volume_laplacian(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                          const SparseMatrix* pattern) {
  using namespace volume_laplacian_detail;
  VolumeLaplacian L;
  L.quality = refinement.quality;
  L.S = pattern ? *pattern : cell_pattern(mesh);
  L.S.coeffs().setZero();
  L.M = L.S;
  Eigen::MatrixXd Sc, Mc;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    cell_matrices(mesh, refinement, c, &Sc, &Mc);
    const auto verts = mesh.cell_vertices(c);
    const int m = int(verts.size());
    for (int b = 0; b < m; ++b)
      for (int a = 0; a < m; ++a) {
        add_to(L.S, verts[a], verts[b], Sc(a, b));
        add_to(L.M, verts[a], verts[b], Mc(a, b));
      }
  }
  L.M_lumped = L.M * Eigen::VectorXd::Ones(mesh.n_vertices());
  return L;
}

}  // namespace polydec
