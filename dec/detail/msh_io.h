// dec/detail/msh_io.h — internal to the readers and writers (not installed API): the gmsh .msh and
// binary MEDIT .meshb entry points the surface and volume dispatch (mesh_io.cpp, volume_io.cpp) call.
#pragma once

#include <algorithm>
#include <array>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "polydec/dec/detail/io_common.h"
#include "polydec/dec/detail/volume_io_common.h"
#include "polydec/dec/io/mesh_groups.h"

namespace polydec::io_detail {

// True when the bytes start (after white space) with gmsh's "$MeshFormat".
bool looks_like_msh(std::string_view bytes);
// True when a .msh file holds 3-D elements (it reads as a volume); false for a file that does not
// parse.
bool msh_holds_volume(std::string_view bytes, const std::string& name);
// A .msh file as a surface (its triangles and quadrangles; FileError when it holds 3-D elements)
// or as a volume (its tetrahedra, hexahedra, prisms and pyramids; FileError when it holds none);
// `groups` (if given) receives its physical groups and skipped elements.
SoupRead read_msh_surface(std::string_view bytes, const std::string& name, MeshGroups* groups = nullptr);
PolyhedronRead read_msh_volume(std::string_view bytes, const std::string& name, MeshGroups* groups = nullptr);
// A .msh file parsed once and read as a volume (as read_msh_volume) when it has 3-D elements, else
// as a surface (as read_msh_surface). Throws FileError.
SurfaceOrVolumeRead read_msh_either(std::string_view bytes, const std::string& name, MeshGroups* groups = nullptr);
// The groups and skipped elements of a .msh file of either kind.
MeshGroups read_msh_groups(std::string_view bytes, const std::string& name);
// gmsh 4.1 ASCII: a surface of triangles and quadrangles, a volume of tetrahedra, hexahedra,
// prisms and pyramids; another face or cell throws FileError naming `name`.
std::string write_msh(const Mesh& mesh, const std::string& name);
std::string write_msh(const VolumeMesh& mesh, const std::string& name);

// A prism (gmsh, MEDIT: its first triangle's normal points to the second) in VTK's wedge order (the
// reverse), and back: the permutation is its own inverse.
constexpr int kPrismToVtk[6] = {0, 2, 1, 3, 5, 4};

// A block of MEDIT cells of one VTK type: vertices (0-based, in MEDIT's order; prisms as gmsh's)
// and where each cell was read (line or byte offset).
struct MeditCells {
  int vtk_type;
  std::vector<int> vertices;
  std::vector<long> where;
};
// The soup of r's positions and these cells (faces identified by vertex set); a face whose
// vertices repeat an earlier face's in another cyclic order is a FileError at its cell.
PolyhedronRead build_medit_cells(PolyhedronRead r, const std::vector<MeditCells>& blocks, const std::string& name,
                                 bool byte_offsets);

// MEDIT references as MeshGroups (mesh_groups.h): an element's reference r (r != 0) puts its
// vertices in the vertex set "ref r" and, when it is one of the mesh's cells, the cell in the
// element set "ref r"; a vertex's own reference r (r != 0) puts it in the vertex set "vertex ref r".
class MeditGroups {
 public:
  void vertex(int v, long long ref) {
    if (ref != 0) vertex_refs_[ref].push_back(v);
  }
  // An element's vertices (0-based) and reference; `cell` is its cell number, -1 for the elements
  // the readers skip (edges, triangles, quadrilaterals).
  void element(std::span<const int> vertices, long long ref, int cell) {
    if (ref == 0) return;
    auto& v = element_vertices_[ref];
    v.insert(v.end(), vertices.begin(), vertices.end());
    if (cell >= 0) cells_[ref].push_back(cell);
  }
  // The groups (sorted, distinct indices) and the counts of the skipped elements.
  MeshGroups take(std::map<std::string, long> skipped) {
    MeshGroups g;
    auto put = [](std::map<std::string, std::vector<int>>& out, const std::string& prefix,
                  std::map<long long, std::vector<int>>& sets) {
      for (auto& [ref, v] : sets) {
        std::sort(v.begin(), v.end());
        v.erase(std::unique(v.begin(), v.end()), v.end());
        out[prefix + std::to_string(ref)] = std::move(v);
      }
    };
    put(g.vertices, "ref ", element_vertices_);
    put(g.vertices, "vertex ref ", vertex_refs_);
    put(g.elements, "ref ", cells_);
    g.skipped = std::move(skipped);
    return g;
  }

 private:
  std::map<long long, std::vector<int>> vertex_refs_, element_vertices_, cells_;
};

// True when the bytes start with a binary MEDIT code word 1 (either byte order) and a version 1-4.
bool looks_like_meshb(std::string_view bytes);
// MEDIT ASCII .mesh and binary .meshb (GMF versions 1-4); `groups` (if given) receives the
// references as groups (MeditGroups) and the counts of the skipped edges, triangles and
// quadrilaterals.
PolyhedronRead read_medit(std::string_view bytes, const std::string& name, MeshGroups* groups);
PolyhedronRead read_meshb(std::string_view bytes, const std::string& name, MeshGroups* groups = nullptr);
// A volume mesh's cells grouped as MEDIT's four cell sections, in this order: Tetrahedra, Prisms,
// Hexahedra, Pyramids; each block holds the cells' 0-based vertices in MEDIT's order (cell_shape's
// VTK order; a prism's reversed). A general polyhedron throws FileError naming `name`.
struct MeditBlocks {
  static constexpr const char* kNames[4] = {"Tetrahedra", "Prisms", "Hexahedra", "Pyramids"};
  static constexpr int kSizes[4] = {4, 6, 8, 5};
  std::array<std::vector<int>, 4> vertices;
};
MeditBlocks medit_blocks(const VolumeMesh& mesh, const std::string& name);
// GMF version 2 (32-bit integers and positions, float64 coordinates, little-endian): tetrahedra,
// prisms, hexahedra and pyramids (cell_shape), references 0; another cell, or a file beyond 2^31
// bytes, throws FileError naming `name`.
std::string write_meshb(const VolumeMesh& mesh, const std::string& name);

}  // namespace polydec::io_detail
