// dec/surface/hodge_star.cpp — refined Whitney stars and the coarse stars P_k^T star_k^f P_k, assembled
// face by face into a precomputed sparse pattern.
#include "polydec/dec/surface/hodge_star.h"

#include <algorithm>
#include <stdexcept>

#include "polydec/dec/detail/drop_zeros.h"
#include "polydec/dec/detail/element_pattern.h"
#include "polydec/dec/surface/whitney.h"

namespace polydec {

namespace {

using Triplet = Eigen::Triplet<double>;

Eigen::Vector3d row3(const Eigen::MatrixX3d& X, int r) { return X.row(r).transpose(); }

void scatter(const StarPattern& cp, int f, int m, const double* local, SparseMatrix& A) {
  const int* slot = cp.slots.data() + cp.offsets[f];
  double* v = A.valuePtr();
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) v[slot[a * m + b]] += local[a + b * m];
}

void scatter(const StarPattern& cp, int f, const Eigen::MatrixXd& local, SparseMatrix& A) {
  scatter(cp, f, int(local.rows()), local.data(), A);
}

// P_f^T star1^f_f P_f of one face, without heap allocation per face: fixed sizes for N = 3, 4
// corners, buffers reused across faces otherwise (N = Eigen::Dynamic). Corners x in face order,
// weights w, `order` the corners sorted by vertex index. Rows of P1 restricted to one fan
// triangle, on the 2n-3 pairs they touch: the polygon edge (lo, hi) -> its pair; spoke (r, v)
// -> sign(s - r) w_s on pair (r, s).
template <int N>
struct Star1Local {
  static constexpr int M = N == Eigen::Dynamic ? Eigen::Dynamic : N * (N - 1) / 2;
  Eigen::Matrix<double, M, M> A;  // the result, pairs in local lexicographic order of corner ranks
  std::vector<int> rank, idx, row;
  std::vector<double> q;

  // Q (3 x (2n-3)) has the column (1, w_hi, -w_lo) for the edge pair and one non-zero q_c in
  // row r_c (1: spoke lo, 2: spoke hi) in every other column c, so Q^T Mk Q is formed entry by
  // entry: with v = Mk Q_0, B_00 = Q_0 . v, B_c0 = B_0c = q_c v_(r_c), B_ab = q_a (Mk_(r_a r_b) q_b).
  void compute(int n, const Eigen::Vector3d* x, const double* w, const Eigen::Vector3d& xf, const FanTriangle* fan,
               const int* order) {
    const int m = n * (n - 1) / 2, u = 2 * n - 3;
    A.setZero(m, m);
    rank.resize(size_t(n));
    idx.resize(size_t(u));
    row.resize(size_t(u));
    q.resize(size_t(u));
    for (int r = 0; r < n; ++r) rank[size_t(order[r])] = r;
    for (int k = 0; k < n; ++k) {
      if (fan[k] == FanTriangle::Degenerate) continue;
      const int l = (k + 1) % n;
      const int lo = std::min(rank[k], rank[l]), hi = std::max(rank[k], rank[l]);
      const Eigen::Vector3d q0(1.0, w[order[hi]], -w[order[lo]]);  // spokes lo (+w_hi) and hi (-w_lo)
      int c = 1;
      for (int s = 0; s < n; ++s) {
        if (s == lo || s == hi) continue;
        idx[c] = lo < s ? local_pair_index(n, lo, s) : local_pair_index(n, s, lo);
        row[c] = 1;
        q[c] = s > lo ? w[order[s]] : -w[order[s]];
        ++c;
        idx[c] = hi < s ? local_pair_index(n, hi, s) : local_pair_index(n, s, hi);
        row[c] = 2;
        q[c] = s > hi ? w[order[s]] : -w[order[s]];
        ++c;
      }
      const int e = local_pair_index(n, lo, hi);
      const Eigen::Matrix3d Mk = whitney1_mass(x[order[lo]], x[order[hi]], xf);
      const Eigen::Vector3d v = Mk * q0;
      A(e, e) += q0.dot(v);
      for (int a = 1; a < u; ++a) {
        const double b0 = q[a] * v[row[a]];
        A(idx[a], e) += b0;
        A(e, idx[a]) += b0;
        for (int b = 1; b < u; ++b) A(idx[a], idx[b]) += q[a] * (Mk(row[a], row[b]) * q[b]);
      }
    }
  }
};

// The three kernels, dispatched by face size; corner positions gathered once per face.
struct Star1Kernels {
  Star1Local<3> tri;
  Star1Local<4> quad;
  Star1Local<Eigen::Dynamic> any;
  std::vector<Eigen::Vector3d> x;

  // Computes face f's block; returns its size m and points `local` at it (column-major).
  int compute(const Mesh& mesh, const Refinement& refinement, const CoarseComplex& complex, int f,
              const double*& local) {
    const auto face = mesh.face(f);
    const int n = int(face.size()), h0 = mesh.face_offsets()[f];
    x.resize(size_t(n));
    for (int k = 0; k < n; ++k) x[size_t(k)] = mesh.position(face[k]);
    const double* w = refinement.weights.data() + h0;
    const Eigen::Vector3d xf = row3(refinement.virtual_points, f);
    const FanTriangle* fan = refinement.fan.data() + h0;
    const int* order = complex.sorted_corners(f).data();
    if (n == 3) {
      tri.compute(n, x.data(), w, xf, fan, order);
      local = tri.A.data();
    } else if (n == 4) {
      quad.compute(n, x.data(), w, xf, fan, order);
      local = quad.A.data();
    } else {
      any.compute(n, x.data(), w, xf, fan, order);
      local = any.A.data();
    }
    return n * (n - 1) / 2;
  }
};

// Rank of each corner (position in `order`).
std::vector<int> corner_ranks(std::span<const int> order) {
  std::vector<int> rank(order.size());
  for (size_t r = 0; r < order.size(); ++r) rank[order[r]] = int(r);
  return rank;
}

// Coarse star0 of one polygon, P_f^T star0^f_f P_f with P_f = [I; w^T], in face order.
Eigen::MatrixXd polygon_star0(const PolygonPositions& X, const Eigen::VectorXd& w,
                              const Eigen::Vector3d& xf) {
  const int n = int(X.rows());
  Eigen::MatrixXd Mc = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd m = Eigen::VectorXd::Zero(n);
  double mu = 0;
  for (int k = 0; k < n; ++k) {
    const int l = (k + 1) % n;
    const Eigen::Matrix3d t = whitney0_mass(row3(X, k), row3(X, l), xf);
    Mc(k, k) += t(0, 0);
    Mc(l, l) += t(1, 1);
    Mc(k, l) += t(0, 1);
    Mc(l, k) += t(1, 0);
    m[k] += t(0, 2);
    m[l] += t(1, 2);
    mu += t(2, 2);
  }
  return Mc + m * w.transpose() + w * m.transpose() + mu * w * w.transpose();
}

}  // namespace

SparseMatrix refined_star0(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "refined_star0");
  const int nv = mesh.n_vertices();
  std::vector<Triplet> t;
  t.reserve(9 * size_t(mesh.n_halfedges()));
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    const int f = mesh.halfedge_face(h);
    const int v[3] = {mesh.halfedge_source(h), mesh.halfedge_target(h), nv + f};
    const Eigen::Matrix3d m =
        whitney0_mass(mesh.position(v[0]), mesh.position(v[1]), row3(refinement.virtual_points, f));
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) t.emplace_back(v[a], v[b], m(a, b));
  }
  SparseMatrix S(refined_n_vertices(mesh), refined_n_vertices(mesh));
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

SparseMatrix refined_star1(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "refined_star1");
  const int ne = mesh.n_edges();
  std::vector<Triplet> t;
  t.reserve(9 * size_t(mesh.n_halfedges()));
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    if (refinement.fan[h] == FanTriangle::Degenerate) continue;
    const int f = mesh.halfedge_face(h), s = mesh.halfedge_source(h), e = mesh.halfedge_target(h);
    const bool up = s < e;
    // Sorted corners (lo, hi, v); local edges (lo,hi), (lo,v), (hi,v).
    const int lo = up ? s : e, hi = up ? e : s;
    const int spoke_s = ne + h, spoke_e = ne + mesh.halfedge_next(h);
    const int cell[3] = {mesh.halfedge_edge(h), up ? spoke_s : spoke_e, up ? spoke_e : spoke_s};
    const Eigen::Matrix3d m =
        whitney1_mass(mesh.position(lo), mesh.position(hi), row3(refinement.virtual_points, f));
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) t.emplace_back(cell[a], cell[b], m(a, b));
  }
  SparseMatrix S(refined_n_edges(mesh), refined_n_edges(mesh));
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

SparseMatrix refined_star2(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "refined_star2");
  std::vector<Triplet> t;
  t.reserve(mesh.n_halfedges());
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    if (refinement.fan[h] == FanTriangle::Degenerate) continue;
    t.emplace_back(
        h, h,
        whitney2_mass(mesh.position(mesh.halfedge_source(h)), mesh.position(mesh.halfedge_target(h)),
                      row3(refinement.virtual_points, mesh.halfedge_face(h))));
  }
  SparseMatrix S(mesh.n_halfedges(), mesh.n_halfedges());
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

Eigen::MatrixXd polygon_star1(const PolygonPositions& X, const Eigen::VectorXd& w, const Eigen::Vector3d& xf,
                              const FanTriangle* fan, std::span<const int> order) {
  const int n = int(X.rows());
  std::vector<Eigen::Vector3d> x(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) x[size_t(k)] = row3(X, k);
  Star1Local<Eigen::Dynamic> s;
  s.compute(n, x.data(), w.data(), xf, fan, order.data());
  return s.A;
}

Eigen::MatrixXd polygon_star2(const PolygonPositions& X, const Eigen::VectorXd& w, const Eigen::Vector3d& xf,
                              const FanTriangle* fan, std::span<const int> order) {
  const int n = int(X.rows()), m = n * (n - 1) * (n - 2) / 6;
  const std::vector<int> rank = corner_ranks(order);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, m);
  std::vector<int> idx;
  std::vector<double> q;
  for (int k = 0; k < n; ++k) {
    if (fan[k] == FanTriangle::Degenerate) continue;
    const int l = (k + 1) % n;
    const int lo = std::min(rank[k], rank[l]), hi = std::max(rank[k], rank[l]);
    // Row of P2 for the triangle (lo, hi, v): det [e_lo; e_hi; w] on each triple {lo, hi, c}.
    idx.clear();
    q.clear();
    for (int c = 0; c < n; ++c) {
      if (c == lo || c == hi) continue;
      int t[3] = {lo, hi, c};
      std::sort(t, t + 3);
      idx.push_back(local_triple_index(n, t[0], t[1], t[2]));
      q.push_back((c > lo && c < hi) ? -w[order[c]] : w[order[c]]);
    }
    const double inv_area = whitney2_mass(row3(X, k), row3(X, l), xf);
    for (size_t a = 0; a < idx.size(); ++a)
      for (size_t b = 0; b < idx.size(); ++b) A(idx[a], idx[b]) += inv_area * q[a] * q[b];
  }
  return A;
}

namespace {
// dst = the pattern of the cells sharing a face (cells_of(f): face f's cells) with absolute slots,
// moved in without copying the matrix (Eigen 3.4's SparseMatrix has no move assignment: a copy
// of FINE SPHERE's star1 pattern is ~40 MB). Columns sorted in place: star1's are short and
// their rows far apart, where this beats the transposition (FINE SPHERE: 54 ms against 63 ms).
template <class FaceCells>
void build_star_pattern(StarPattern& dst, int n_cells, int n_faces, FaceCells cells_of) {
  detail::ElementPattern ep =
      detail::element_pattern<detail::SlotKind::absolute, detail::ColumnOrder::sort>(n_cells, n_faces, cells_of);
  dst.pattern.swap(ep.pattern);
  dst.offsets = std::move(ep.offsets);
  dst.slots = std::move(ep.slots);
}
}  // namespace

StarPatterns star_patterns(const Mesh& mesh, const CoarseComplex& complex, HodgeStarParts parts) {
  StarPatterns P;
  const int nf = mesh.n_faces();
  if (parts.star0 || parts.star0_lumped)
    build_star_pattern(P.star0, mesh.n_vertices(), nf, [&](int f) { return mesh.face(f); });
  if (parts.star1) build_star_pattern(P.star1, complex.n_pairs(), nf, [&](int f) { return complex.face_pairs(f); });
  if (parts.star2)
    build_star_pattern(P.star2, complex.n_triples(), nf, [&](int f) { return complex.face_triples(f); });
  return P;
}

HodgeStars hodge_stars(const Mesh& mesh, const Refinement& refinement, const CoarseComplex& complex,
                       HodgeStarParts parts, const StarPatterns* patterns) {
  check_refinement(mesh, refinement, "hodge_stars");
  HodgeStars H;
  const int nf = mesh.n_faces();
  const bool want0 = parts.star0 || parts.star0_lumped;
  StarPatterns own = patterns ? StarPatterns{} : star_patterns(mesh, complex, parts);  // no copy (elided)
  if (!patterns) patterns = &own;
  const StarPattern &p0 = patterns->star0, &p1 = patterns->star1, &p2 = patterns->star2;
  if ((want0 && long(p0.offsets.size()) != nf + 1) || (parts.star1 && long(p1.offsets.size()) != nf + 1) ||
      (parts.star2 && long(p2.offsets.size()) != nf + 1))
    throw std::invalid_argument("hodge_stars: the patterns were built for other parts or another mesh");
  // Eigen's SparseMatrix has no move constructor: swap our own patterns in, copy shared ones.
  auto take = [&](const StarPattern& p, StarPattern* mine, SparseMatrix& A) {
    if (mine)
      A.swap(mine->pattern);
    else
      A = p.pattern;
  };
  const bool owned = patterns == &own;
  if (want0) take(p0, owned ? &own.star0 : nullptr, H.star0);
  if (parts.star1) take(p1, owned ? &own.star1 : nullptr, H.star1);
  if (parts.star2) take(p2, owned ? &own.star2 : nullptr, H.star2);
  Star1Kernels k1;
  for (int f = 0; f < nf; ++f) {
    if (parts.star1) {
      const double* local = nullptr;
      const int m = k1.compute(mesh, refinement, complex, f, local);
      scatter(p1, f, m, local, H.star1);
    }
    if (!want0 && !parts.star2) continue;
    const PolygonPositions X = face_positions(mesh, f);
    const int h0 = mesh.face_offsets()[f];
    const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(refinement.weights.data() + h0, X.rows());
    const Eigen::Vector3d xf = row3(refinement.virtual_points, f);
    const FanTriangle* fan = refinement.fan.data() + h0;
    if (want0) scatter(p0, f, polygon_star0(X, w, xf), H.star0);
    if (parts.star2) scatter(p2, f, polygon_star2(X, w, xf, fan, complex.sorted_corners(f)), H.star2);
  }
  if (parts.star0_lumped) {
    H.star0_lumped = Eigen::VectorXd::Zero(mesh.n_vertices());
    for (int j = 0; j < H.star0.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(H.star0, j); it; ++it) H.star0_lumped[it.row()] += it.value();
  }
  if (!parts.star0) H.star0 = SparseMatrix();
  // The face blocks are dense in the pattern, but pairs and triples that no fan triangle joins
  // (triples without a polygon edge, say, or of degenerate fan triangles) meet in exact zeros:
  // dropped, so that the stars store their non-zeros only (the values are untouched).
  detail::drop_exact_zeros(H.star0);
  detail::drop_exact_zeros(H.star1);
  detail::drop_exact_zeros(H.star2);
  return H;
}

SparseMatrix star1(const Mesh& mesh, const Refinement& refinement, const CoarseComplex& complex) {
  check_refinement(mesh, refinement, "star1");
  HodgeStars H = hodge_stars(mesh, refinement, complex, {false, false, true, false});
  SparseMatrix A;
  A.swap(H.star1);
  return A;
}

SparseMatrix star2(const Mesh& mesh, const Refinement& refinement, const CoarseComplex& complex) {
  check_refinement(mesh, refinement, "star2");
  HodgeStars H = hodge_stars(mesh, refinement, complex, {false, false, false, true});
  SparseMatrix A;
  A.swap(H.star2);
  return A;
}

}  // namespace polydec
