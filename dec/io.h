// dec/io.h — reading and writing polygon meshes (OBJ, OFF ascii/binary, PLY ascii/binary) and
// sparse matrices (Matrix Market). Readers keep the file's vertex order exactly.
#pragma once

#include "dec/mesh.h"

#include <Eigen/Sparse>
#include <map>
#include <stdexcept>
#include <string>

namespace polydec {

// A file that cannot be read as a mesh. `line` is 1-based (0 when unknown, e.g. binary
// data); `byte_offset` is set for binary formats (-1 when unknown). what() reads
// "FILE:LINE: REASON" (or "FILE: byte OFFSET: REASON").
class FileError : public std::runtime_error {
 public:
  FileError(std::string file, long line, long byte_offset, std::string reason);
  std::string file;
  long line;
  long byte_offset;
  std::string reason;
};

// Reads OBJ, OFF or PLY, chosen by the file's extension (case-insensitive). Throws FileError.
PolygonSoup read_polygon_soup(const std::string& path);

// read_polygon_soup + validation; an InvalidMeshError is reported as a FileError naming the file.
Mesh read_mesh(const std::string& path);

// Per-vertex scalar fields written as PLY properties (name -> |V| values).
using VertexScalars = std::map<std::string, Eigen::VectorXd>;

// Writers, chosen by extension (.obj, .off, .ply). Scalars are written only to PLY.
// Positions with 17 significant digits. Throw FileError when the file cannot be written.
void write_mesh(const std::string& path, const Mesh& mesh, const VertexScalars& scalars = {});

// Matrix Market "coordinate real general", 1-based, 17 significant digits.
void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& A);
// Reads a Matrix Market coordinate real (general or symmetric) file.
Eigen::SparseMatrix<double> read_matrix_market(const std::string& path);

}  // namespace polydec
