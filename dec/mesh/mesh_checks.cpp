// dec/mesh/mesh_checks.cpp — diagnostics of a validated mesh.
#include "polydec/dec/mesh/mesh_checks.h"
#include "polydec/dec/detail/face_shape.h"
#include "polydec/dec/detail/union_find.h"

#include <fmt/format.h>

#include <algorithm>
#include <compare>
#include <numeric>
#include <span>

namespace polydec {

namespace {

// "a, b, c" for the first few items, "..." after.
template <class T, class F>
std::string first_few(const std::vector<T>& items, F format) {
  std::string s;
  for (size_t i = 0; i < items.size() && i < 5; ++i) s += (i ? ", " : "") + format(items[i]);
  if (items.size() > 5) s += ", ...";
  return s;
}

}  // namespace

bool MeshReport::clean() const {
  return duplicate_faces.empty() && zero_area_faces.empty() && thin_faces.empty() &&
         collinear_corners.empty() && non_manifold_vertices.empty() && unreferenced_vertices.empty() &&
         n_components <= 1 && fan.ok();
}

std::vector<std::string> MeshReport::summary() const {
  std::vector<std::string> s;
  auto num = [](int i) { return std::to_string(i); };
  if (!duplicate_faces.empty())
    s.push_back(fmt::format(
        "{} duplicate faces (face = earlier face): {}", duplicate_faces.size(),
        first_few(duplicate_faces, [](auto p) { return fmt::format("{} = {}", p.first, p.second); })));
  if (!zero_area_faces.empty())
    s.push_back(
        fmt::format("{} zero-area faces: {}", zero_area_faces.size(), first_few(zero_area_faces, num)));
  if (!thin_faces.empty())
    s.push_back(fmt::format("{} extremely thin faces: {}", thin_faces.size(), first_few(thin_faces, num)));
  if (!collinear_corners.empty())
    s.push_back(fmt::format("{} collinear consecutive corners (face: vertex): {}", collinear_corners.size(),
                            first_few(collinear_corners, [](const CollinearCorner& c) {
                              return fmt::format("{}: {}{}", c.face, c.vertex, c.spike ? " (spike)" : "");
                            })));
  if (!non_manifold_vertices.empty())
    s.push_back(fmt::format("{} non-manifold vertices: {}", non_manifold_vertices.size(),
                            first_few(non_manifold_vertices, num)));
  if (!unreferenced_vertices.empty())
    s.push_back(fmt::format("{} unreferenced vertices: {}", unreferenced_vertices.size(),
                            first_few(unreferenced_vertices, num)));
  if (n_components > 1)
    s.push_back(
        fmt::format("{} connected components (faces: {})", n_components, first_few(component_faces, num)));
  if (fan.n_degenerate > 0 || fan.n_inverted > 0)
    s.push_back(
        fmt::format("fan triangles: {} degenerate (no stiffness, no gradient), {} inverted, in {} faces",
                    fan.n_degenerate, fan.n_inverted, fan.n_faces_affected));
  return s;
}

MeshReport check_mesh(const Mesh& mesh, const MeshCheckOptions& options) {
  MeshReport r;
  const int nv = mesh.n_vertices(), nf = mesh.n_faces(), nh = mesh.n_halfedges();

  // Duplicate faces: same cyclic vertex sequence, either direction. Such faces start their
  // canonical cycles (stored like the faces, at Mesh::face_offsets) with the same smallest vertex,
  // so only the faces of one smallest vertex (a counting sort: faster here than scanning
  // Mesh::vertex_faces) are compared: sorted by their cycles, then by number, each is paired with
  // the first of its run.
  const std::vector<int>& key_start = mesh.face_offsets();
  std::vector<int> key(static_cast<size_t>(nh)), by_first(size_t(nv) + 1, 0);
  for (int f = 0; f < nf; ++f) {
    canonical_cycle(mesh.face(f), key.data() + key_start[size_t(f)]);
    ++by_first[size_t(key[size_t(key_start[size_t(f)])]) + 1];
  }
  std::partial_sum(by_first.begin(), by_first.end(), by_first.begin());
  std::vector<int> faces_by_first(static_cast<size_t>(nf));
  {
    std::vector<int> next(by_first.begin(), by_first.end() - 1);
    for (int f = 0; f < nf; ++f) faces_by_first[size_t(next[size_t(key[size_t(key_start[size_t(f)])])]++)] = f;
  }
  auto cycle = [&](int f) {
    const int b = key_start[size_t(f)], e = key_start[size_t(f) + 1];
    return std::span<const int>(key.data() + b, size_t(e - b));
  };
  for (int v = 0; v < nv; ++v) {
    const auto begin = faces_by_first.begin() + by_first[size_t(v)];
    const auto end = faces_by_first.begin() + by_first[size_t(v) + 1];
    if (end - begin < 2) continue;
    std::sort(begin, end, [&](int a, int b) {
      const auto ka = cycle(a), kb = cycle(b);
      if (ka.size() != kb.size()) return ka.size() < kb.size();
      const auto c = std::lexicographical_compare_three_way(ka.begin(), ka.end(), kb.begin(), kb.end());
      return c != 0 ? c < 0 : a < b;
    });
    for (auto it = begin + 1, first = begin; it != end; ++it) {
      if (std::ranges::equal(cycle(*it), cycle(*first)))
        r.duplicate_faces.emplace_back(*it, *first);
      else
        first = it;
    }
  }
  std::sort(r.duplicate_faces.begin(), r.duplicate_faces.end());

  // Shape of each face: singular values of the centred corners; corners with collinear edges.
  for (int f = 0; f < nf; ++f) {
    const PolygonPositions X = face_positions(mesh, f);
    const Eigen::Vector3d sigma = centred_singular_values(X);
    if (sigma[1] <= options.zero_area_tolerance * sigma[0])
      r.zero_area_faces.push_back(f);
    else if (sigma[1] < options.thin_ratio * sigma[0])
      r.thin_faces.push_back(f);
    const int n = int(X.rows());
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d a = (X.row(k) - X.row((k + n - 1) % n)).transpose();
      const Eigen::Vector3d b = (X.row((k + 1) % n) - X.row(k)).transpose();
      if (a.cross(b).norm() <= options.collinear_tolerance * a.norm() * b.norm())
        r.collinear_corners.push_back({f, mesh.face(f)[k], a.dot(b) < 0});
    }
  }

  // Non-manifold vertices: corners (halfedges by source) around a vertex are joined across
  // each interior edge incident to it; more than one group means more than one fan.
  std::vector<int> parent(nh);
  std::iota(parent.begin(), parent.end(), 0);
  for (int h = 0; h < nh; ++h) {
    const int o = mesh.halfedge_opposite(h);
    if (o < 0) continue;
    const int a = find_root(parent, h),
              b = find_root(parent, mesh.halfedge_next(o));  // both corners at source(h)
    if (a != b) parent[a] = b;
  }
  std::vector<int> first_root(nv, -1);
  std::vector<unsigned char> flagged(nv, 0);
  for (int h = 0; h < nh; ++h) {
    const int v = mesh.halfedge_source(h), root = find_root(parent, h);
    if (first_root[v] < 0)
      first_root[v] = root;
    else if (first_root[v] != root)
      flagged[v] = 1;
  }
  for (int v = 0; v < nv; ++v) {
    if (flagged[v]) r.non_manifold_vertices.push_back(v);
    if (mesh.vertex_faces(v).empty()) r.unreferenced_vertices.push_back(v);
  }

  // Components of referenced vertices, numbered by their lowest vertex.
  std::vector<int> vp(nv);
  std::iota(vp.begin(), vp.end(), 0);
  for (int e = 0; e < mesh.n_edges(); ++e) {
    const int a = find_root(vp, mesh.edges()(e, 0)), b = find_root(vp, mesh.edges()(e, 1));
    if (a != b) vp[std::max(a, b)] = std::min(a, b);
  }
  r.component.assign(nv, -1);
  std::vector<int> id(nv, -1);
  for (int v = 0; v < nv; ++v) {
    if (mesh.vertex_faces(v).empty()) continue;
    const int root = find_root(vp, v);
    if (id[root] < 0) id[root] = r.n_components++;
    r.component[v] = id[root];
  }
  r.component_faces.assign(r.n_components, 0);
  for (int f = 0; f < nf; ++f) ++r.component_faces[r.component[mesh.face(f)[0]]];

  r.fan = refine(mesh, options.refinement).quality;
  return r;
}

}  // namespace polydec
