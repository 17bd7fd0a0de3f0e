// dec/surface/split_refinement.cpp — pieces of faces with invalid squared-area fans, their virtual
// vertices, refined triangles and prolongation.
#include "polydec/dec/surface/split_refinement.h"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>

namespace polydec {

namespace {

using Vec2 = Eigen::Vector2d;

// Twice the signed area of the 2-D triangle (a, b, c).
double area2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
}

// A polygon in its best-fit plane, oriented counter-clockwise, with the orientation tolerance
// `eps` (twice an area: 1e-12 of its squared diameter).
struct Plane2D {
  std::vector<Vec2> u;
  double eps = 0;

  explicit Plane2D(const PolygonPositions& X) {
    const int n = int(X.rows());
    const Eigen::RowVector3d c = X.colwise().mean();
    const Eigen::MatrixX3d Y = X.rowwise() - c;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(Y), Eigen::ComputeThinV);
    const Eigen::Vector3d e0 = svd.matrixV().col(0), e1 = svd.matrixV().col(1);
    u.resize(n);
    double r2 = 0, signed_area = 0;
    for (int k = 0; k < n; ++k) {
      u[k] = Vec2(Y.row(k).dot(e0), Y.row(k).dot(e1));
      r2 = std::max(r2, u[k].squaredNorm());
    }
    for (int k = 0; k < n; ++k) {
      const Vec2& p = u[k];
      const Vec2& q = u[(k + 1) % n];
      signed_area += p.x() * q.y() - p.y() * q.x();
    }
    if (signed_area < 0)
      for (Vec2& p : u) p.y() = -p.y();
    eps = 1e-12 * 4 * r2;
  }
  bool left(int a, int b, int c) const { return area2(u[a], u[b], u[c]) > eps; }
  bool left_on(int a, int b, int c) const { return area2(u[a], u[b], u[c]) > -eps; }
  bool collinear(int a, int b, int c) const { return std::abs(area2(u[a], u[b], u[c])) <= eps; }
  // c on the closed segment (a, b), up to the tolerance.
  bool between(int a, int b, int c) const {
    if (!collinear(a, b, c)) return false;
    const Vec2 d = u[b] - u[a];
    const double t = (u[c] - u[a]).dot(d);
    return t >= -std::sqrt(eps) * d.norm() && t <= d.squaredNorm() + std::sqrt(eps) * d.norm();
  }
  // The closed segments (a, b) and (c, d) meet.
  bool intersect(int a, int b, int c, int d) const {
    if (!collinear(a, b, c) && !collinear(a, b, d) && !collinear(c, d, a) && !collinear(c, d, b))
      return (left(a, b, c) != left(a, b, d)) && (left(c, d, a) != left(c, d, b));
    return between(a, b, c) || between(a, b, d) || between(c, d, a) || between(c, d, b);
  }
  // The segment from corner i towards corner j starts inside the polygon's angle at i.
  bool in_cone(int i, int j) const {
    const int n = int(u.size()), i0 = (i + n - 1) % n, i1 = (i + 1) % n;
    if (left_on(i, i1, i0)) return left(i, j, i0) && left(j, i, i1);  // convex corner
    return !(left_on(i, j, i1) && left_on(j, i, i0));
  }
};

// Splits the sorted piece `piece` along its diagonal (a, b), a < b, both in it.
std::pair<std::vector<int>, std::vector<int>> cut(const std::vector<int>& piece, int a, int b) {
  std::vector<int> inner, outer;
  for (int k : piece) {
    if (k >= a && k <= b) inner.push_back(k);
    if (k <= a || k >= b) outer.push_back(k);
  }
  return {inner, outer};
}

bool crossing(const std::pair<int, int>& p, const std::pair<int, int>& q) {
  const auto [a, b] = p;
  const auto [c, d] = q;
  return (a < c && c < b && b < d) || (c < a && a < d && d < b);
}

// The squared-area weights, virtual point and worst fan-triangle quality of the piece with the
// given corners of X; `valid` when no fan triangle is degenerate or inverted.
struct PieceFan {
  Eigen::VectorXd w;
  Eigen::Vector3d x;
  double worst = 0;
  bool valid = false;
  int n_degenerate = 0, n_inverted = 0;
};

PieceFan piece_fan(const PolygonPositions& X, const std::vector<int>& piece, double tol, double planarity_tolerance,
                   double noise) {
  const int m = int(piece.size());
  PolygonPositions Xp(m, 3);
  for (int k = 0; k < m; ++k) Xp.row(k) = X.row(piece[k]);
  const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> rows = Xp;  // corners row by row
  const PlanarityCut cutp = planarity_cut(planarity_tolerance, noise, rows.data(), m);
  PieceFan out;
  out.w = squared_area_weights(Xp, cutp);
  const Eigen::RowVector3d c = Xp.colwise().mean();
  Eigen::RowVector3d s = Eigen::RowVector3d::Zero(), normal = Eigen::RowVector3d::Zero();
  for (int k = 0; k < m; ++k) {
    s += out.w[k] * (Xp.row(k) - c);
    normal += (Xp.row(k) - c).cross(Xp.row((k + 1) % m) - c);
  }
  out.x = (c + s).transpose();
  out.worst = std::numeric_limits<double>::infinity();
  for (int k = 0; k < m; ++k) {
    const double q = fan_triangle_quality(Xp.row(k).transpose(), Xp.row((k + 1) % m).transpose(), out.x,
                                          normal.transpose(), tol);
    out.worst = std::min(out.worst, q);
    if (q == 0) ++out.n_degenerate;
    if (q < 0) ++out.n_inverted;
  }
  out.valid = out.n_degenerate == 0 && out.n_inverted == 0;
  return out;
}

// The fewest valid pieces (2 .. max_pieces) of X, best worst quality among them; invalid (whole
// polygon) when none.
PolygonSplit search_split(const PolygonPositions& X, const SplitOptions& o, double planarity_tolerance, double noise) {
  const int n = int(X.rows());
  PolygonSplit best;
  best.pieces = {std::vector<int>(n)};
  for (int k = 0; k < n; ++k) best.pieces[0][k] = k;
  if (n > o.max_corners || n < 4) return best;
  const std::vector<std::pair<int, int>> D = interior_diagonals(X);
  std::map<std::vector<int>, std::pair<bool, double>> memo;  // piece -> (valid, worst)
  auto evaluate = [&](const std::vector<int>& piece) {
    auto it = memo.find(piece);
    if (it != memo.end()) return it->second;
    const PieceFan f = piece_fan(X, piece, o.degenerate_tolerance, planarity_tolerance, noise);
    return memo.emplace(piece, std::make_pair(f.valid, f.worst)).first->second;
  };
  std::vector<int> chosen;
  bool found = false;
  // Evaluates the split by the diagonals `chosen`; keeps it when valid and better.
  auto consider = [&] {
    std::vector<std::vector<int>> pieces{std::vector<int>(n)};
    for (int k = 0; k < n; ++k) pieces[0][k] = k;
    for (int d : chosen) {
      const auto [a, b] = D[d];
      for (size_t p = 0; p < pieces.size(); ++p) {
        const auto& q = pieces[p];
        if (std::binary_search(q.begin(), q.end(), a) && std::binary_search(q.begin(), q.end(), b)) {
          auto [inner, outer] = cut(q, a, b);
          pieces[p] = std::move(inner);
          pieces.push_back(std::move(outer));
          break;
        }
      }
    }
    double worst = std::numeric_limits<double>::infinity();
    for (const auto& q : pieces) {
      const auto [valid, w] = evaluate(q);
      if (!valid) return;
      worst = std::min(worst, w);
    }
    // Ties to round-off keep the first split in lexicographic order, so that moving or scaling the
    // polygon does not change the choice.
    if (!found || worst > best.worst + 1e-9 * std::abs(best.worst)) {
      found = true;
      std::sort(pieces.begin(), pieces.end());
      best.pieces = std::move(pieces);
      best.worst = worst;
      best.valid = true;
    }
  };
  // All sets of `count` pairwise non-crossing diagonals, in lexicographic order.
  std::function<void(int, int)> choose = [&](int from, int count) {
    if (count == 0) return consider();
    for (int d = from; d < int(D.size()); ++d) {
      bool ok = true;
      for (int e : chosen) ok = ok && !crossing(D[d], D[e]);
      if (!ok) continue;
      chosen.push_back(d);
      choose(d + 1, count - 1);
      chosen.pop_back();
    }
  };
  for (int k = 2; k <= o.max_pieces && !found; ++k) choose(0, k - 1);
  return best;
}

}  // namespace

double fan_triangle_quality(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& x,
                            const Eigen::Vector3d& normal, double degenerate_tolerance) {
  const Eigen::Vector3d p = a - x, q = b - x;
  const Eigen::Vector3d area2 = p.cross(q);
  const double longest2 = std::max({p.squaredNorm(), q.squaredNorm(), (q - p).squaredNorm()});
  const double norm = area2.norm();
  if (!(norm > degenerate_tolerance * longest2)) return 0.0;
  return (area2.dot(normal) < 0 ? -norm : norm) / longest2;
}

std::vector<std::pair<int, int>> interior_diagonals(const PolygonPositions& X) {
  const int n = int(X.rows());
  std::vector<std::pair<int, int>> out;
  if (n < 4) return out;
  const Plane2D P(X);
  for (int i = 0; i < n; ++i)
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // an edge
      if (!P.in_cone(i, j) || !P.in_cone(j, i)) continue;
      bool ok = true;
      for (int k = 0; k < n && ok; ++k) {
        const int k1 = (k + 1) % n;
        if (k != i && k != j && P.between(i, j, k)) ok = false;
        if (k == i || k == j || k1 == i || k1 == j) continue;
        if (P.intersect(i, j, k, k1)) ok = false;
      }
      if (ok) out.emplace_back(i, j);
    }
  return out;
}

PolygonSplit split_polygon(const PolygonPositions& X, const SplitOptions& options, double planarity_tolerance,
                           double noise) {
  const int n = int(X.rows());
  std::vector<int> all(n);
  for (int k = 0; k < n; ++k) all[k] = k;
  const PieceFan whole = piece_fan(X, all, options.degenerate_tolerance, planarity_tolerance, noise);
  if (whole.valid) return {{all}, whole.worst, true};
  PolygonSplit s = search_split(X, options, planarity_tolerance, noise);
  if (!s.valid) s.worst = whole.worst;
  return s;
}

SplitRefinement split_refine(const Mesh& mesh, const SplitOptions& options) {
  if (options.max_pieces < 1) throw std::invalid_argument("split_refine: max_pieces must be at least 1");
  RefinementOptions ro;
  ro.degenerate_tolerance = options.degenerate_tolerance;
  const Refinement r = refine(mesh, ro);
  SplitRefinement s;
  s.options = options;
  s.before = r.quality;
  s.pieces_histogram.assign(std::max(options.max_pieces, 1) + 1, 0);
  s.piece_offsets.push_back(0);
  s.corner_offsets.push_back(0);
  std::vector<Eigen::Vector3d> points;
  const double noise = mesh.precision().noise > 0 ? mesh.coordinate_noise() : 0.0;
  const double ptol = mesh.precision().planarity_tolerance;
  s.worst_before = s.worst_after = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const PolygonPositions X = face_positions(mesh, f);
    const int n = int(X.rows()), h0 = mesh.face_offsets()[f];
    // The single fan's quality, from the refinement's own point and normal.
    const Eigen::RowVector3d c = X.colwise().mean();
    Eigen::RowVector3d normal = Eigen::RowVector3d::Zero();
    for (int k = 0; k < n; ++k) normal += (X.row(k) - c).cross(X.row((k + 1) % n) - c);
    const Eigen::Vector3d xf = r.virtual_points.row(f).transpose();
    double worst = std::numeric_limits<double>::infinity();
    bool valid = true;
    for (int k = 0; k < n; ++k) {
      worst = std::min(worst, fan_triangle_quality(X.row(k).transpose(), X.row((k + 1) % n).transpose(), xf,
                                                   normal.transpose(), options.degenerate_tolerance));
      valid = valid && r.fan[h0 + k] == FanTriangle::Valid;
    }
    s.worst_before = std::min(s.worst_before, worst);
    PolygonSplit split;
    if (!valid) split = search_split(X, options, ptol, noise);
    if (valid || !split.valid) {  // one piece: the paper's weights and point
      for (int k = 0; k < n; ++k) {
        s.corners.push_back(k);
        s.weights.push_back(r.weights[h0 + k]);
        const FanTriangle t = r.fan[h0 + k];
        s.after.n_degenerate += t == FanTriangle::Degenerate;
        s.after.n_inverted += t == FanTriangle::Inverted;
      }
      s.after.n_faces_affected += !valid;
      s.n_faces_unsplittable += !valid;
      points.push_back(xf);
      s.corner_offsets.push_back(int(s.corners.size()));
      s.worst_after = std::min(s.worst_after, worst);
      ++s.pieces_histogram[1];
    } else {
      for (const auto& piece : split.pieces) {
        const PieceFan pf = piece_fan(X, piece, options.degenerate_tolerance, ptol, noise);
        for (size_t k = 0; k < piece.size(); ++k) {
          s.corners.push_back(piece[k]);
          s.weights.push_back(pf.w[Eigen::Index(k)]);
        }
        points.push_back(pf.x);
        s.corner_offsets.push_back(int(s.corners.size()));
        s.worst_after = std::min(s.worst_after, pf.worst);
      }
      ++s.n_faces_split;
      ++s.pieces_histogram[split.pieces.size()];
    }
    s.piece_offsets.push_back(int(points.size()));
  }
  s.virtual_points.resize(Eigen::Index(points.size()), 3);
  for (size_t p = 0; p < points.size(); ++p) s.virtual_points.row(Eigen::Index(p)) = points[p].transpose();
  if (mesh.n_faces() == 0) s.worst_before = s.worst_after = 0;
  return s;
}

std::vector<Eigen::Vector3i> split_triangles(const Mesh& mesh, const SplitRefinement& split) {
  std::vector<Eigen::Vector3i> tris;
  const int nv = mesh.n_vertices();
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    for (int p = split.piece_offsets[f]; p < split.piece_offsets[f + 1]; ++p) {
      const int b = split.corner_offsets[p], m = split.corner_offsets[p + 1] - b;
      for (int k = 0; k < m; ++k)
        tris.emplace_back(face[split.corners[b + k]], face[split.corners[b + (k + 1) % m]], nv + p);
    }
  }
  return tris;
}

Eigen::MatrixX3d split_positions(const Mesh& mesh, const SplitRefinement& split) {
  Eigen::MatrixX3d X(mesh.n_vertices() + split.n_pieces(), 3);
  X.topRows(mesh.n_vertices()) = mesh.positions();
  X.bottomRows(split.n_pieces()) = split.virtual_points;
  return X;
}

Eigen::SparseMatrix<double> split_prolongation(const Mesh& mesh, const SplitRefinement& split) {
  const int nv = mesh.n_vertices();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(size_t(nv) + split.corners.size());
  for (int v = 0; v < nv; ++v) t.emplace_back(v, v, 1.0);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    for (int p = split.piece_offsets[f]; p < split.piece_offsets[f + 1]; ++p)
      for (int c = split.corner_offsets[p]; c < split.corner_offsets[p + 1]; ++c)
        t.emplace_back(nv + p, face[split.corners[c]], split.weights[c]);
  }
  Eigen::SparseMatrix<double> P(nv + split.n_pieces(), nv);
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

}  // namespace polydec
