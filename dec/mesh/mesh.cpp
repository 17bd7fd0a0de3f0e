// dec/mesh/mesh.cpp — validation of a polygon soup and derivation of the mesh connectivity.
#include "polydec/dec/mesh/mesh.h"

#include "polydec/dec/detail/edge_buckets.h"
#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/detail/scale.h"
#include "polydec/dec/detail/union_find.h"

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <fmt/format.h>
#include <numeric>

namespace polydec {

namespace {

// Rejects non-finite coordinates and magnitudes above kMaxCoordinate (Mesh's documented limit: the
// operators form fourth powers of lengths, which overflow double beyond about 1e77).
void check_position(const Eigen::MatrixX3d& X, long v) {
  if (!X.row(v).allFinite())
    throw InvalidMeshError("vertex", v, fmt::format("vertex {} has a non-finite coordinate", v));
  if (X.row(v).cwiseAbs().maxCoeff() > kMaxCoordinate)
    throw InvalidMeshError("vertex", v,
                           fmt::format("vertex {} has a coordinate of magnitude {:g}, above the limit {:g} (fourth "
                                       "powers of lengths would overflow)",
                                       v, X.row(v).cwiseAbs().maxCoeff(), kMaxCoordinate));
}

}  // namespace

// Rejects a coordinate precision or planarity tolerance outside [0, 1) (NaN included).
void check_coordinate_precision(const CoordinatePrecision& p) {
  for (double x : {p.noise, p.planarity_tolerance})
    if (!(x >= 0 && x < 1))
      throw InvalidMeshError(
          "mesh", 0,
          fmt::format("coordinate precision {:g} outside [0, 1) (relative to the mesh's size)", x));
}

void PolygonSoup::add_face(std::span<const int> f) {
  face_indices.insert(face_indices.end(), f.begin(), f.end());
  face_offsets.push_back(int(face_indices.size()));
}

InvalidMeshError::InvalidMeshError(std::string element_, long index_, const std::string& what)
    : std::runtime_error(what), element(std::move(element_)), index(index_) {}

Mesh::Mesh(PolygonSoup soup) {
  auto t = std::make_shared<Topology>();
  const long nv = soup.positions.rows();
  if (nv > std::numeric_limits<int>::max() / 2) throw InvalidMeshError("vertex", nv, "too many vertices");
  if (soup.face_offsets.empty() || soup.face_offsets.front() != 0 ||
      soup.face_offsets.back() != long(soup.face_indices.size()))
    throw InvalidMeshError("face", 0, "face offsets do not match the face index list");
  const int nf = int(soup.face_offsets.size()) - 1;

  for (long v = 0; v < nv; ++v) check_position(soup.positions, v);
  check_coordinate_precision(soup.precision);
  precision_ = soup.precision;

  // Faces: size, index range, repeated vertices.
  for (int f = 0; f < nf; ++f) {
    const int b = soup.face_offsets[f], e = soup.face_offsets[f + 1];
    if (e - b < 3)
      throw InvalidMeshError("face", f, fmt::format("face {} has {} vertices (at least 3 needed)", f, e - b));
    for (int k = b; k < e; ++k) {
      const int v = soup.face_indices[k];
      if (v < 0 || v >= nv)
        throw InvalidMeshError("face", f,
                               fmt::format("face {} refers to vertex {}, out of range [0, {})", f, v, nv));
    }
    for (int k = b; k < e; ++k)
      for (int l = k + 1; l < e; ++l)
        if (soup.face_indices[k] == soup.face_indices[l])
          throw InvalidMeshError("face", f,
                                 fmt::format("face {} repeats vertex {}", f, soup.face_indices[k]));
    t->max_face_size = std::max(t->max_face_size, e - b);
  }

  const int nh = int(soup.face_indices.size());
  t->face_offsets = std::move(soup.face_offsets);
  t->face_indices = std::move(soup.face_indices);
  // The per-halfedge and per-vertex arrays below take huge pages (dec/detail/huge_pages.h): on a
  // 1.5M-face mesh their first-touch page faults cost more than the work on them.
  assign_on_huge_pages(t->halfedge_face, size_t(nh));
  for (int f = 0; f < nf; ++f)
    for (int h = t->face_offsets[f]; h < t->face_offsets[f + 1]; ++h) t->halfedge_face[h] = f;

  // Undirected edges: sort halfedges by (min, max) key.
  auto next = [&](int h) {
    const int f = t->halfedge_face[h];
    return h + 1 < t->face_offsets[f + 1] ? h + 1 : t->face_offsets[f];
  };
  // Edges in lexicographic order, the halfedges of each ascending (dec/detail/edge_buckets.h).
  const detail::EdgeBuckets buckets = detail::bucket_edges(
      int(nv), nh,
      [&](auto&& emit) {
        for (int h = 0; h < nh; ++h) emit(t->face_indices[h], t->face_indices[next(h)]);
      },
      true);
  const std::vector<int>&bucket_start = buckets.start, &by_edge = buckets.id, &other = buckets.other;
  assign_on_huge_pages(t->halfedge_edge, size_t(nh), -1);
  assign_on_huge_pages(t->halfedge_opposite, size_t(nh), -1);
  std::vector<std::array<int, 2>> edge_list;
  edge_list.reserve(size_t(nh));  // at most one edge per halfedge; pages are touched as used
  advise_huge_pages(edge_list.data(), sizeof(std::array<int, 2>) * size_t(nh));
  for (long v = 0; v < nv; ++v) {
    const int hi = bucket_start[size_t(v) + 1];
    for (int k = bucket_start[size_t(v)]; k < hi;) {
      int l = k;
      while (l < hi && other[size_t(l)] == other[size_t(k)]) ++l;
      const int e = int(edge_list.size());
      const int h0 = by_edge[size_t(k)];
      const int a = int(v), b = other[size_t(k)];
      edge_list.push_back({a, b});
      if (l - k > 2)
        throw InvalidMeshError("edge", e,
                               fmt::format("edge ({}, {}) is shared by {} faces (non-manifold; faces {}, {}, {}...)", a,
                                           b, l - k, t->halfedge_face[by_edge[size_t(k)]],
                                           t->halfedge_face[by_edge[size_t(k) + 1]],
                                           t->halfedge_face[by_edge[size_t(k) + 2]]));
      if (l - k == 2) {
        const int h1 = by_edge[size_t(k) + 1];
        if (t->face_indices[h1] == t->face_indices[h0]) {
          throw InvalidMeshError(
              "edge", e,
              fmt::format("faces {} and {} traverse edge ({}, {}) in the same direction (inconsistent orientation)",
                          t->halfedge_face[h0], t->halfedge_face[h1], a, b));
        }
        t->halfedge_opposite[h0] = h1;
        t->halfedge_opposite[h1] = h0;
      }
      for (int m = k; m < l; ++m) t->halfedge_edge[by_edge[size_t(m)]] = e;
      k = l;
    }
  }
  const int ne = int(edge_list.size());
  t->edges.resize(ne, 2);
  advise_huge_pages(t->edges.data(), sizeof(int) * 2 * size_t(ne));
  assign_on_huge_pages(t->edge_is_boundary, size_t(ne), decltype(t->edge_is_boundary)::value_type(0));
  for (int e = 0; e < ne; ++e) t->edges.row(e) << edge_list[e][0], edge_list[e][1];

  // Boundary: halfedges without opposite.
  t->vertex_is_boundary.assign(nv, 0);
  std::vector<int> boundary_out(nv, -1);  // boundary halfedge leaving each vertex
  bool nonmanifold_boundary = false;
  for (int h = 0; h < nh; ++h) {
    if (t->halfedge_opposite[h] >= 0) continue;
    t->edge_is_boundary[t->halfedge_edge[h]] = 1;
    ++t->n_boundary_edges;
    const int v = t->face_indices[h];
    t->vertex_is_boundary[v] = 1;
    if (boundary_out[v] >= 0) nonmanifold_boundary = true;
    boundary_out[v] = h;
  }
  // Loops: follow boundary halfedges target to target. Where a vertex has two outgoing
  // boundary halfedges (two boundary fans touching at a vertex) we still terminate: every
  // boundary halfedge is visited once.
  std::vector<unsigned char> visited;
  assign_on_huge_pages(visited, size_t(nh), (unsigned char)0);
  std::vector<std::vector<int>> out_lists;
  if (nonmanifold_boundary) {
    out_lists.resize(nv);
    for (int h = 0; h < nh; ++h)
      if (t->halfedge_opposite[h] < 0) out_lists[t->face_indices[h]].push_back(h);
  }
  for (int h = 0; h < nh; ++h) {
    if (t->halfedge_opposite[h] >= 0 || visited[h]) continue;
    std::vector<int> loop;
    int g = h;
    while (g >= 0 && !visited[g]) {
      visited[g] = 1;
      loop.push_back(t->face_indices[g]);
      const int w = t->face_indices[next(g)];
      int nextg = boundary_out[w];
      if (nonmanifold_boundary) {
        nextg = -1;
        for (int c : out_lists[w])
          if (!visited[c]) {
            nextg = c;
            break;
          }
      }
      g = nextg;
    }
    t->boundary_loops.push_back(std::move(loop));
  }

  // Vertex-face adjacency (faces ascending by construction).
  t->vertex_face_offsets.assign(nv + 1, 0);
  for (int h = 0; h < nh; ++h) ++t->vertex_face_offsets[t->face_indices[h] + 1];
  for (long v = 0; v < nv; ++v) t->vertex_face_offsets[v + 1] += t->vertex_face_offsets[v];
  assign_on_huge_pages(t->vertex_face_indices, size_t(nh));
  {
    std::vector<int> fill(t->vertex_face_offsets.begin(), t->vertex_face_offsets.end() - 1);
    for (int h = 0; h < nh; ++h) t->vertex_face_indices[fill[t->face_indices[h]]++] = t->halfedge_face[h];
  }
  for (long v = 0; v < nv; ++v)
    if (t->vertex_face_offsets[v + 1] == t->vertex_face_offsets[v]) ++t->n_unreferenced;

  // Connected components of referenced vertices (union-find over edges).
  std::vector<int> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  for (int e = 0; e < ne; ++e) {
    const int a = find_root(parent, t->edges(e, 0)), b = find_root(parent, t->edges(e, 1));
    if (a != b) parent[a] = b;
  }
  for (long v = 0; v < nv; ++v)
    if (t->vertex_face_offsets[v + 1] > t->vertex_face_offsets[v] && find_root(parent, int(v)) == v)
      ++t->n_components;

  positions_ = std::move(soup.positions);
  topo_ = std::move(t);
}

Mesh Mesh::with_positions(Eigen::MatrixX3d positions) const {
  if (positions.rows() != positions_.rows())
    throw InvalidMeshError("vertex", positions.rows(),
                           fmt::format("with_positions: {} rows given, mesh has {} vertices", positions.rows(),
                                       positions_.rows()));
  for (long v = 0; v < positions.rows(); ++v) check_position(positions, v);
  Mesh m;
  m.positions_ = std::move(positions);
  m.precision_ = precision_;
  m.topo_ = topo_;
  return m;
}

Mesh Mesh::with_precision(const CoordinatePrecision& precision) const {
  check_coordinate_precision(precision);
  Mesh m = *this;
  m.precision_ = precision;
  return m;
}

double rms_radius(const Eigen::MatrixX3d& X) {
  if (X.rows() == 0) return 0.0;
  // Coordinates far outside the ordinary sizes (volumes accept up to kMaxVolumeCoordinate): in
  // units of 2^e, so that the squares hold.
  const int e = detail::normalizing_exponent(X.cwiseAbs().maxCoeff());
  if (e != 0) return std::ldexp(rms_radius(X * std::ldexp(1.0, -e)), e);
  const Eigen::RowVector3d c = X.colwise().mean();
  return std::sqrt((X.rowwise() - c).rowwise().squaredNorm().mean());
}

double Mesh::rms_radius() const { return polydec::rms_radius(positions_); }

double Mesh::mean_edge_length() const {
  if (n_edges() == 0) return 0.0;
  double sum = 0.0;
  for (int e = 0; e < n_edges(); ++e) sum += (positions_.row(edges()(e, 0)) - positions_.row(edges()(e, 1))).norm();
  return sum / n_edges();
}

double Mesh::bounding_box_diagonal() const {
  if (n_vertices() == 0) return 0.0;
  return (positions_.colwise().maxCoeff() - positions_.colwise().minCoeff()).norm();
}

}  // namespace polydec
