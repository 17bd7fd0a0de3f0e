// dec/io/virtual_positions.h — the per-face virtual-vertex positions file of `--virtual-positions`
// (dec/surface/virtual_lift.h): one "x y z" line per face, in face order; blank lines and lines
// starting with '#' are skipped.
#pragma once

#include "polydec/dec/mesh/eigen_abi.h"
#include <Eigen/Core>
#include <string>
#include <string_view>

namespace polydec {

// Reads exactly n_faces positions (|F| x 3, finite). Throws FileError naming the file and line for
// a line that is not three finite numbers, for fewer or more position lines than n_faces, and for
// an unreadable file. Memory is bounded by n_faces and the file's size.
Eigen::MatrixX3d read_virtual_positions(const std::string& path, int n_faces);
// The same from bytes in memory; `name` is used in error messages only.
Eigen::MatrixX3d read_virtual_positions_from_memory(std::string_view bytes, int n_faces, const std::string& name);

// Writes one "x y z" line per row with 17 significant digits (bit-exact). Throws FileError when the
// file cannot be written.
void write_virtual_positions(const std::string& path, const Eigen::MatrixX3d& positions);

}  // namespace polydec
