// dec/surface/form_span.cpp — reduced bases of the Whitney 1- and 2-forms by blockwise pivoted QR.
#include "polydec/dec/surface/form_span.h"

#include <Eigen/QR>
#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "polydec/dec/detail/union_find.h"
#include "polydec/dec/surface/prolongation.h"

namespace polydec {

FormSpan form_span(const Mesh& mesh, const Refinement& refinement, const CoarseComplex& complex, int degree,
                   double tolerance) {
  check_refinement(mesh, refinement, "form_span");
  if (degree != 1 && degree != 2) throw std::invalid_argument("form_span: degree must be 1 or 2");
  FormSpan span;
  span.degree = degree;
  span.tolerance = tolerance;
  const int nf = mesh.n_faces(), ne = mesh.n_edges();
  const int n_cells = degree == 1 ? complex.n_pairs() : complex.n_triples();
  auto face_cells = [&](int f) { return degree == 1 ? complex.face_pairs(f) : complex.face_triples(f); };
  // Candidates: for k = 1 the diagonals (every mesh edge is kept: its P1 row is a unit row, so
  // edges are independent of everything else and their columns drop out of the rank question).
  std::vector<unsigned char> candidate(n_cells, 1), selected(n_cells, 0);
  if (degree == 1)
    for (int p = 0; p < n_cells; ++p)
      if (complex.is_edge(p)) candidate[p] = 0, selected[p] = 1;

  // Faces linked by a shared candidate cell form one block.
  std::vector<int> parent(nf), owner(n_cells, -1);
  std::iota(parent.begin(), parent.end(), 0);
  for (int f = 0; f < nf; ++f)
    for (int c : face_cells(f)) {
      if (!candidate[c]) continue;
      if (owner[c] < 0)
        owner[c] = f;
      else
        parent[find_root(parent, f)] = find_root(parent, owner[c]);
    }
  std::vector<std::vector<int>> blocks(nf);
  for (int f = 0; f < nf; ++f) blocks[find_root(parent, f)].push_back(f);

  // The rows of P_k on the refined cells interior to the faces: spokes (k = 1), triangles (k = 2).
  const Eigen::SparseMatrix<double> P =
      degree == 1 ? prolongation1(mesh, refinement, complex) : prolongation2(mesh, refinement, complex);
  const int row0 = degree == 1 ? ne : 0;
  std::vector<int> local_row(P.rows(), -1);
  std::vector<int> cols;
  for (const auto& block : blocks) {
    if (block.empty()) continue;
    cols.clear();
    int n_rows = 0;
    for (int f : block) {
      const int h0 = mesh.face_offsets()[f], h1 = mesh.face_offsets()[f + 1];
      for (int h = h0; h < h1; ++h) {
        // Only refined cells that carry mass count: a fan triangle that is not degenerate
        // (k = 2), a spoke with at least one such triangle beside it (k = 1).
        const int prev = h == h0 ? h1 - 1 : h - 1;
        const bool massive = refinement.fan[h] != FanTriangle::Degenerate ||
                             (degree == 1 && refinement.fan[prev] != FanTriangle::Degenerate);
        if (massive) local_row[row0 + h] = n_rows++;
      }
      for (int c : face_cells(f))
        if (candidate[c]) cols.push_back(c);
    }
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    if (!cols.empty()) {
      Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n_rows, long(cols.size()));
      for (size_t j = 0; j < cols.size(); ++j)
        for (Eigen::SparseMatrix<double>::InnerIterator it(P, cols[j]); it; ++it)
          if (local_row[it.row()] >= 0) B(local_row[it.row()], long(j)) = it.value();
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(B);
      qr.setThreshold(tolerance);
      for (long r = 0; r < qr.rank(); ++r) selected[cols[qr.colsPermutation().indices()[r]]] = 1;
    }
    for (int f : block)
      for (int h = mesh.face_offsets()[f]; h < mesh.face_offsets()[f + 1]; ++h) local_row[row0 + h] = -1;
  }

  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < n_cells; ++c)
    if (selected[c]) {
      t.emplace_back(c, int(span.cells.size()), 1.0);
      span.cells.push_back(c);
    }
  span.R.resize(n_cells, long(span.cells.size()));
  span.R.setFromTriplets(t.begin(), t.end());
  return span;
}

}  // namespace polydec
