// dec/io/mesh_groups.h — what a mesh file carries beside the mesh polydec reads: named element
// sets (gmsh physical groups, MEDIT references) and the counts of the lower-dimensional elements a
// reader skipped. Formats without such sets (OBJ, OFF, PLY, OVM, VTK, VTU) give empty groups.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec {

struct MeshGroups {
  // Group name -> the sorted, distinct vertex indices of its elements (of any dimension). A gmsh
  // physical group is named by its $PhysicalNames entry, else by its number ("7"); groups of
  // different dimensions with the same name are merged. A MEDIT (.mesh, .meshb) element reference r
  // gives the group "ref r" (the vertices of every element with that reference: cells, and the
  // edges, triangles and quadrilaterals beside them), a vertex's own reference r the group
  // "vertex ref r" (the vertices carrying it); reference 0 means "none" and makes no group.
  std::map<std::string, std::vector<int>> vertices;
  // Group name -> the sorted faces (surface) or cells (volume) among the mesh's own elements;
  // only groups holding such elements appear (MEDIT: "ref r", the cells with reference r).
  std::map<std::string, std::vector<int>> elements;
  // Element kind ("points", "lines", "triangles", "quadrangles") -> how many elements of a lower
  // dimension than the mesh's the reader skipped (boundary triangles beside tetrahedra, ...).
  std::map<std::string, long> skipped;
};

// read_mesh / read_volume_mesh (dec/io/mesh_io.h, dec/io/volume_io.h), and the file's groups and
// skipped elements in `groups`. Throws FileError.
Mesh read_mesh_with_groups(const std::string& path, MeshGroups& groups);
VolumeMesh read_volume_mesh_with_groups(const std::string& path, MeshGroups& groups);

// A mesh file of either kind, read and parsed once (read_mesh_file): exactly one of surface, soup
// and volume is set.
struct MeshFile {
  std::optional<Mesh> surface;
  std::optional<PolygonSoup> soup;  // a surface's polygons, not validated (MeshFileOptions::validate_surface)
  std::optional<VolumeMesh> volume;
  MeshGroups groups;      // as read_mesh_groups, with MeshFileOptions::groups
  VolumeReadNotes notes;  // a volume's skipped VTK cells, as read_volume_mesh
  bool is_volume() const { return volume.has_value(); }
};
struct MeshFileOptions {
  bool volume = false;           // read as a volume mesh whatever the file's name
  bool validate_surface = true;  // false: a surface comes back as its polygon soup (to repair it first)
  bool groups = false;           // also read the file's groups and skipped elements into MeshFile::groups
};
// Reads `path` as the kind is_volume_mesh_path (dec/io/volume_io.h) decides, parsing the file once:
// a volume for .ovm, .vtk, .mesh, .meshb (or options.volume), a surface for .obj, .off, .ply and
// other names (recognized by content as read_mesh does), and for .msh and .vtu what the file holds
// (a volume when it has 3-D cells; a .vtu without cells and a .msh that does not start like one are
// read as volumes, so that the error says why). Results and FileErrors are those of
// read_mesh_with_groups or read_volume_mesh (with its notes and read_volume_mesh_with_groups' groups).
MeshFile read_mesh_file(const std::string& path, const MeshFileOptions& options = {});

// The groups of a surface or volume mesh file (a gmsh .msh file's physical groups, a MEDIT file's
// references), without validating its mesh; empty for the other formats. Throws FileError.
MeshGroups read_mesh_groups(const std::string& path);

}  // namespace polydec
