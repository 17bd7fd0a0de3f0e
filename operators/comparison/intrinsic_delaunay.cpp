// operators/comparison/intrinsic_delaunay.cpp — intrinsic edge flips on a halfedge structure of lengths.
#include "polydec/operators/comparison/intrinsic_delaunay.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace polydec {

namespace {

// Halfedge 3t+k of triangle t runs from corner k to corner k+1.
struct Halfedges {
  std::vector<int> tail, twin;
  std::vector<double> len;
  static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
};

// Cotangent of the angle opposite halfedge h in its triangle.
double cot_opposite(const Halfedges& H, int h) {
  const double a = H.len[h], b = H.len[Halfedges::next(h)], c = H.len[Halfedges::prev(h)];
  const double A = triangle_area_from_lengths(a, b, c);
  return (b * b + c * c - a * a) / (4.0 * A);
}

// Angle opposite halfedge h.
double angle_opposite(const Halfedges& H, int h) {
  const double a = H.len[h], b = H.len[Halfedges::next(h)], c = H.len[Halfedges::prev(h)];
  return std::atan2(4.0 * triangle_area_from_lengths(a, b, c), b * b + c * c - a * a);
}

// Flips the edge of halfedge h (a -> b, triangle (a, b, c)) with twin g (b -> a, triangle
// (b, a, d)) to the edge c - d. Returns false (no flip) when the two triangles touch each other
// along another edge, where the flip is not a local operation.
bool flip(Halfedges& H, int h) {
  const int g = H.twin[h];
  const int t1 = h / 3, t2 = g / 3;
  if (t1 == t2) return false;
  const int hn = Halfedges::next(h), hp = Halfedges::prev(h), gn = Halfedges::next(g),
            gp = Halfedges::prev(g);
  const int outer[4] = {hp, gn, gp, hn};  // c->a, a->d, d->b, b->c
  int tw[4];
  double l[4];
  for (int k = 0; k < 4; ++k) {
    tw[k] = H.twin[outer[k]];
    l[k] = H.len[outer[k]];
    if (tw[k] >= 0 && (tw[k] / 3 == t1 || tw[k] / 3 == t2)) return false;
  }
  const int a = H.tail[h], b = H.tail[g], c = H.tail[hp], d = H.tail[gp];
  // Lay out a = (0,0), b = (l_ab, 0), c above and d below the x axis; the new length is |c - d|.
  const double lab = H.len[h];
  const double lca = l[0], lbc = l[3], lad = l[1], ldb = l[2];
  const double cx = (lab * lab + lca * lca - lbc * lbc) / (2 * lab);
  const double cy = 2 * triangle_area_from_lengths(lab, lbc, lca) / lab;
  const double dx = (lab * lab + lad * lad - ldb * ldb) / (2 * lab);
  const double dy = -2 * triangle_area_from_lengths(lab, ldb, lad) / lab;
  const double lcd = std::hypot(cx - dx, cy - dy);
  // New triangles: t1 = (c, a, d), t2 = (d, b, c).
  const int n1[3] = {3 * t1, 3 * t1 + 1, 3 * t1 + 2}, n2[3] = {3 * t2, 3 * t2 + 1, 3 * t2 + 2};
  auto set = [&](int he, int tail, double len, int twin) {
    H.tail[he] = tail;
    H.len[he] = len;
    H.twin[he] = twin;
    if (twin >= 0) H.twin[twin] = he;
  };
  set(n1[0], c, lca, tw[0]);
  set(n1[1], a, lad, tw[1]);
  set(n1[2], d, lcd, n2[2]);
  set(n2[0], d, ldb, tw[2]);
  set(n2[1], b, lbc, tw[3]);
  set(n2[2], c, lcd, n1[2]);
  return true;
}

}  // namespace

IntrinsicTriangulation intrinsic_delaunay(const Eigen::MatrixX3d& X, const std::vector<Eigen::Vector3i>& tris,
                                          const IntrinsicDelaunayOptions& options) {
  const int nt = int(tris.size());
  Halfedges H;
  H.tail.resize(3 * nt);
  H.twin.assign(3 * nt, -1);
  H.len.resize(3 * nt);
  // Twins by sorting directed edges (tail, head): the twin of (i, j) is the unique (j, i).
  std::vector<std::array<int, 3>> keys(3 * nt);
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int h = 3 * t + k, i = tris[t][k], j = tris[t][(k + 1) % 3];
      if (i < 0 || j < 0 || i >= X.rows() || j >= X.rows())
        throw std::invalid_argument(
            fmt::format("intrinsic_delaunay: triangle {} has a vertex index out of range", t));
      H.tail[h] = i;
      H.len[h] = (X.row(j) - X.row(i)).norm();
      keys[h] = {i, j, h};
    }
  std::sort(keys.begin(), keys.end());
  for (size_t a = 0; a + 1 < keys.size(); ++a)
    if (keys[a][0] == keys[a + 1][0] && keys[a][1] == keys[a + 1][1])
      throw std::invalid_argument(
          fmt::format("intrinsic_delaunay: edge ({}, {}) appears twice with the same direction (non-manifold "
                      "or inconsistently "
                      "oriented triangles)",
                      keys[a][0], keys[a][1]));
  for (int h = 0; h < 3 * nt; ++h) {
    const int i = H.tail[h], j = H.tail[Halfedges::next(h)];
    const std::array<int, 3> probe = {j, i, -1};
    const auto it = std::lower_bound(keys.begin(), keys.end(), probe);
    if (it != keys.end() && (*it)[0] == j && (*it)[1] == i) H.twin[h] = (*it)[2];
  }
  IntrinsicTriangulation out;
  // Sweep until no edge is flipped. Every flip strictly decreases the Dirichlet energy of the
  // piecewise linear functions (Bobenko-Springborn), so the sweeps terminate; the bound below only
  // guards against round-off cycling.
  const long max_flips = 1000L * std::max(1, 3 * nt);
  bool changed = true;
  while (changed) {
    changed = false;
    for (int h = 0; h < 3 * nt; ++h) {
      const int g = H.twin[h];
      if (g < h) continue;  // boundary (g = -1) or visited from the twin
      if (cot_opposite(H, h) + cot_opposite(H, g) >= -options.tolerance) continue;
      if (flip(H, h)) {
        changed = true;
        if (++out.n_flips > max_flips) throw std::runtime_error("intrinsic_delaunay: flips do not terminate");
      }
    }
  }
  out.triangles.n_vertices = int(X.rows());
  out.triangles.triangles.resize(nt);
  out.triangles.lengths.resize(nt);
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      out.triangles.triangles[t][k] = H.tail[3 * t + k];
      out.triangles.lengths[t][k] = H.len[3 * t + k];
    }
  for (int h = 0; h < 3 * nt; ++h)
    if (H.twin[h] > h) ++out.n_edges_checked;
  out.twin = std::move(H.twin);
  return out;
}

double max_delaunay_violation(const IntrinsicTriangulation& T) {
  const auto& tris = T.triangles.triangles;
  const int nt = int(tris.size());
  Halfedges H;
  H.tail.resize(3 * nt);
  H.len.resize(3 * nt);
  H.twin = T.twin;
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      H.tail[3 * t + k] = tris[t][k];
      H.len[3 * t + k] = T.triangles.lengths[t][k];
    }
  double worst = -M_PI;
  for (int h = 0; h < 3 * nt; ++h)
    if (H.twin[h] > h) worst = std::max(worst, angle_opposite(H, h) + angle_opposite(H, H.twin[h]) - M_PI);
  return worst;
}

}  // namespace polydec
