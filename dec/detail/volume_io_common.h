// dec/detail/volume_io_common.h — internal to the volume readers and writers (not installed API): the
// reader result with the line of every vertex, face and cell, the per-format entry points, and
// the whitespace token reader of the VTK and MEDIT readers.
#pragma once

#include <algorithm>
#include <climits>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "polydec/dec/detail/io_common.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/polyhedron_builder.h"

namespace polydec::io_detail {

// A volume reader's result: the soup plus the 1-based line each vertex, face and cell came
// from (VTK and MEDIT faces are derived from cells: their line is the first cell's), or their
// byte offset in a binary file (`where_is_byte_offset`).
struct PolyhedronRead {
  PolyhedronSoup soup;
  std::vector<long> vertex_where, face_where, cell_where;
  bool where_is_byte_offset = false;
  std::map<std::string, long> skipped;  // cells of lower dimension left out, by VTK cell name
};

// Whitespace-separated tokens with the line each starts on; errors are FileErrors naming the file
// and line. With `hash_comments`, '#' starts a comment to the end of the line (MEDIT). Files with
// binary payloads between their text (VTK BINARY) switch to byte offsets (use_byte_offsets):
// then where() and every error name the byte offset instead of the line.
class VolumeTokens {
 public:
  VolumeTokens(std::string_view text, const std::string& name, bool hash_comments = false)
      : text_(text), name_(name), hash_comments_(hash_comments) {}

  bool next(std::string_view& t) {
    for (;;) {
      while (pos_ < text_.size() && (is_space(text_[pos_]) || text_[pos_] == '\n')) {
        if (text_[pos_] == '\n') ++line_;
        ++pos_;
      }
      if (hash_comments_ && pos_ < text_.size() && text_[pos_] == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        continue;
      }
      break;
    }
    if (pos_ >= text_.size()) return false;
    const size_t b = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != '\n') ++pos_;
    t = text_.substr(b, pos_ - b);
    token_line_ = line_;
    token_pos_ = b;
    return true;
  }
  // True when the next token is `k` (case-insensitive); consumes nothing.
  bool next_is(std::string_view k) {
    const size_t pos = pos_, token_pos = token_pos_;
    const long line = line_, token_line = token_line_;
    std::string_view t;
    const bool is = next(t) && lower(t) == lower(k);
    pos_ = pos, token_pos_ = token_pos, line_ = line, token_line_ = token_line;
    return is;
  }
  // Consumes the rest of the line up to and including its '\n', failing on anything but white
  // space there: where a binary payload starts.
  void end_line(const char* what) {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    if (pos_ >= text_.size()) fail(here(), fmt::format("unexpected end of file: expected {}", what));
    if (text_[pos_] != '\n') fail(here(), fmt::format("expected the end of the line before {}", what));
    ++pos_, ++line_;
  }
  // True when the current line holds only white space.
  bool blank_line() const {
    size_t p = pos_;
    while (p < text_.size() && is_space(text_[p])) ++p;
    return p >= text_.size() || text_[p] == '\n';
  }
  // Byte offsets: the next unread byte, and skipping n bytes (a binary payload already checked
  // against remaining()).
  size_t position() const { return pos_; }
  void advance(size_t n) { pos_ += std::min(n, remaining()); }
  void use_byte_offsets() { byte_offsets_ = true; }
  // Where the last token starts: its line, or its byte offset after use_byte_offsets().
  long where() const { return byte_offsets_ ? long(token_pos_) : token_line_; }
  // The rest of the current line (after the last token), for VTK's title.
  std::string_view rest_of_line() {
    const size_t e = text_.find('\n', pos_);
    const size_t end = e == std::string_view::npos ? text_.size() : e;
    std::string_view r = text_.substr(pos_, end - pos_);
    pos_ = end;
    return r;
  }
  // Skips to the start of the next line.
  void skip_line() {
    const size_t e = text_.find('\n', pos_);
    pos_ = e == std::string_view::npos ? text_.size() : e + 1;
    if (e != std::string_view::npos) ++line_;
  }
  // The current position: its line, or its byte offset after use_byte_offsets().
  long here() const { return byte_offsets_ ? long(pos_) : line_; }
  long line() const { return token_line_; }
  long current_line() const { return line_; }
  size_t remaining() const { return text_.size() - pos_; }

  // Throws a FileError at `at`: a line, or a byte offset after use_byte_offsets().
  [[noreturn]] void fail(long at, const std::string& reason) const {
    if (byte_offsets_) throw FileError(name_, 0, at, reason);
    throw FileError(name_, at, -1, reason);
  }

  std::string_view expect(const char* what) {
    std::string_view t;
    if (!next(t)) fail(here(), fmt::format("unexpected end of file: expected {}", what));
    return t;
  }
  long long integer(const char* what) {
    const std::string_view t = expect(what);
    long long x;
    if (!parse_int(t, x)) fail(where(), fmt::format("bad {} {}", what, quote(t)));
    return x;
  }
  // A count named `what`, at most INT_MAX / 2 and at most what the remaining bytes can hold at
  // `min_bytes` per record.
  long long count(const std::string& what, long long min_bytes) {
    const long long n = integer(what.c_str());
    if (n < 0) fail(where(), fmt::format("negative {} {}", what, n));
    if (n > INT_MAX / 2) fail(where(), fmt::format("{} {} is too large (at most {})", what, n, INT_MAX / 2));
    if (n * min_bytes > (long long)remaining() + 1)
      fail(where(), fmt::format("{} {} needs at least {} bytes but only {} follow", what, n, n * min_bytes,
                                remaining()));
    return n;
  }
  // The keyword k (case-insensitive).
  void keyword(const char* k) {
    const std::string_view t = expect(k);
    if (lower(t) != lower(k)) fail(where(), fmt::format("expected '{}', found {}", k, quote(t)));
  }

 private:
  std::string_view text_;
  const std::string& name_;
  bool hash_comments_;

  size_t pos_ = 0, token_pos_ = 0;
  long line_ = 1, token_line_ = 0;
  bool byte_offsets_ = false;
};

PolyhedronRead read_ovm(std::string_view bytes, const std::string& name);
PolyhedronRead read_vtk(std::string_view bytes, const std::string& name);
PolyhedronRead read_medit(std::string_view bytes, const std::string& name);
// VTK XML unstructured grid (.vtu): the volume cells (dec/io/vtu.cpp); surface cells beside them
// are skipped and counted.
PolyhedronRead read_vtu(std::string_view bytes, const std::string& name);
// A file of a format that holds either kind (.msh, .vtu), parsed once and read as what it holds:
// `cells` when `volume`, else `surface`.
struct SurfaceOrVolumeRead {
  bool volume = false;
  SoupRead surface;
  PolyhedronRead cells;
};
// A .vtu file read as a volume (as read_vtu) when it has volume cells or no cells at all, else as a
// surface (as read_vtu_surface). Throws FileError.
SurfaceOrVolumeRead read_vtu_either(std::string_view bytes, const std::string& name);
// Whether a .vtu file holds volume cells (else it is a surface); true for bytes that do not parse,
// so the volume reader reports why.
bool vtu_holds_volume(std::string_view bytes, const std::string& name);

// The dimension of a VTK cell type: 3 for the volume cells read (10 tetra, 11 voxel, 12 hexahedron,
// 13 wedge, 14 pyramid, 42 polyhedron), 0 to 2 for vertex, poly-vertex, line, poly-line, triangle,
// triangle strip, polygon, pixel and quad cells; -1 for any other type.
int vtk_cell_dimension(long long type);
// The VTK name of a cell type of known dimension ("triangle"), "" for others.
const char* vtk_cell_name(long long type);
// "3 triangle, 2 line" for skipped cells by name ("none" when empty).
std::string skipped_summary(const std::map<std::string, long>& skipped);
// The problem with lower-dimensional cell number c of VTK type `type` (0 to 2 dimensions) and
// point ids `cell`, which a volume reader skips: a count its type does not allow (a triangle's 3,
// a line's 2, ...), or a point id outside [0, nv); empty when there is none.
std::string vtk_lower_cell_problem(int type, std::span<const int> cell, long long nv, long long c);
// Adds volume cell number c of VTK type `type` to the builder and closes it: for 10, 11, 12, 13, 14
// `cell` holds its point ids (a voxel's reordered to a hexahedron's), for 42 its face stream
// "n_faces k_1 ids_1 .. k_n ids_n"; point ids are checked against [0, nv). Returns the problem
// (naming the cell), empty when there is none.
std::string add_vtk_volume_cell(PolyhedronSoupBuilder& builder, int type, std::span<const int> cell,
                                long long nv, long long c);

std::string write_ovm(const VolumeMesh& mesh);
// VTK legacy: ASCII, or BINARY (big-endian payloads) with `binary`; `name` (the file) is named
// in the FileError of a mesh too large for the format (check_vtk_int32).
std::string write_vtk(const VolumeMesh& mesh, const std::string& name, bool binary = false);
// A count a VTK legacy file stores as a 32-bit signed integer (the classic CELLS list size, which
// bounds every number in the list; ASCII and BINARY readers take it as int32): a FileError naming
// `file`, `what`, the value and the limit INT32_MAX when it does not fit, instead of a corrupt file.
void check_vtk_int32(const std::string& file, std::string_view what, std::uint64_t value);
// The classic VTK cell list of the mesh (per cell its count, then its point ids in VTK's order or,
// for a polyhedron (42), its face stream with outward faces) and the cells' VTK types.
void vtk_cells(const VolumeMesh& mesh, const std::string& file, std::vector<int>& entries,
               std::vector<int>& types);
std::string write_medit(const VolumeMesh& mesh, const std::string& name);

}  // namespace polydec::io_detail
