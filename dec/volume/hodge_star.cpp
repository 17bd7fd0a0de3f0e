// dec/volume/hodge_star.cpp — P0..P3 by determinants of P rows, refined Whitney stars of the
// sub-tetrahedra, coarse stars and reduced bases.
#include "polydec/dec/volume/hodge_star.h"

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "polydec/dec/detail/drop_zeros.h"
#include "polydec/dec/volume/mesh_complex.h"
#include "polydec/dec/volume/prolongation.h"
#include "polydec/dec/volume/whitney.h"

namespace polydec {

namespace volume_hodge_star_detail {
namespace {

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

double row_entry(const RowMajor& P, int r, int col) {
  const int* b = P.innerIndexPtr() + P.outerIndexPtr()[r];
  const int* e = P.innerIndexPtr() + P.outerIndexPtr()[r + 1];
  const int* it = std::lower_bound(b, e, col);
  return it != e && *it == col ? P.valuePtr()[it - P.innerIndexPtr()] : 0.0;
}

// Appends the entries of row `row` of P_k for the sorted refined simplex s (k + 1 vertices).
void prolong_row(const RowMajor& P0, const SimplexComplex3& coarse, std::span<const int> s, int nV, int row,
                 std::vector<Eigen::Triplet<double>>& out) {
  const int n = int(s.size());
  std::vector<int> forced, candidates;
  int n_weight_rows = 0;
  for (int r : s) {
    if (r < nV) {
      forced.push_back(r);
    } else {
      ++n_weight_rows;
      for (int p = P0.outerIndexPtr()[r]; p < P0.outerIndexPtr()[r + 1]; ++p)
        candidates.push_back(P0.innerIndexPtr()[p]);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  candidates.erase(
      std::remove_if(candidates.begin(), candidates.end(),
                     [&](int v) { return std::find(forced.begin(), forced.end(), v) != forced.end(); }),
      candidates.end());
  const int nc = int(candidates.size());
  Eigen::Matrix4d A;
  auto emit = [&](std::vector<int> chosen) {
    chosen.insert(chosen.end(), forced.begin(), forced.end());
    std::sort(chosen.begin(), chosen.end());
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) A(a, b) = row_entry(P0, s[a], chosen[b]);
    const double det = A.topLeftCorner(n, n).determinant();
    if (det == 0.0) return;
    const int col = coarse.index(chosen);
    if (col < 0) throw std::logic_error("volume prolongation: coarse simplex missing");
    out.emplace_back(row, col, det);
  };
  if (n_weight_rows == 0) {
    emit({});
  } else if (n_weight_rows == 1) {
    for (int a = 0; a < nc; ++a) emit({candidates[a]});
  } else if (n_weight_rows == 2) {
    for (int a = 0; a < nc; ++a)
      for (int b = a + 1; b < nc; ++b) emit({candidates[a], candidates[b]});
  } else {
    throw std::logic_error("volume prolongation: refined simplex with more than two virtual points");
  }
}

}  // namespace
}  // namespace volume_hodge_star_detail

Eigen::SparseMatrix<double> volume_prolongation_k(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                                  const SimplexComplex3& coarse,
                                                  const SimplexComplex3& refined, int k) {
  check_refinement(mesh, refinement, "volume_prolongation_k");
  using namespace volume_hodge_star_detail;
  if (k < 0 || k > 3)
    throw std::invalid_argument("volume_prolongation_k: k = " + std::to_string(k) + " (0..3)");
  const RowMajor P0 = volume_prolongation(mesh, refinement);
  if (k == 0) return Eigen::SparseMatrix<double>(P0);
  const int nV = mesh.n_vertices();
  std::vector<Eigen::Triplet<double>> t;
  const int rows = refined.n_simplices(k);
  for (int r = 0; r < rows; ++r) {
    std::span<const int> s = k == 1   ? std::span<const int>(refined.pairs()[r])
                             : k == 2 ? std::span<const int>(refined.triples()[r])
                                      : std::span<const int>(refined.quads()[r]);
    prolong_row(P0, coarse, s, nV, r, t);
  }
  Eigen::SparseMatrix<double> P(rows, coarse.n_simplices(k));
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

Eigen::SparseMatrix<double> volume_refined_star(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                                const SimplexComplex3& refined, int k) {
  check_refinement(mesh, refinement, "volume_refined_star");
  if (k < 0 || k > 3)
    throw std::invalid_argument("volume_refined_star: k = " + std::to_string(k) + " (0..3)");
  std::vector<Eigen::Triplet<double>> t;
  for (const RefinedTet& tet : refined_tets(mesh, refinement)) {
    if (k > 0 && tet.quality == SubTet::Degenerate) continue;
    int v[4] = {tet.v[0], tet.v[1], tet.v[2], tet.v[3]};
    std::sort(v, v + 4);
    Eigen::Vector3d p[4];
    for (int a = 0; a < 4; ++a) p[a] = refined_position(mesh, refinement, v[a]);
    if (k == 0) {
      const Eigen::Matrix4d M = tet_whitney0_mass(p[0], p[1], p[2], p[3]);
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) t.emplace_back(v[a], v[b], M(a, b));
    } else if (k == 1) {
      const Matrix6d M = tet_whitney1_mass(p[0], p[1], p[2], p[3]);
      int id[6];
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) {
          const int e[2] = {v[a], v[b]};
          id[tet_local_edge(a, b)] = refined.index(e);
        }
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) t.emplace_back(id[a], id[b], M(a, b));
    } else if (k == 2) {
      const Eigen::Matrix4d M = tet_whitney2_mass(p[0], p[1], p[2], p[3]);
      int id[4];
      for (int missing = 0; missing < 4; ++missing) {
        int tri[3];
        for (int a = 0, l = 0; a < 4; ++a)
          if (a != missing) tri[l++] = v[a];
        id[tet_local_triangle_without(missing)] = refined.index(tri);
      }
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) t.emplace_back(id[a], id[b], M(a, b));
    } else {
      t.emplace_back(refined.index(v), refined.index(v), tet_whitney3_mass(p[0], p[1], p[2], p[3]));
    }
  }
  const int n = refined.n_simplices(k);
  Eigen::SparseMatrix<double> S(n, n);
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

VolumeDec volume_dec(const VolumeMesh& mesh, const VolumeRefinement& refinement, int max_degree) {
  return volume_dec(mesh, refinement, VolumeDecOptions{.max_degree = max_degree});
}

VolumeDec volume_dec(const VolumeMesh& mesh, const VolumeRefinement& refinement, const VolumeDecOptions& options) {
  check_refinement(mesh, refinement, "volume_dec");
  const int max_degree = options.max_degree;
  if (max_degree < 0 || max_degree > 3)
    throw std::invalid_argument("volume_dec: max_degree " + std::to_string(max_degree) + " (0..3)");
  check_length_powers(mesh, star_length_powers(max_degree));
  VolumeDec D;
  D.complex = options.complex;
  if (options.complex == DecComplex::Mesh) {
    D.max_degree = max_degree;
    D.refined = volume_refined_complex(mesh, refinement);
    VolumeMeshDec M = volume_mesh_dec(mesh, refinement, D.refined, max_degree, options.spoke_rule);
    for (int k = 0; k < 3; ++k) D.d[k].swap(M.d[k]);
    for (int k = 0; k < 4; ++k) D.P[k].swap(M.P[k]), D.star[k].swap(M.star[k]);
    for (int k = 0; k < 4; ++k) detail::drop_exact_zeros(D.star[k]);
    return D;
  }
  D.max_degree = max_degree;
  D.coarse = volume_coarse_complex(mesh, max_degree);
  D.refined = volume_refined_complex(mesh, refinement);
  for (int k = 0; k < max_degree; ++k) D.d[k] = D.coarse.d(k);
  for (int k = 0; k <= max_degree; ++k) {
    D.P[k] = volume_prolongation_k(mesh, refinement, D.coarse, D.refined, k);
    const Eigen::SparseMatrix<double> s = volume_refined_star(mesh, refinement, D.refined, k);
    D.star[k] = Eigen::SparseMatrix<double>(D.P[k].transpose() * s * D.P[k]);
    // The product keeps its structural entries, exact zeros among them (cells of a polyhedron
    // that no sub-tetrahedron joins): dropped, the values untouched.
    detail::drop_exact_zeros(D.star[k]);
  }
  return D;
}

FormSpan volume_form_span(const VolumeDec& dec, const VolumeMesh& mesh, const VolumeRefinement& refinement,
                          int degree, double tolerance, long max_entries) {
  check_refinement(mesh, refinement, "volume_form_span");
  if (degree < 1 || degree > dec.max_degree)
    throw std::invalid_argument("volume_form_span: degree " + std::to_string(degree) + " (1.." +
                                std::to_string(dec.max_degree) + " for this VolumeDec)");
  // Refined simplices with mass: those of the non-degenerate sub-tetrahedra.
  const Eigen::SparseMatrix<double> s = volume_refined_star(mesh, refinement, dec.refined, degree);
  std::vector<int> rows;
  for (int r = 0; r < s.outerSize(); ++r)
    if (s.outerIndexPtr()[r + 1] > s.outerIndexPtr()[r]) rows.push_back(r);
  const Eigen::SparseMatrix<double>& P = dec.P[degree];
  const long cols = P.cols();
  if (long(rows.size()) * cols > max_entries)
    throw std::invalid_argument("volume_form_span: " + std::to_string(rows.size()) + " x " +
                                std::to_string(cols) + " dense rank decision exceeds the limit of " +
                                std::to_string(max_entries) + " entries");
  std::vector<int> index(P.rows(), -1);
  for (size_t i = 0; i < rows.size(); ++i) index[rows[i]] = int(i);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(long(rows.size()), cols);
  for (int c = 0; c < cols; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(P, c); it; ++it)
      if (index[it.row()] >= 0) A(index[it.row()], c) = it.value();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  qr.setThreshold(tolerance);
  FormSpan span;
  span.degree = degree;
  span.tolerance = tolerance;
  const int rank = int(qr.rank());
  for (int j = 0; j < rank; ++j) span.cells.push_back(int(qr.colsPermutation().indices()(j)));
  std::sort(span.cells.begin(), span.cells.end());
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < rank; ++j) t.emplace_back(span.cells[j], j, 1.0);
  span.R.resize(cols, rank);
  span.R.setFromTriplets(t.begin(), t.end());
  return span;
}

}  // namespace polydec
