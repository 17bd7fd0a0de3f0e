// dec/io/vtu.h — VTK XML unstructured grids (.vtu, ParaView's format): writing volume and surface
// meshes with point and cell data, and reading the point and cell data arrays of a file. The
// meshes themselves are read through read_volume_mesh (dec/io/volume_io.h) and read_mesh
// (dec/io/mesh_io.h); what the reader accepts is documented in docs/io.md.
#pragma once

#include <Eigen/Dense>
#include <map>
#include <string>
#include <string_view>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec {

// Fields written beside a mesh: per-vertex scalars (|V| values) and 3-vectors (|V| x 3), and
// per-cell scalars (one value per cell of a volume mesh, per face of a surface). Names must be
// non-empty; any other characters are escaped.
struct VtuFields {
  std::map<std::string, Eigen::VectorXd> point_scalars;
  std::map<std::string, Eigen::MatrixX3d> point_vectors;
  std::map<std::string, Eigen::VectorXd> cell_scalars;
};

// The bytes of a .vtu file of the mesh and fields: one piece, Float64 points and fields, Int64
// connectivity and offsets, UInt8 types; inline base64 binary (little-endian, UInt64 headers) when
// `binary`, else ASCII with 17 significant digits (bit-exact either way). `compressed` (whatever
// `binary` says): appended raw data in zlib blocks of 32 KiB (compressor vtkZLibDataCompressor),
// as ParaView writes by default; smaller, and bit-exact too. Volume cells are written
// as tetra 10, pyramid 14, wedge 13 or hexahedron 12 when they have that shape, else as polyhedron
// 42 with their outward faces; surface faces as triangle 5, quad 9 or polygon 7. Throws
// std::invalid_argument for a field of the wrong size or an empty name.
std::string write_vtu_to_string(const VolumeMesh& mesh, const VtuFields& fields = {}, bool binary = true,
                                bool compressed = false);
std::string write_vtu_to_string(const Mesh& mesh, const VtuFields& fields = {}, bool binary = true,
                                bool compressed = false);
// The same written to `path`; FileError when it cannot be written.
void write_vtu(const std::string& path, const VolumeMesh& mesh, const VtuFields& fields = {},
               bool binary = true, bool compressed = false);
void write_vtu(const std::string& path, const Mesh& mesh, const VtuFields& fields = {}, bool binary = true,
               bool compressed = false);

// The point and cell data arrays of a .vtu file whose arrays have 1 or 3 components (other arrays
// are skipped), converted to double; the arrays of several pieces concatenated in piece order (an
// array missing from a piece is left out). Throws FileError as the mesh readers do.
VtuFields read_vtu_fields(const std::string& path);
VtuFields read_vtu_fields_from_memory(std::string_view bytes, const std::string& name);

}  // namespace polydec
