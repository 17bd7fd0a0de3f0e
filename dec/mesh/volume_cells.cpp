// dec/mesh/volume_cells.cpp — cell shape recognition for dec/mesh/volume_cells.h.
#include "polydec/dec/mesh/volume_cells.h"

#include <algorithm>
#include <vector>

#include "polydec/dec/mesh/polyhedron_builder.h"

namespace polydec {
namespace volume_cells_detail {
namespace {

// The outward vertex cycle of half-face h.
std::vector<int> outward(const VolumeMesh& m, int h) {
  const auto f = m.face(h / 2);
  std::vector<int> p(f.begin(), f.end());
  if (h & 1) std::reverse(p.begin() + 1, p.end());
  return p;
}

// The neighbour of v along the cell's edges that is not in `exclude`; -1 unless exactly one.
int third_neighbour(const std::vector<std::pair<int, int>>& edges, int v, std::span<const int> exclude) {
  int found = -1, count = 0;
  for (const auto& [a, b] : edges) {
    const int w = a == v ? b : b == v ? a : -1;
    if (w < 0 || std::find(exclude.begin(), exclude.end(), w) != exclude.end()) continue;
    found = w;
    ++count;
  }
  return count == 1 ? found : -1;
}

// True when the template faces of `type` on `order` are exactly the cell's outward faces.
bool matches(const VolumeMesh& m, int c, int type, const std::array<int, 8>& order) {
  const auto& faces = vtk_cell_faces(type);
  if (int(faces.size()) != m.cell_size(c)) return false;
  for (const auto& tf : faces) {
    bool found = false;
    for (int h : m.cell(c)) {
      const std::vector<int> p = outward(m, h);
      if (p.size() != tf.size()) continue;
      for (size_t s = 0; s < p.size() && !found; ++s) {
        bool same = true;
        for (size_t i = 0; i < p.size() && same; ++i) same = p[(s + i) % p.size()] == order[tf[i]];
        found = same;
      }
      if (found) break;
    }
    if (!found) return false;
  }
  return true;
}

}  // namespace
}  // namespace volume_cells_detail

const char* cell_shape_name(CellShape shape) {
  switch (shape) {
    case CellShape::tetrahedron:
      return "tetrahedron";
    case CellShape::pyramid:
      return "pyramid";
    case CellShape::wedge:
      return "wedge";
    case CellShape::hexahedron:
      return "hexahedron";
    default:
      return "other";
  }
}

CellShape cell_shape(const VolumeMesh& m, int c, std::array<int, 8>* vtk_order) {
  using namespace volume_cells_detail;
  int tris = 0, quads = 0, first_tri = -1, first_quad = -1;
  for (int h : m.cell(c)) {
    const int n = m.face_size(h / 2);
    if (n == 3 && tris++ == 0) first_tri = h;
    if (n == 4 && quads++ == 0) first_quad = h;
  }
  const int nf = m.cell_size(c), nv = int(m.cell_vertices(c).size());
  int type = 0;
  if (nf == 4 && tris == 4 && nv == 4)
    type = kVtkTetra;
  else if (nf == 5 && tris == 4 && quads == 1 && nv == 5)
    type = kVtkPyramid;
  else if (nf == 5 && tris == 2 && quads == 3 && nv == 6)
    type = kVtkWedge;
  else if (nf == 6 && quads == 6 && nv == 8)
    type = kVtkHexahedron;
  if (type == 0) return CellShape::other;

  std::vector<std::pair<int, int>> edges;
  for (int h : m.cell(c)) {
    const auto f = m.face(h / 2);
    for (size_t i = 0; i < f.size(); ++i) {
      const int a = f[i], b = f[(i + 1) % f.size()];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  std::array<int, 8> o;
  o.fill(-1);
  CellShape shape = CellShape::other;
  if (type == kVtkTetra) {
    const auto p = outward(m, first_tri);  // = (v0, v2, v1)
    o[0] = p[0], o[2] = p[1], o[1] = p[2];
    for (int v : m.cell_vertices(c))
      if (v != p[0] && v != p[1] && v != p[2]) o[3] = v;
    shape = CellShape::tetrahedron;
  } else if (type == kVtkPyramid) {
    const auto p = outward(m, first_quad);  // = (v0, v3, v2, v1)
    o[0] = p[0], o[3] = p[1], o[2] = p[2], o[1] = p[3];
    for (int v : m.cell_vertices(c))
      if (std::find(p.begin(), p.end(), v) == p.end()) o[4] = v;
    shape = CellShape::pyramid;
  } else if (type == kVtkWedge) {
    const auto p = outward(m, first_tri);  // = (v0, v1, v2)
    for (int i = 0; i < 3; ++i) o[i] = p[i];
    for (int i = 0; i < 3; ++i) o[3 + i] = third_neighbour(edges, p[i], p);
    shape = CellShape::wedge;
  } else {
    const auto p = outward(m, first_quad);  // = (v0, v3, v2, v1)
    o[0] = p[0], o[3] = p[1], o[2] = p[2], o[1] = p[3];
    for (int i = 0; i < 4; ++i) o[4 + i] = third_neighbour(edges, o[i], p);
    shape = CellShape::hexahedron;
  }
  for (int i = 0; i < vtk_cell_size(type); ++i)
    if (o[i] < 0) return CellShape::other;
  if (!matches(m, c, type, o)) return CellShape::other;
  if (vtk_order) *vtk_order = o;
  return shape;
}

}  // namespace polydec
