// dec/io/virtual_positions.cpp — reading and writing per-face virtual-vertex positions.
#include "polydec/dec/io/virtual_positions.h"

#include <cmath>
#include <fstream>

#include "polydec/dec/detail/io_common.h"

namespace polydec {

using namespace io_detail;

Eigen::MatrixX3d read_virtual_positions_from_memory(std::string_view bytes, int n_faces, const std::string& name) {
  if (n_faces < 0) throw FileError(name, 0, -1, fmt::format("{} faces asked for", n_faces));
  // Each position line takes at least 6 bytes ("0 0 0\n"): a file too short for n_faces lines is
  // refused before anything is allocated for them.
  if (bytes.size() + 1 < 6 * size_t(n_faces))
    throw FileError(name, 0, -1,
                    fmt::format("{} bytes cannot hold the {} position lines of the mesh's faces", bytes.size(), n_faces));
  Eigen::MatrixX3d X(n_faces, 3);
  LineReader lines(strip_bom(bytes));
  std::string_view line;
  std::vector<std::string_view> tok;
  int f = 0;
  while (lines.next(line)) {
    split(line, tok);
    if (tok.empty() || tok[0][0] == '#') continue;
    if (f == n_faces)
      throw FileError(name, lines.line(), -1, fmt::format("more position lines than the mesh's {} faces", n_faces));
    if (tok.size() != 3)
      throw FileError(name, lines.line(), -1, fmt::format("expected 'x y z', found {} values", tok.size()));
    for (int d = 0; d < 3; ++d) {
      double v;
      if (!parse_double(tok[size_t(d)], v) || !std::isfinite(v))
        throw FileError(name, lines.line(), -1, fmt::format("{} is not a finite number", quote(tok[size_t(d)])));
      X(f, d) = v;
    }
    ++f;
  }
  if (f != n_faces)
    throw FileError(name, lines.line(), -1, fmt::format("{} position lines for the mesh's {} faces", f, n_faces));
  return X;
}

Eigen::MatrixX3d read_virtual_positions(const std::string& path, int n_faces) {
  return read_virtual_positions_from_memory(slurp(path), n_faces, path);
}

void write_virtual_positions(const std::string& path, const Eigen::MatrixX3d& positions) {
  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  for (Eigen::Index f = 0; f < positions.rows(); ++f)
    fmt::format_to(out, "{:.17g} {:.17g} {:.17g}\n", positions(f, 0), positions(f, 1), positions(f, 2));
  std::ofstream file(path, std::ios::binary);
  if (!file) throw FileError(path, 0, -1, "cannot open file for writing");
  file.write(b.data(), std::streamsize(b.size()));
  file.close();
  if (!file) throw FileError(path, 0, -1, "write failed");
}

}  // namespace polydec
