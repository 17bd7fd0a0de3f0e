// dec/mesh/volume_mesh.cpp — validation of a polyhedron soup (closed, consistently oriented cells),
// orientation of the half-faces outward, and the derived connectivity of VolumeMesh.
#include "polydec/dec/mesh/volume_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "polydec/dec/detail/edge_buckets.h"
#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/detail/scale.h"
#include "polydec/dec/detail/union_find.h"

namespace polydec {
namespace volume_mesh_detail {
namespace {

void check_position(const Eigen::MatrixX3d& X, long v) {
  if (!X.row(v).allFinite())
    throw InvalidMeshError("vertex", v, fmt::format("vertex {} has a non-finite coordinate", v));
  if (X.row(v).cwiseAbs().maxCoeff() > kMaxVolumeCoordinate)
    throw InvalidMeshError("vertex", v,
                           fmt::format("vertex {} has a coordinate of magnitude {:g}, above the limit {:g}",
                                       v, X.row(v).cwiseAbs().maxCoeff(), kMaxVolumeCoordinate));
}

void check_offsets(const std::vector<int>& offsets, size_t n_indices, const char* element) {
  if (offsets.empty() || offsets.front() != 0 || offsets.back() != long(n_indices))
    throw InvalidMeshError(element, 0,
                           fmt::format("{} offsets do not match the {} index list", element, element));
  for (size_t k = 0; k + 1 < offsets.size(); ++k)
    if (offsets[k] > offsets[k + 1])
      throw InvalidMeshError(element, long(k),
                             fmt::format("{} offsets decrease at {} {}", element, element, k));
}

// Signed volume of the closed surface given by half-faces `hf`, as v 2^(3 e): each face split into
// triangles (c_f, x_i, x_{i+1}) around its vertex centroid c_f (independent of where the face's
// vertex cycle starts), tetrahedra to the origin `o` (the first vertex of the first face):
// 1/6 sum (c - o) . ((a - o) x (b - o)), in coordinates relative to o scaled by 2^-e (e = 0 for
// ordinary sizes, dec/detail/scale.h), so that cells of any representable size get a volume.
struct ScaledVolume {
  double v = 0;
  int e = 0;
};
ScaledVolume signed_volume(const Eigen::MatrixX3d& X, const std::vector<int>& fo, const std::vector<int>& fi,
                           std::span<const int> hf) {
  if (hf.empty()) return {};
  const Eigen::Vector3d o = X.row(fi[fo[hf[0] / 2]]).transpose();
  double extent = 0;
  for (int h : hf)
    for (int k = fo[h / 2]; k < fo[h / 2 + 1]; ++k) extent = std::fmax(extent, (X.row(fi[k]).transpose() - o).cwiseAbs().maxCoeff());
  const int e = detail::normalizing_exponent(extent);
  const double inv = std::ldexp(1.0, -e);
  auto at = [&](int k) -> Eigen::Vector3d { return (X.row(fi[k]).transpose() - o) * inv; };
  double v6 = 0.0;
  for (int h : hf) {
    const int f = h / 2, b = fo[f], n = fo[f + 1] - b;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k) c += X.row(fi[b + k]).transpose();
    c = (c / double(n) - o) * inv;
    for (int k = 0; k < n; ++k) {
      Eigen::Vector3d p = at(b + k), q = at(b + (k + 1) % n);
      if (h & 1) std::swap(p, q);
      v6 += c.dot(p.cross(q));
    }
  }
  return {v6 / 6.0, e};
}

}  // namespace
}  // namespace volume_mesh_detail

using namespace volume_mesh_detail;

int PolyhedronSoup::add_face(std::span<const int> f) {
  face_indices.insert(face_indices.end(), f.begin(), f.end());
  face_offsets.push_back(int(face_indices.size()));
  return n_faces() - 1;
}

void PolyhedronSoup::add_cell(std::span<const int> halffaces) {
  cell_halffaces.insert(cell_halffaces.end(), halffaces.begin(), halffaces.end());
  cell_offsets.push_back(int(cell_halffaces.size()));
}

VolumeMesh::VolumeMesh(PolyhedronSoup soup) {
  auto t = std::make_shared<Topology>();
  const long nv = soup.positions.rows();
  if (nv > std::numeric_limits<int>::max() / 2) throw InvalidMeshError("vertex", nv, "too many vertices");
  check_offsets(soup.face_offsets, soup.face_indices.size(), "face");
  check_offsets(soup.cell_offsets, soup.cell_halffaces.size(), "cell");
  const int nf = int(soup.face_offsets.size()) - 1, nc = int(soup.cell_offsets.size()) - 1;
  if (nf > std::numeric_limits<int>::max() / 2) throw InvalidMeshError("face", nf, "too many faces");
  const auto& fo = soup.face_offsets;
  const auto& fi = soup.face_indices;

  for (long v = 0; v < nv; ++v) check_position(soup.positions, v);
  check_coordinate_precision(soup.precision);
  precision_ = soup.precision;

  // Faces: size, index range, repeated vertices, duplicates (same vertex set as another face).
  std::vector<int> sorted(fi);  // each face's vertices ascending, same offsets
  for (int f = 0; f < nf; ++f) {
    const int b = fo[f], e = fo[f + 1];
    if (e - b < 3)
      throw InvalidMeshError("face", f, fmt::format("face {} has {} vertices (at least 3 needed)", f, e - b));
    for (int k = b; k < e; ++k)
      if (fi[k] < 0 || fi[k] >= nv)
        throw InvalidMeshError(
            "face", f, fmt::format("face {} refers to vertex {}, out of range [0, {})", f, fi[k], nv));
    std::sort(sorted.begin() + b, sorted.begin() + e);
    if (const auto r = std::adjacent_find(sorted.begin() + b, sorted.begin() + e); r != sorted.begin() + e)
      throw InvalidMeshError("face", f, fmt::format("face {} repeats vertex {}", f, *r));
  }
  {
    auto key = [&](int f) { return std::span<const int>(sorted.data() + fo[f], size_t(fo[f + 1] - fo[f])); };
    std::vector<int> order(nf);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const auto ka = key(a), kb = key(b);
      if (ka.size() != kb.size()) return ka.size() < kb.size();
      if (!std::equal(ka.begin(), ka.end(), kb.begin()))
        return std::lexicographical_compare(ka.begin(), ka.end(), kb.begin(), kb.end());
      return a < b;
    });
    for (int k = 0; k + 1 < nf; ++k) {
      const auto ka = key(order[k]), kb = key(order[k + 1]);
      if (ka.size() == kb.size() && std::equal(ka.begin(), ka.end(), kb.begin()))
        throw InvalidMeshError(
            "face", order[k + 1],
            fmt::format("face {} has the same vertices as face {} (duplicate face)", order[k + 1], order[k]));
    }
  }

  // Cells: half-face range, each face at most once per cell and in at most two cells, with
  // opposite half-faces when shared.
  std::vector<std::array<int, 2>> use(nf, {-1, -1});  // cell using 2f, cell using 2f+1
  for (int c = 0; c < nc; ++c) {
    const int b = soup.cell_offsets[c], e = soup.cell_offsets[c + 1];
    if (e - b < 4)
      throw InvalidMeshError("cell", c, fmt::format("cell {} has {} faces (at least 4 needed)", c, e - b));
    for (int k = b; k < e; ++k) {
      const int h = soup.cell_halffaces[k];
      if (h < 0 || h >= 2 * nf)
        throw InvalidMeshError(
            "cell", c, fmt::format("cell {} refers to half-face {}, out of range [0, {})", c, h, 2 * nf));
      const int f = h / 2, s = h & 1;
      if (use[f][0] == c || use[f][1] == c)
        throw InvalidMeshError("cell", c, fmt::format("cell {} uses face {} twice", c, f));
      if (use[f][s] >= 0) {
        if (use[f][1 - s] >= 0)
          throw InvalidMeshError(
              "face", f,
              fmt::format("face {} is used by three or more cells ({}, {}, {})", f, use[f][0], use[f][1], c));
        throw InvalidMeshError(
            "face", f,
            fmt::format("cells {} and {} use face {} with the same orientation (half-face {}; inconsistent "
                        "orientation: a shared face must appear as 2f in one cell and 2f+1 in the other)",
                        use[f][s], c, f, h));
      }
      use[f][s] = c;
    }
  }
  for (int f = 0; f < nf; ++f)
    if (use[f][0] < 0 && use[f][1] < 0)
      throw InvalidMeshError("face", f, fmt::format("face {} belongs to no cell", f));

  // Each cell closed (every edge of its half-faces twice, in opposite directions) and connected.
  {
    std::vector<std::array<int, 4>> he;  // (min, max, direction a<b, local face)
    std::vector<int> parent;
    for (int c = 0; c < nc; ++c) {
      const int b = soup.cell_offsets[c], e = soup.cell_offsets[c + 1];
      he.clear();
      for (int k = b; k < e; ++k) {
        const int h = soup.cell_halffaces[k], f = h / 2, n = fo[f + 1] - fo[f];
        for (int i = 0; i < n; ++i) {
          int p = fi[fo[f] + i], q = fi[fo[f] + (i + 1) % n];
          if (h & 1) std::swap(p, q);
          he.push_back({std::min(p, q), std::max(p, q), p < q ? 1 : 0, k - b});
        }
      }
      std::sort(he.begin(), he.end());
      parent.resize(e - b);
      std::iota(parent.begin(), parent.end(), 0);
      for (size_t i = 0; i < he.size();) {
        size_t j = i;
        while (j < he.size() && he[j][0] == he[i][0] && he[j][1] == he[i][1]) ++j;
        if (j - i != 2)
          throw InvalidMeshError(
              "cell", c,
              fmt::format("cell {} is not closed: its edge ({}, {}) is used by {} of its faces "
                          "(exactly 2 needed)",
                          c, he[i][0], he[i][1], j - i));
        if (he[i][2] == he[i + 1][2])
          throw InvalidMeshError(
              "cell", c,
              fmt::format("cell {}: two of its half-faces traverse edge ({}, {}) in the same "
                          "direction (inconsistently oriented faces within the cell)",
                          c, he[i][0], he[i][1]));
        const int r0 = find_root(parent, he[i][3]), r1 = find_root(parent, he[i + 1][3]);
        if (r0 != r1) parent[r0] = r1;
        i = j;
      }
      const int root = find_root(parent, 0);
      for (int k = 1; k < e - b; ++k)
        if (find_root(parent, k) != root)
          throw InvalidMeshError(
              "cell", c,
              fmt::format("cell {} is not connected (face {} is apart)", c, soup.cell_halffaces[b + k] / 2));
    }
  }

  // Orientation: consistently inward cells (negative total volume) are flipped once.
  // The cells' volumes summed in the units of the largest cell (ordinary meshes: all in units of 1).
  std::vector<ScaledVolume> volumes(static_cast<size_t>(nc));
  int largest = std::numeric_limits<int>::min();
  for (int c = 0; c < nc; ++c) {
    const int b = soup.cell_offsets[c], e = soup.cell_offsets[c + 1];
    volumes[size_t(c)] = signed_volume(soup.positions, fo, fi, {soup.cell_halffaces.data() + b, size_t(e - b)});
    largest = std::max(largest, volumes[size_t(c)].e);
  }
  double total = 0.0;
  for (const ScaledVolume& v : volumes) total += std::ldexp(v.v, 3 * (v.e - largest));
  if (total < 0) {
    for (int& h : soup.cell_halffaces) h ^= 1;
    for (auto& u : use) std::swap(u[0], u[1]);
  }
  t->face_cells = std::move(use);

  // Cell vertices, ascending.
  t->cell_vertex_offsets.reserve(nc + 1);
  for (int c = 0; c < nc; ++c) {
    sorted.clear();
    for (int k = soup.cell_offsets[c]; k < soup.cell_offsets[c + 1]; ++k) {
      const int f = soup.cell_halffaces[k] / 2;
      sorted.insert(sorted.end(), fi.begin() + fo[f], fi.begin() + fo[f + 1]);
    }
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    t->cell_vertex_indices.insert(t->cell_vertex_indices.end(), sorted.begin(), sorted.end());
    t->cell_vertex_offsets.push_back(int(t->cell_vertex_indices.size()));
  }

  // Undirected edges of the faces, lexicographic (dec/detail/edge_buckets.h).
  {
    const auto each_side = [&](auto&& emit) {
      for (int f = 0; f < nf; ++f)
        for (int k = fo[f]; k < fo[f + 1]; ++k) emit(fi[size_t(k)], fi[size_t(k + 1 < fo[f + 1] ? k + 1 : fo[f])]);
    };
    const detail::EdgeBuckets buckets = detail::bucket_edges(int(nv), int(fi.size()), each_side, false);
    // Calls edge(v, w) once per distinct pair, in lexicographic order.
    auto each_edge = [&](auto&& edge) {
      for (int v = 0; v < int(nv); ++v)
        for (int k = buckets.start[size_t(v)]; k < buckets.start[size_t(v) + 1]; ++k)
          if (k == buckets.start[size_t(v)] || buckets.other[size_t(k)] != buckets.other[size_t(k) - 1])
            edge(v, buckets.other[size_t(k)]);
    };
    Eigen::Index ne = 0;
    each_edge([&](int, int) { ++ne; });
    t->edges.resize(ne, 2);
    advise_huge_pages(t->edges.data(), sizeof(int) * 2 * size_t(ne));
    Eigen::Index e = 0;
    each_edge([&](int v, int w) { t->edges(e, 0) = v, t->edges(e, 1) = w, ++e; });
  }

  // Boundary and unreferenced vertices.
  t->vertex_is_boundary.assign(nv, 0);
  std::vector<unsigned char> referenced(nv, 0);
  for (int f = 0; f < nf; ++f) {
    const bool boundary = t->face_cells[f][0] < 0 || t->face_cells[f][1] < 0;
    for (int k = fo[f]; k < fo[f + 1]; ++k) {
      referenced[fi[k]] = 1;
      if (boundary) t->vertex_is_boundary[fi[k]] = 1;
    }
  }
  t->n_unreferenced = int(std::count(referenced.begin(), referenced.end(), 0));

  t->face_offsets = std::move(soup.face_offsets);
  t->face_indices = std::move(soup.face_indices);
  t->cell_offsets = std::move(soup.cell_offsets);
  t->cell_halffaces = std::move(soup.cell_halffaces);
  positions_ = std::move(soup.positions);
  topo_ = std::move(t);
}

VolumeMesh VolumeMesh::with_positions(Eigen::MatrixX3d positions) const {
  if (positions.rows() != positions_.rows())
    throw InvalidMeshError("vertex", positions.rows(),
                           fmt::format("with_positions: {} rows given, mesh has {} vertices",
                                       positions.rows(), positions_.rows()));
  for (long v = 0; v < positions.rows(); ++v) check_position(positions, v);
  VolumeMesh m;
  m.positions_ = std::move(positions);
  m.precision_ = precision_;
  m.topo_ = topo_;
  return m;
}

VolumeMesh VolumeMesh::with_precision(const CoordinatePrecision& precision) const {
  check_coordinate_precision(precision);
  VolumeMesh m = *this;
  m.precision_ = precision;
  return m;
}

double VolumeMesh::rms_radius() const { return polydec::rms_radius(positions_); }

Mesh VolumeMesh::boundary_surface() const {
  PolygonSoup s;
  s.positions = positions_;
  s.precision = precision_;
  std::vector<int> poly;
  for (int f = 0; f < n_faces(); ++f) {
    const auto fc = face_cells(f);
    if (fc[0] >= 0 && fc[1] >= 0) continue;
    const auto verts = face(f);
    poly.assign(verts.begin(), verts.end());
    if (fc[0] < 0) std::reverse(poly.begin() + 1, poly.end());  // the cell has 2f+1: reversed is outward
    s.add_face(poly);
  }
  return Mesh(std::move(s));
}

double VolumeMesh::cell_volume(int c) const {
  const ScaledVolume v = signed_volume(positions_, topo_->face_offsets, topo_->face_indices, cell(c));
  const double r = std::ldexp(v.v, 3 * v.e);
  // Overflow to inf, or underflow below the normal doubles (precision lost, or a true volume read as 0).
  if (!std::isfinite(r) || (v.v != 0 && std::fabs(r) < std::numeric_limits<double>::min()))
    throw InvalidMeshError("cell", c,
                           fmt::format("cell {} has a volume of about 1e{:+.0f}, outside what double holds; rescale the mesh",
                                       c, std::log10(std::fabs(v.v)) + 3 * v.e * std::log10(2.0)));
  return r;
}

double VolumeMesh::volume() const {
  double v = 0.0;
  for (int c = 0; c < n_cells(); ++c) v += cell_volume(c);
  if (!std::isfinite(v))
    throw InvalidMeshError("mesh", -1, "the cells' volumes are each finite but their sum is beyond what double holds; "
                                       "rescale the mesh");
  return v;
}

double VolumeMesh::mean_edge_length() const {
  const auto& E = edges();
  if (E.rows() == 0) return 0.0;
  // Lengths in units of 2^s when the mesh is far outside the ordinary sizes (their squares would not hold).
  const int s = detail::normalizing_exponent(bounding_box_diagonal());
  const double inv = std::ldexp(1.0, -s);
  double sum = 0.0;
  for (Eigen::Index e = 0; e < E.rows(); ++e)
    sum += ((positions_.row(E(e, 1)) - positions_.row(E(e, 0))) * inv).norm();
  return std::ldexp(sum / double(E.rows()), s);
}

double VolumeMesh::bounding_box_diagonal() const {
  if (positions_.rows() == 0) return 0.0;
  const Eigen::RowVector3d d = positions_.colwise().maxCoeff() - positions_.colwise().minCoeff();
  const int s = detail::normalizing_exponent(d.cwiseAbs().maxCoeff());
  return std::ldexp((d * std::ldexp(1.0, -s)).norm(), s);
}

void check_length_power(const VolumeMesh& mesh, int power, const std::string& what) {
  check_length_powers(mesh, {{power, what}});
}

void check_length_powers(const VolumeMesh& mesh, const std::vector<LengthPower>& quantities) {
  if (std::all_of(quantities.begin(), quantities.end(), [](const LengthPower& q) { return q.power == 0; })) return;
  // Each edge's binary exponent from its largest coordinate difference (no squares that could
  // overflow); the length is within sqrt(3) of it.
  const auto& E = mesh.edges();
  const auto& X = mesh.positions();
  int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
  Eigen::Index e_lo = -1, e_hi = -1;
  for (Eigen::Index e = 0; e < E.rows(); ++e) {
    const double d = (X.row(E(e, 1)) - X.row(E(e, 0))).cwiseAbs().maxCoeff();
    if (!(d > 0)) continue;
    const int k = std::ilogb(d);
    if (k < lo) lo = k, e_lo = e;
    if (k > hi) hi = k, e_hi = e;
  }
  constexpr int kLimit = 960;
  for (const LengthPower& q : quantities)
    for (const Eigen::Index e : {e_lo, e_hi}) {
      if (e < 0) continue;
      const double d = (X.row(E(e, 1)) - X.row(E(e, 0))).cwiseAbs().maxCoeff();
      const long p = long(q.power) * std::ilogb(d);
      if (p > kLimit || p < -kLimit)
        throw InvalidMeshError(
            "edge", long(e),
            fmt::format("edge {} has a length of about {:.3g}: {} scale as length^{} and would reach about "
                        "1e{:+.0f}, outside what double holds with full precision (about 1e-289 .. 1e289); "
                        "rescale the mesh",
                        e, d, q.what, q.power, double(q.power) * std::log10(d)));
    }
}

std::vector<LengthPower> star_length_powers(int max_degree) {
  std::vector<LengthPower> stars;
  for (int k = 0; k <= max_degree; ++k) stars.push_back({3 - 2 * k, "star" + std::to_string(k) + "'s entries"});
  return stars;
}

}  // namespace polydec
