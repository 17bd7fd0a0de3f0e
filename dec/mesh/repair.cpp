// dec/mesh/repair.cpp — opt-in repair steps on a polygon soup, each reporting what it changed.
#include "polydec/dec/mesh/repair.h"
#include "polydec/dec/detail/face_shape.h"
#include "polydec/dec/detail/union_find.h"

#include <fmt/format.h>

#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace polydec {

namespace {

// Rebuilds soup's faces keeping those with keep[f]; returns old face -> new face (-1 dropped).
std::vector<int> keep_faces(PolygonSoup& soup, const std::vector<std::vector<int>>& faces,
                            const std::vector<unsigned char>& keep) {
  std::vector<int> map(faces.size(), -1);
  soup.face_offsets.assign(1, 0);
  soup.face_indices.clear();
  int next = 0;
  for (size_t f = 0; f < faces.size(); ++f)
    if (keep[f]) {
      map[f] = next++;
      soup.add_face(faces[f]);
    }
  return map;
}

std::vector<std::vector<int>> face_lists(const PolygonSoup& soup) {
  std::vector<std::vector<int>> faces(soup.n_faces());
  for (int f = 0; f < soup.n_faces(); ++f)
    faces[f].assign(soup.face_indices.begin() + soup.face_offsets[f],
                    soup.face_indices.begin() + soup.face_offsets[f + 1]);
  return faces;
}

void check_offsets(const PolygonSoup& soup) {
  if (soup.face_offsets.empty() || soup.face_offsets.front() != 0 ||
      soup.face_offsets.back() != long(soup.face_indices.size()) ||
      !std::is_sorted(soup.face_offsets.begin(), soup.face_offsets.end()))
    throw std::invalid_argument("repair: face offsets do not match the face index list");
}

// The vertices that keep[v] selects, renumbered in order; returns old -> new (-1 removed).
std::vector<int> keep_vertices(PolygonSoup& soup, const std::vector<int>& representative) {
  const int nv = soup.n_vertices();
  std::vector<int> map(nv, -1);
  int next = 0;
  for (int v = 0; v < nv; ++v)
    if (representative[v] == v) map[v] = next++;
  Eigen::MatrixX3d P(next, 3);
  for (int v = 0; v < nv; ++v)
    if (map[v] >= 0) P.row(map[v]) = soup.positions.row(v);
  for (int v = 0; v < nv; ++v)
    if (representative[v] >= 0) map[v] = map[representative[v]];
  for (int& i : soup.face_indices) i = map[i];
  soup.positions = std::move(P);
  return map;
}

// Whether the points are collinear (or coincident) up to the relative tolerance.
bool collinear(const PolygonSoup& soup, const std::vector<int>& face, double tolerance) {
  Eigen::MatrixXd Y(face.size(), 3);
  for (size_t k = 0; k < face.size(); ++k) Y.row(long(k)) = soup.positions.row(face[k]);
  const Eigen::Vector3d sigma = centred_singular_values(Y);
  return sigma[1] <= tolerance * sigma[0];
}

}  // namespace

VertexRemoval remove_unreferenced_vertices(PolygonSoup& soup) {
  check_offsets(soup);
  const int nv = soup.n_vertices();
  std::vector<int> representative(nv, -1);
  for (int i : soup.face_indices) {
    if (i < 0 || i >= nv)
      throw std::invalid_argument(fmt::format(
          "remove_unreferenced_vertices: face index {} out of range [0, {}): drop invalid faces first", i,
          nv));
    representative[i] = i;
  }
  VertexRemoval r;
  r.vertex_map = keep_vertices(soup, representative);
  r.n_removed = nv - soup.n_vertices();
  return r;
}

FaceDrop drop_invalid_faces(PolygonSoup& soup, const FaceDropOptions& options) {
  check_offsets(soup);
  const long nv = soup.n_vertices();
  auto faces = face_lists(soup);
  std::vector<unsigned char> keep(faces.size(), 0);
  FaceDrop d;
  for (size_t f = 0; f < faces.size(); ++f) {
    auto& face = faces[f];
    if (std::any_of(face.begin(), face.end(), [&](int v) { return v < 0 || v >= nv; })) {
      ++d.n_out_of_range;
      continue;
    }
    if (options.collapse_consecutive_repeats) {
      const size_t before = face.size();
      face.erase(std::unique(face.begin(), face.end()), face.end());
      while (face.size() > 1 && face.front() == face.back()) face.pop_back();
      d.n_collapsed_corners += int(before - face.size());
    }
    std::vector<int> sorted = face;
    std::sort(sorted.begin(), sorted.end());
    const size_t distinct = size_t(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
    if (distinct < 3) {
      ++d.n_too_few;
    } else if (distinct < face.size()) {
      ++d.n_repeated_vertex;
    } else if (collinear(soup, face, options.zero_area_tolerance)) {
      ++d.n_zero_area;
    } else {
      keep[f] = 1;
    }
  }
  d.face_map = keep_faces(soup, faces, keep);
  return d;
}

VertexMerge merge_duplicate_vertices(PolygonSoup& soup, double relative_tolerance) {
  check_offsets(soup);
  if (!(relative_tolerance >= 0) || !std::isfinite(relative_tolerance))
    throw std::invalid_argument("merge_duplicate_vertices: tolerance must be finite and non-negative");
  const int nv = soup.n_vertices();
  for (int v = 0; v < nv; ++v)
    if (!soup.positions.row(v).allFinite())
      throw std::invalid_argument(
          fmt::format("merge_duplicate_vertices: vertex {} has a non-finite coordinate", v));
  VertexMerge m;
  if (nv == 0) return m;
  const Eigen::RowVector3d lo = soup.positions.colwise().minCoeff();
  const double diag = (soup.positions.colwise().maxCoeff() - lo).norm();
  m.distance = relative_tolerance * diag;
  // Hash grid with cells no smaller than the merge distance (and no finer than 2^-40 of the
  // diagonal, so that cell coordinates fit in 64 bits); each vertex is compared with the
  // vertices of its 27 neighbouring cells.
  const double cell = std::max({m.distance, diag * 0x1p-40, std::numeric_limits<double>::min()});
  auto key = [](long long x, long long y, long long z) {  // unsigned: wraps instead of overflowing
    return (std::uint64_t(x) * 73856093ULL) ^ (std::uint64_t(y) * 19349663ULL) ^ (std::uint64_t(z) * 83492791ULL);
  };
  std::unordered_multimap<std::uint64_t, int> grid;
  grid.reserve(nv);
  std::vector<std::array<long long, 3>> cells(nv);
  for (int v = 0; v < nv; ++v) {
    for (int c = 0; c < 3; ++c) cells[v][c] = (long long)std::floor((soup.positions(v, c) - lo[c]) / cell);
    grid.emplace(key(cells[v][0], cells[v][1], cells[v][2]), v);
  }
  std::vector<int> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  for (int v = 0; v < nv; ++v)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto range = grid.equal_range(key(cells[v][0] + dx, cells[v][1] + dy, cells[v][2] + dz));
          for (auto it = range.first; it != range.second; ++it) {
            const int u = it->second;
            if (u <= v || (soup.positions.row(u) - soup.positions.row(v)).norm() > m.distance) continue;
            const int a = find_root(parent, u), b = find_root(parent, v);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
          }
        }
  std::vector<int> representative(nv);
  for (int v = 0; v < nv; ++v) representative[v] = find_root(parent, v);
  for (int i : soup.face_indices)
    if (i < 0 || i >= nv)
      throw std::invalid_argument(fmt::format(
          "merge_duplicate_vertices: face index {} out of range [0, {}): drop invalid faces first", i, nv));
  m.vertex_map = keep_vertices(soup, representative);
  m.n_merged = nv - soup.n_vertices();
  return m;
}

FaceDeduplication remove_duplicate_faces(PolygonSoup& soup) {
  check_offsets(soup);
  const auto faces = face_lists(soup);
  std::vector<unsigned char> keep(faces.size(), 1);
  std::map<std::vector<int>, std::pair<int, bool>> seen;  // canonical sequence -> (face, reversed)
  FaceDeduplication r;
  for (size_t f = 0; f < faces.size(); ++f) {
    const auto& face = faces[f];
    if (face.empty()) continue;
    bool reversed = false;
    std::vector<int> key = canonical_cycle(face, reversed);
    auto [it, inserted] = seen.emplace(std::move(key), std::make_pair(int(f), reversed));
    if (inserted) continue;
    keep[f] = 0;
    if (it->second.second == reversed)
      ++r.n_same_orientation;
    else
      ++r.n_opposite_orientation;
  }
  r.face_map = keep_faces(soup, faces, keep);
  return r;
}

bool RepairReport::changed() const {
  return merge.n_merged > 0 || drop.n_dropped() > 0 || drop.n_collapsed_corners > 0 ||
         dedup.n_removed() > 0 || unreferenced.n_removed > 0;
}

std::vector<std::string> RepairReport::summary() const {
  std::vector<std::string> s;
  if (merge.n_merged > 0)
    s.push_back(
        fmt::format("merged {} vertices into others (distance <= {:.3g})", merge.n_merged, merge.distance));
  if (drop.n_collapsed_corners > 0)
    s.push_back(fmt::format("collapsed {} repeated consecutive corners", drop.n_collapsed_corners));
  if (drop.n_dropped() > 0)
    s.push_back(fmt::format(
        "dropped {} invalid faces: {} with an index out of range, {} with fewer than 3 distinct vertices, "
        "{} repeating a vertex, {} of zero area",
        drop.n_dropped(), drop.n_out_of_range, drop.n_too_few, drop.n_repeated_vertex, drop.n_zero_area));
  if (dedup.n_removed() > 0)
    s.push_back(fmt::format("removed {} duplicate faces ({} same orientation, {} opposite orientation)",
                            dedup.n_removed(), dedup.n_same_orientation, dedup.n_opposite_orientation));
  if (unreferenced.n_removed > 0)
    s.push_back(fmt::format("removed {} unreferenced vertices", unreferenced.n_removed));
  if (s.empty()) s.push_back("nothing changed");
  return s;
}

namespace {

// a then b: a maps old -> middle, b middle -> new (-1 passes through).
std::vector<int> compose(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> c(a.size());
  for (size_t i = 0; i < a.size(); ++i) c[i] = a[i] < 0 ? -1 : b[a[i]];
  return c;
}

std::vector<int> identity(int n) {
  std::vector<int> m(n);
  std::iota(m.begin(), m.end(), 0);
  return m;
}

}  // namespace

RepairReport repair(PolygonSoup& soup, const RepairOptions& options) {
  check_offsets(soup);
  RepairReport r;
  r.vertex_map = identity(soup.n_vertices());
  r.face_map = identity(soup.n_faces());
  if (options.drop_invalid_faces && options.merge_vertices) {
    // A first pass before merging: merging needs indices in range.
    r.drop = drop_invalid_faces(soup, options.face_drop);
    r.face_map = compose(r.face_map, r.drop.face_map);
  }
  if (options.merge_vertices) {
    r.merge = merge_duplicate_vertices(soup, options.merge_tolerance);
    r.vertex_map = compose(r.vertex_map, r.merge.vertex_map);
  }
  if (options.drop_invalid_faces) {
    FaceDrop d = drop_invalid_faces(soup, options.face_drop);
    r.face_map = compose(r.face_map, d.face_map);
    if (r.drop.face_map.empty()) {
      r.drop = std::move(d);
    } else {  // second pass after merging: add its counts to the first pass's
      r.drop.n_out_of_range += d.n_out_of_range;
      r.drop.n_too_few += d.n_too_few;
      r.drop.n_repeated_vertex += d.n_repeated_vertex;
      r.drop.n_zero_area += d.n_zero_area;
      r.drop.n_collapsed_corners += d.n_collapsed_corners;
      r.drop.face_map = compose(r.drop.face_map, d.face_map);
    }
  }
  if (options.remove_duplicate_faces) {
    r.dedup = remove_duplicate_faces(soup);
    r.face_map = compose(r.face_map, r.dedup.face_map);
  }
  if (options.remove_unreferenced_vertices) {
    r.unreferenced = remove_unreferenced_vertices(soup);
    r.vertex_map = compose(r.vertex_map, r.unreferenced.vertex_map);
  }
  return r;
}

}  // namespace polydec
