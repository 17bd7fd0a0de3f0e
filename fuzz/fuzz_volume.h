// fuzz/fuzz_volume.h — the contract every fuzzed volume file must satisfy: the reader throws
// FileError (naming the file, with a reason and a sane line) or returns a soup with consistent
// offsets and indices in range; VolumeMesh then throws only InvalidMeshError or yields a mesh
// whose volume is finite (or refused as beyond double) and which survives OVM, VTK ASCII and VTK BINARY round trips (same
// cells, same volume) and, when its cells are MEDIT's kinds, a binary MEDIT round trip (same cells and
// positions); the MEDIT readers' references make groups of sorted indices in range.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string_view>

#include "polydec/dec/detail/msh_io.h"
#include "polydec/dec/io/volume_io.h"

namespace polydec::fuzz_volume {

inline void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "contract violated: %s\n", what);
    std::abort();
  }
}

inline bool offsets_ok(const std::vector<int>& o, size_t n) {
  if (o.empty() || o.front() != 0 || o.back() != int(n)) return false;
  for (size_t k = 0; k + 1 < o.size(); ++k)
    if (o[k] > o[k + 1]) return false;
  return true;
}

inline void check_volume_reader(const uint8_t* data, size_t size, const char* format) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  PolyhedronSoup s;
  try {
    s = read_polyhedron_soup_from_memory(bytes, format, "fuzz");
  } catch (const FileError& e) {
    require(e.file == "fuzz", "FileError names the file");
    require(!e.reason.empty(), "FileError has a reason");
    require(e.line >= 0 && e.line <= long(size) + 1, "FileError line in range");
    return;
  }
  require(offsets_ok(s.face_offsets, s.face_indices.size()), "face offsets consistent");
  require(offsets_ok(s.cell_offsets, s.cell_halffaces.size()), "cell offsets consistent");
  for (int i : s.face_indices) require(i >= 0 && i < s.n_vertices(), "face indices in range");
  for (int h : s.cell_halffaces) require(h >= 0 && h < 2 * s.n_faces(), "half-faces in range");
  VolumeMesh m;
  try {
    m = VolumeMesh(std::move(s));
  } catch (const InvalidMeshError&) {
    return;
  }
  // The volume is finite, or refused as beyond double's range (coordinates near the limit).
  double v = std::numeric_limits<double>::quiet_NaN();
  try {
    v = m.volume();
    require(std::isfinite(v), "finite volume");
  } catch (const InvalidMeshError&) {
  }
  try {
    const Mesh b = m.boundary_surface();
    require(b.n_vertices() == m.n_vertices(), "boundary on all vertices");
  } catch (const InvalidMeshError&) {
    // A non-manifold boundary (cells touching along an edge) is not a surface Mesh.
  }
  // A mesh without cells is a VolumeMesh (Python builds them) but no volume file: reading one
  // back is refused, so there is no round trip to check.
  if (m.n_cells() == 0) return;
  std::string meshb;
  try {
    meshb = write_volume_mesh_to_string(m, "meshb");
  } catch (const FileError&) {
    // A general polyhedron: MEDIT has no element for it.
  }
  if (!meshb.empty()) {
    const VolumeMesh r = read_volume_mesh_from_memory(meshb, "meshb", "round trip");
    require(r.n_cells() == m.n_cells() && r.n_faces() == m.n_faces(), "MEDIT round trip keeps cells and faces");
    require(r.positions() == m.positions(), "MEDIT round trip keeps positions");
  }
  for (int k = 0; k < 3; ++k) {
    const char* f = k == 0 ? "ovm" : "vtk";
    WriteOptions options;
    options.binary = k == 2;
    const VolumeMesh r =
        read_volume_mesh_from_memory(write_volume_mesh_to_string(m, f, options), f, "round trip");
    require(r.n_cells() == m.n_cells() && r.n_faces() == m.n_faces(), "round trip keeps cells and faces");
    require(r.positions() == m.positions(), "round trip keeps positions");
    // Rounding scale of the volume sum: per cell (diameter)^3 times its corner count (the
    // products of coordinates relative to a cell vertex), so needle cells with huge coordinates
    // do not count as a difference.
    double scale = 0;
    for (int c = 0; c < m.n_cells(); ++c) {
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e308), hi = -lo;
      for (int u : m.cell_vertices(c)) lo = lo.cwiseMin(m.position(u)), hi = hi.cwiseMax(m.position(u));
      int corners = 0;
      for (int h : m.cell(c)) corners += m.face_size(h / 2);
      scale += std::pow((hi - lo).norm(), 3) * corners;
    }
    if (!std::isfinite(v) || !std::isfinite(scale)) continue;
    // A degenerate cell's volume is rounding noise of its corner products: read back with its faces
    // in another order it may fall outside double's normal range and be refused, like m's would.
    double rv = 0;
    try {
      rv = r.volume();
    } catch (const InvalidMeshError&) {
      continue;
    }
    require(std::abs(rv - v) <= 1e-12 * scale + 1e-300, "round trip keeps the volume");
  }
}

// The groups of a MEDIT file (`binary`: .meshb): sorted, distinct vertex indices and cells in range.
inline void check_medit_groups(const uint8_t* data, size_t size, bool binary) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  MeshGroups g;
  io_detail::PolyhedronRead r;
  try {
    r = binary ? io_detail::read_meshb(bytes, "fuzz", &g) : io_detail::read_medit(bytes, "fuzz", &g);
  } catch (const FileError&) {
    return;
  }
  auto ok = [](const std::vector<int>& v, int n) {
    return std::adjacent_find(v.begin(), v.end(), [](int a, int b) { return a >= b; }) == v.end() &&
           (v.empty() || (v.front() >= 0 && v.back() < n));
  };
  for (const auto& [name, v] : g.vertices) require(ok(v, r.soup.n_vertices()), "group vertices sorted and in range");
  for (const auto& [name, c] : g.elements) require(ok(c, r.soup.n_cells()), "group cells sorted and in range");
}

}  // namespace polydec::fuzz_volume
