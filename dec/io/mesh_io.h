// dec/io/mesh_io.h — reading and writing polygon meshes (OBJ, OFF ascii/binary, PLY ascii/binary, VTK XML
// .vtu) and sparse matrices (Matrix Market). Readers keep the file's vertex order exactly; what each format
// accepts and rejects is documented in docs/io.md.
#pragma once

#include <Eigen/Sparse>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>

#include "polydec/dec/mesh/mesh.h"

namespace polydec {

// A file that cannot be read (or written). `line` is 1-based (0 when unknown, e.g. binary
// data); `byte_offset` is set for binary formats (-1 when unknown). what() reads
// "FILE:LINE: REASON" (or "FILE: byte OFFSET: REASON", or "FILE: REASON").
class FileError : public std::runtime_error {
 public:
  FileError(std::string file, long line, long byte_offset, std::string reason);
  std::string file;
  long line;
  long byte_offset;
  std::string reason;
};

// Reads OBJ, OFF, PLY, gmsh .msh (its triangles and quadrangles) or .vtu (triangle, quad, pixel and
// polygon cells of a file without volume cells; vertex and line cells skipped), chosen by the
// file's extension (case-insensitive), or for another extension by the content ("$MeshFormat",
// "<?xml", "<VTKFile"). Throws FileError.
// No validation beyond what the format needs (indices in range); Mesh validates the rest.
PolygonSoup read_polygon_soup(const std::string& path);

// The same from bytes in memory; `format` is "obj", "off", "ply", "msh" or "vtu" (case-insensitive) and
// `name` is used in error messages only.
PolygonSoup read_polygon_soup_from_memory(std::string_view bytes, std::string_view format,
                                          const std::string& name);

// read_polygon_soup + validation; an InvalidMeshError is reported as a FileError naming the
// file and, for a vertex or face, its line (text formats) or byte offset (binary formats).
Mesh read_mesh(const std::string& path);
Mesh read_mesh_from_memory(std::string_view bytes, std::string_view format, const std::string& name);

// Per-vertex scalar fields written as PLY properties (name -> |V| values).
using VertexScalars = std::map<std::string, Eigen::VectorXd>;

struct WriteOptions {
  // PLY: binary_little_endian instead of ascii (doubles, bit-exact either way).
  // OFF: "OFF BINARY" in pmp-library's layout (little-endian, float32 positions: lossy).
  // VTU: inline base64 (little-endian Float64, bit-exact) instead of ASCII.
  // OBJ: no binary form; ignored.
  bool binary = false;
};

// Writers, chosen by extension (.obj, .off, .ply, .msh: gmsh 4.1 ASCII of triangles and
// quadrangles, .vtu). Scalars are written to PLY (as `property double NAME`; names must be
// non-empty without whitespace) and .vtu (Float64 point data; vector fields too through write_vtu,
// dec/io/vtu.h), one value per vertex; OBJ, OFF and .msh hold none and refuse them (FileError).
// Text positions with 17 significant digits (bit-exact). Throw FileError when the file
// cannot be written or a scalar field does not fit the mesh.
void write_mesh(const std::string& path, const Mesh& mesh, const VertexScalars& scalars = {},
                const WriteOptions& options = {});

// Matrix Market "coordinate real general", 1-based, 17 significant digits.
void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& A);
// Matrix Market "array real general" (dense, column by column), 17 significant digits: eigenvector
// blocks and other dense results. read_matrix_market reads it back (as a sparse matrix).
void write_dense_matrix_market(const std::string& path, const Eigen::MatrixXd& A);
// Reads a Matrix Market file, coordinate (duplicate entries are summed) or dense array format
// (column by column; zeros not stored), real or integer; general, symmetric or skew-symmetric.
// Throws FileError.
Eigen::SparseMatrix<double> read_matrix_market(const std::string& path);
Eigen::SparseMatrix<double> read_matrix_market_from_memory(std::string_view bytes, const std::string& name);

}  // namespace polydec
