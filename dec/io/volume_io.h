// dec/io/volume_io.h — reading and writing polyhedral volume meshes: OVM ASCII (OpenVolumeMesh),
// VTK legacy unstructured grids (ASCII or BINARY), VTK XML unstructured grids (.vtu) and MEDIT .mesh. Formats
// are chosen by extension; what each accepts is documented in docs/io.md and docs/volumes.md. Errors are
// FileErrors (dec/io/mesh_io.h) naming the file and line.
#pragma once

#include <map>
#include <string>
#include <string_view>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec {

// True when the path's extension (case-insensitive) is a volume format: .ovm, .vtk, .mesh, .meshb,
// or .msh / .vtu unless the file exists and holds no 3-D elements (a gmsh or VTK surface).
bool is_volume_mesh_path(const std::string& path);

// Reads the file's polyhedra without validation beyond what the format needs (indices in
// range, faces of VTK/MEDIT cells identified by their vertex sets). Throws FileError.
PolyhedronSoup read_polyhedron_soup(const std::string& path);
// The same from bytes; `format` is "ovm", "vtk", "vtu", "mesh", "meshb" or "msh"; `name` is used in messages only.
PolyhedronSoup read_polyhedron_soup_from_memory(std::string_view bytes, std::string_view format,
                                                const std::string& name);

// Files whose extension is none of these are recognized by their first word ("OVM", "# vtk",
// "MeshVersionFormatted", "$MeshFormat", "<?xml" or "<VTKFile") or the binary MEDIT code word.
// read_polyhedron_soup + validation (VolumeMesh); an InvalidMeshError about a vertex, face or
// cell is reported as a FileError naming the line where that element was read.
// What a reader left out: the lower-dimensional cells of a VTK file (vertex, line, triangle, quad,
// polygon: boundary groups) beside its volume cells, counted by VTK cell name.
struct VolumeReadNotes {
  std::map<std::string, long> skipped_cells;
};
VolumeMesh read_volume_mesh(const std::string& path, VolumeReadNotes* notes = nullptr);
VolumeMesh read_volume_mesh_from_memory(std::string_view bytes, std::string_view format,
                                        const std::string& name);

// Writes by extension (.ovm, .vtk, .vtu, .mesh, .msh: gmsh 4.1 ASCII of tetrahedra, hexahedra,
// prisms and pyramids, another cell a FileError), positions with 17 significant digits. OVM files
// are written with outward half-faces (polydec's convention; the reader accepts either).
// MEDIT (.mesh, .meshb) holds tetrahedra, prisms, hexahedra and pyramids: another cell throws FileError. With
// options.binary, VTK is written as a legacy BINARY file (version 4.2, big-endian float64
// points, classic int32 cell list and types: bit-exact like the ASCII file); OVM and MEDIT have
// no binary form here (ignored); .vtu is ASCII, or inline base64 with options.binary (dec/io/vtu.h). Throws
// FileError when the file cannot be written, or when a VTK cell list would exceed the format's int32 counts.
void write_volume_mesh(const VolumeMesh& mesh, const std::string& path, const WriteOptions& options = {});
// A .vtu file with the arrays as Float64 point data (write_vtu, dec/io/vtu.h), or a VTK legacy file
// (extension .vtk; any other is a FileError) of the mesh followed by a POINT_DATA
// section with one "SCALARS NAME double 1" array per entry (|V| values each, 17 significant digits;
// non-finite values written as nan/inf). The reader ignores that section, so the file reads back
// as the mesh. Throws std::invalid_argument for an array of the wrong size or a name with spaces.
void write_volume_vtk_with_point_data(const VolumeMesh& mesh, const std::string& path,
                                      const VertexScalars& scalars);
// The file's bytes for `format` ("ovm", "vtk", "vtu", "mesh" or "msh").
std::string write_volume_mesh_to_string(const VolumeMesh& mesh, std::string_view format,
                                        const WriteOptions& options = {});

}  // namespace polydec
