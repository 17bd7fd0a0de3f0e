// dec/detail/msh_io.h — internal to the readers and writers (not installed API): the gmsh .msh and
// binary MEDIT .meshb entry points the surface and volume dispatch (mesh_io.cpp, volume_io.cpp) call.
#pragma once

#include <string>
#include <string_view>

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

// True when the bytes start with a binary MEDIT code word 1 (either byte order) and a version 1-4.
bool looks_like_meshb(std::string_view bytes);
// Binary MEDIT .meshb (GMF versions 1-4): the element kinds read_medit reads.
PolyhedronRead read_meshb(std::string_view bytes, const std::string& name, MeshGroups* groups = nullptr);

}  // namespace polydec::io_detail
