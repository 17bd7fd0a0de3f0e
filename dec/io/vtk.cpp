// dec/io/vtk.cpp — VTK legacy unstructured grids, ASCII or BINARY: "# vtk DataFile Version N", a
// title line, ASCII|BINARY, DATASET UNSTRUCTURED_GRID, POINTS, CELLS (the classic layout
// "n k i_1 .. i_k", or version 5's OFFSETS/CONNECTIVITY arrays) and CELL_TYPES, each array
// optionally followed by a METADATA block (skipped); cell types 10 tetra, 12 hexahedron, 13 wedge,
// 14 pyramid (VTK's vertex orders) and 42 polyhedron (its numbers are the face stream
// "n_faces k_1 face_1 .. " in either layout). BINARY payloads are big-endian: points float32 or
// float64, classic cell lists and cell types int32, version 5 offsets and connectivity
// vtktypeint32 or vtktypeint64; each payload starts after its header line's '\n'. Faces shared
// by cells are identified by their vertex sets. Dataset-level FIELD data before POINTS (its
// arrays of any VTK type, strings included) is skipped; sections after CELL_TYPES (POINT_DATA,
// CELL_DATA, FIELD) are ignored.
#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <span>

#include "polydec/dec/detail/io_common.h"
#include "polydec/dec/detail/volume_io_common.h"
#include "polydec/dec/mesh/polyhedron_builder.h"
#include "polydec/dec/mesh/volume_cells.h"

namespace polydec {
namespace io_vtk_detail {
namespace {

using namespace io_detail;

// How the values of a field array of VTK data type `type` are stored: numbers of `width` bytes
// in BINARY files (1, 2, 4, 8), bits packed 8 to a byte, strings (ASCII one line each; BINARY
// each behind a length header), `long`/`unsigned_long` (their binary width is the writing
// platform's), or a type VTK's legacy reader does not know.
enum class FieldKind { number, bit, string, platform_long, unknown };
struct FieldType {
  FieldKind kind;
  int width;
};
FieldType field_type(std::string_view type) {
  const std::string t = io_detail::lower(type);
  if (t == "bit") return {FieldKind::bit, 0};
  if (t == "char" || t == "signed_char" || t == "unsigned_char") return {FieldKind::number, 1};
  if (t == "short" || t == "unsigned_short") return {FieldKind::number, 2};
  if (t == "int" || t == "unsigned_int" || t == "float" || t == "vtkidtype") return {FieldKind::number, 4};
  if (t == "double" || t == "vtktypeint64" || t == "vtktypeuint64") return {FieldKind::number, 8};
  if (t == "long" || t == "unsigned_long") return {FieldKind::platform_long, 0};
  if (t == "string" || t == "utf8_string") return {FieldKind::string, 0};
  return {FieldKind::unknown, 0};
}

// True when the whole token is a number (values beyond the double range included: field values
// are skipped, not used).
bool is_number(std::string_view t) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  double x;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
  return !t.empty() && (r.ec == std::errc() || r.ec == std::errc::result_out_of_range) &&
         r.ptr == t.data() + t.size();
}

// The reader's state: the tokens (lines in ASCII files, byte offsets in BINARY ones) and the
// bytes the binary payloads are read from.
struct Input {
  Input(io_detail::VolumeTokens& tokens, std::string_view bytes, const std::string& file)
      : in(tokens), text(bytes), name(file) {}
  io_detail::VolumeTokens& in;
  std::string_view text;
  const std::string& name;
  bool binary = false;

  // Skips a METADATA block (VTK 8+ writes one after an array; it ends with an empty line).
  void skip_metadata() {
    if (!in.next_is("METADATA")) return;
    in.keyword("METADATA");
    in.skip_line();
    while (in.remaining() > 0 && !in.blank_line()) in.skip_line();
    in.skip_line();
  }

  // Skips dataset-level field data (ParaView writes e.g. the time value there, before POINTS):
  // "FIELD name n_arrays", then per array "name n_components n_tuples type" and its values, or
  // the word NULL_ARRAY; each array optionally followed by a METADATA block. ASCII values are
  // tokens that must be numbers, strings one line each; BINARY values are the big-endian payload
  // after the header line (strings each behind VTK's 1-, 2-, 4- or 8-byte length header).
  void skip_field_data() {
    in.keyword("FIELD");
    in.expect("the field data name");
    const long long n_arrays = in.count("field array count", 2);
    for (long long a = 0; a < n_arrays; ++a) {
      const std::string_view array_name = in.expect("a field array name");
      if (array_name == "NULL_ARRAY") continue;
      const std::string what = "field array " + io_detail::quote(array_name);
      const long long components = in.count(what + " component count", 0);
      const long long tuples = in.count(what + " tuple count", 0);
      const std::string_view type = in.expect("the field array data type");
      const FieldType ft = field_type(type);
      if (ft.kind == FieldKind::unknown)
        in.fail(in.where(), fmt::format("{} has the unsupported data type {} (numeric types, bit, string are read)",
                                        what, io_detail::quote(type)));
      if (binary && ft.kind == FieldKind::platform_long)
        in.fail(in.where(), fmt::format("{} has type {}, whose size in binary files depends on the writing "
                                        "platform (vtktypeint64 is read)",
                                        what, io_detail::quote(type)));
      const long long n = components * tuples;  // both at most INT_MAX / 2: no overflow
      if (ft.kind == FieldKind::string)
        binary ? skip_binary_strings(n, what) : skip_text_lines(n, what);
      else if (binary)
        skip_binary_values(n, ft, what);
      else
        skip_text_values(n, what);
      skip_metadata();
    }
  }

  // n number tokens of a field array.
  void skip_text_values(long long n, const std::string& what) {
    if (n > ((long long)in.remaining() + 1) / 2)
      in.fail(in.where(), fmt::format("{} announces {} values but only {} bytes follow", what, n, in.remaining()));
    for (long long k = 0; k < n; ++k) {
      const std::string_view t = in.expect("a field value");
      if (!is_number(t)) in.fail(in.where(), fmt::format("bad value {} in {}", io_detail::quote(t), what));
    }
  }

  // n lines of an ASCII string array, after the rest of its header line.
  void skip_text_lines(long long n, const std::string& what) {
    in.skip_line();
    for (long long k = 0; k < n; ++k) {
      if (in.remaining() == 0)
        in.fail(in.here(), fmt::format("unexpected end of file: {} announces {} strings, the file ends after {}",
                                       what, n, k));
      in.skip_line();
    }
  }

  // The binary payload of n numbers (or bits) after the header line.
  void skip_binary_values(long long n, FieldType ft, const std::string& what) {
    in.end_line(what.c_str());
    const size_t left = in.remaining();
    size_t bytes = 0;
    if (ft.kind == FieldKind::bit) {
      bytes = size_t(n + 7) / 8;
    } else {
      if (size_t(n) > left / size_t(ft.width))
        in.fail(in.here(), fmt::format("truncated {}: needs {} values of {} bytes, the file ends after {}", what,
                                       n, ft.width, left));
      bytes = size_t(n) * size_t(ft.width);
    }
    io_detail::BinaryCursor(text, in.position(), true, name).need(bytes, what.c_str());
    in.advance(bytes);
  }

  // n binary strings after the header line, each a big-endian length header whose first byte's
  // top two bits give its size (3: 1 byte, 2: 2, 1: 4, 0: 8; the other bits hold the length)
  // and then the string's bytes.
  void skip_binary_strings(long long n, const std::string& what) {
    in.end_line(what.c_str());
    io_detail::BinaryCursor cur(text, in.position(), true, name);
    if (size_t(n) > cur.remaining())
      in.fail(in.here(), fmt::format("truncated {}: {} strings need at least {} bytes, the file ends after {}",
                                     what, n, n, cur.remaining()));
    for (long long k = 0; k < n; ++k) {
      const std::uint8_t first = cur.read<std::uint8_t>(what.c_str());
      const int header = (first >> 6) == 3 ? 1 : (first >> 6) == 2 ? 2 : (first >> 6) == 1 ? 4 : 8;
      std::uint64_t length = first & 0x3f;
      for (int b = 1; b < header; ++b) length = (length << 8) | cur.read<std::uint8_t>(what.c_str());
      cur.skip(size_t(length), what.c_str());
    }
    in.advance(cur.position() - in.position());
  }

  // The byte width of a binary integer array of VTK type `type` (ASCII: unused, 0).
  int integer_width(std::string_view type, const char* what) {
    if (!binary) return 0;
    const std::string t = io_detail::lower(type);
    if (t == "vtktypeint64") return 8;
    if (t == "vtktypeint32" || t == "int") return 4;
    in.fail(in.where(),
            fmt::format("{} type {} is not supported in binary files (vtktypeint32, vtktypeint64)", what,
                        io_detail::quote(type)));
  }

  // An integer array of n entries: ASCII tokens, or big-endian binary of `width` bytes (4 or 8)
  // starting after the current line, checked against the file's end before anything is read.
  void begin_array(long long n, int width, const char* what) {
    if (!binary) return;
    in.end_line(what);
    cursor.emplace(text, in.position(), true, name);
    cursor->need(size_t(n) * size_t(width), what);
    width_ = width;
    end_ = in.position() + size_t(n) * size_t(width);
  }
  // The array's next entry and where it is (line or byte offset).
  long long next(const char* what, long& at) {
    if (!binary) {
      const long long x = in.integer(what);
      at = in.where();
      return x;
    }
    at = long(cursor->position());
    return width_ == 8 ? (long long)cursor->read<std::int64_t>(what) : cursor->read<std::int32_t>(what);
  }
  // Moves past the array's payload.
  void end_array() {
    if (binary) in.advance(end_ - in.position());
  }

  std::optional<io_detail::BinaryCursor> cursor;
  int width_ = 4;
  size_t end_ = 0;
};

// Coordinates that no writer means: non-finite, subnormal, or with a magnitude beyond 1e30 times
// (or below 1e-30 times) the median nonzero magnitude of the others; `values` decoded as floats
// of `width` bytes in the byte order `big_endian`.
long implausible(std::string_view values, size_t width, bool big_endian, const std::string& name) {
  io_detail::BinaryCursor cur(values, 0, big_endian, name);
  std::vector<double> sane;
  long bad = 0;
  while (cur.remaining() >= width) {
    bool normal = false;
    double x = 0;
    if (width == 4) {
      const float f = cur.read<float>("a coordinate");
      normal = std::isnormal(f), x = std::abs(double(f));
    } else {
      x = std::abs(cur.read<double>("a coordinate"));
      normal = std::isnormal(x);
    }
    if (x == 0) continue;
    if (normal)
      sane.push_back(x);
    else
      ++bad;
  }
  if (sane.empty()) return bad;
  std::nth_element(sane.begin(), sane.begin() + long(sane.size() / 2), sane.end());
  const double median = sane[sane.size() / 2];
  for (double x : sane) bad += x > 1e30 * median || x < 1e-30 * median;
  return bad;
}

// Refuses binary coordinates that are evidently little-endian (the legacy format is big-endian):
// implausible values read big-endian while none are read byte-swapped.
void check_byte_order(std::string_view values, size_t width, io_detail::VolumeTokens& in) {
  const std::string name = "coordinates";
  const long big = implausible(values, width, true, name);
  if (big == 0) return;
  const long little = implausible(values, width, false, name);
  if (little == 0)
    in.fail(
        long(in.position()),
        fmt::format("the binary point coordinates are little-endian: {} of {} read big-endian (as the VTK "
                    "legacy format requires) are non-finite, subnormal or absurdly large or small, and none "
                    "read little-endian; write the file big-endian (VTK's writers do)",
                    big, values.size() / width));
}

}  // namespace
}  // namespace io_vtk_detail

namespace io_detail {

int vtk_cell_dimension(long long type) {
  switch (type) {
    case 1:  // vertex
    case 2:  // poly-vertex
      return 0;
    case 3:  // line
    case 4:  // poly-line
      return 1;
    case 5:  // triangle
    case 6:  // triangle strip
    case 7:  // polygon
    case 8:  // pixel
    case 9:  // quad
      return 2;
    case kVtkTetra:
    case kVtkVoxel:
    case kVtkHexahedron:
    case kVtkWedge:
    case kVtkPyramid:
    case kVtkPolyhedron:
      return 3;
    default:
      return -1;
  }
}

const char* vtk_cell_name(long long type) {
  switch (type) {
    case 1:
      return "vertex";
    case 2:
      return "poly-vertex";
    case 3:
      return "line";
    case 4:
      return "poly-line";
    case 5:
      return "triangle";
    case 6:
      return "triangle strip";
    case 7:
      return "polygon";
    case 8:
      return "pixel";
    case 9:
      return "quad";
    case kVtkTetra:
      return "tetra";
    case kVtkVoxel:
      return "voxel";
    case kVtkHexahedron:
      return "hexahedron";
    case kVtkWedge:
      return "wedge";
    case kVtkPyramid:
      return "pyramid";
    case kVtkPolyhedron:
      return "polyhedron";
    default:
      return "";
  }
}

std::string skipped_summary(const std::map<std::string, long>& skipped) {
  std::string s;
  for (const auto& [kind, n] : skipped) s += fmt::format("{}{} {}", s.empty() ? "" : ", ", n, kind);
  return s.empty() ? "none" : s;
}

std::string vtk_lower_cell_problem(int type, std::span<const int> cell, long long nv, long long c) {
  static const std::map<int, size_t> kSize{{1, 1}, {3, 2}, {5, 3}, {8, 4}, {9, 4}};
  const auto fixed = kSize.find(type);
  const size_t least = type == 6 || type == 7 ? 3 : 1;
  if ((fixed != kSize.end() && cell.size() != fixed->second) || cell.size() < least)
    return fmt::format("cell {} of type {} ({}) cannot have {} points", c, type, vtk_cell_name(type),
                       cell.size());
  for (int v : cell)
    if (v < 0 || v >= nv) return fmt::format("point index {} out of range [0, {})", v, nv);
  return {};
}

std::string add_vtk_volume_cell(PolyhedronSoupBuilder& builder, int type, std::span<const int> cell,
                                long long nv, long long c) {
  if (type == kVtkPolyhedron) {
    if (cell.empty()) return fmt::format("polyhedron cell {} is empty", c);
    std::vector<int> poly;
    size_t p = 1;
    for (int f = 0; f < cell[0]; ++f) {
      if (p >= cell.size())
        return fmt::format("polyhedron cell {}: face {} lies beyond the cell's numbers", c, f);
      const size_t k = size_t(cell[p]);
      if (k > cell.size() - p - 1)
        return fmt::format("polyhedron cell {}: face {} lists {} points, beyond the cell's numbers", c, f, k);
      if (k < 3) return fmt::format("polyhedron cell {}: face {} has {} points (at least 3 needed)", c, f, k);
      poly.assign(cell.begin() + p + 1, cell.begin() + p + 1 + k);
      for (int v : poly)
        if (v < 0 || v >= nv) return fmt::format("point index {} out of range [0, {})", v, nv);
      if (builder.add_polygon(poly) < 0)
        return fmt::format("polyhedron cell {}: face {} has the points of face {} in another cyclic order", c,
                           f, builder.last_face());
      p += 1 + k;
    }
    if (p != cell.size())
      return fmt::format("polyhedron cell {}: its {} faces use {} of its {} numbers", c, cell[0], p,
                         cell.size());
    builder.end_cell();
    return {};
  }
  // A voxel is a hexahedron whose points 2, 3 and 6, 7 are swapped (x fastest, then y, then z).
  const int linear = type == kVtkVoxel ? int(kVtkHexahedron) : type;
  const int n = vtk_cell_size(linear);
  if (int(cell.size()) != n)
    return fmt::format("cell {} of type {} needs {} points, it lists {}", c, type, n, cell.size());
  for (int v : cell)
    if (v < 0 || v >= nv) return fmt::format("point index {} out of range [0, {})", v, nv);
  std::array<int, 8> order{};
  for (int i = 0; i < n; ++i) order[i] = cell[type == kVtkVoxel ? (i ^ ((i >> 1) & 1)) : i];
  if (!builder.add_vtk_cell(linear, {order.data(), size_t(n)}))
    return fmt::format("cell {}: a face has the points of face {} in another cyclic order", c,
                       builder.last_face());
  return {};
}

PolyhedronRead read_vtk(std::string_view bytes, const std::string& name) {
  const std::string_view text = strip_bom(bytes);
  VolumeTokens in(text, name);
  io_vtk_detail::Input io{in, text, name};
  // Header line, title line, ASCII|BINARY, DATASET UNSTRUCTURED_GRID.
  std::string_view t;
  if (!in.next(t)) in.fail(0, "empty file (no '# vtk DataFile' header)");
  std::string_view head = in.rest_of_line();
  const std::string header = lower(std::string(t) + std::string(head));
  if (header.rfind("# vtk datafile", 0) != 0 && header.rfind("#vtk datafile", 0) != 0)
    in.fail(1, fmt::format("expected the header '# vtk DataFile Version ...', found {}", quote(t)));
  const bool version5 = header.find("version 5") != std::string::npos;
  in.skip_line();  // end of the header line
  in.skip_line();  // the title line
  const std::string_view format = in.expect("ASCII or BINARY");
  io.binary = lower(format) == "binary";
  if (!io.binary && lower(format) != "ascii")
    in.fail(in.line(), fmt::format("expected 'ASCII' or 'BINARY', found {}", quote(format)));
  if (io.binary) in.use_byte_offsets();
  in.keyword("DATASET");
  const std::string_view dataset = in.expect("a dataset type");
  if (lower(dataset) != "unstructured_grid")
    in.fail(in.where(), fmt::format("dataset {} is not supported (only UNSTRUCTURED_GRID)", quote(dataset)));

  // Dataset-level FIELD data (skipped), then POINTS.
  while (in.next_is("FIELD")) io.skip_field_data();
  in.keyword("POINTS");
  PolyhedronRead r;
  r.where_is_byte_offset = io.binary;
  const long long nv = in.count("point count", io.binary ? 12 : 6);
  const std::string_view point_type = in.expect("the point data type");
  const std::string pt = lower(point_type);
  if (pt != "float" && pt != "double")
    in.fail(in.where(),
            fmt::format("point data type {} is not supported (float, double)", quote(point_type)));
  r.soup.positions.resize(nv, 3);
  r.vertex_where.resize(nv);
  if (io.binary) {
    in.end_line("the point coordinates");
    const size_t width = pt == "float" ? 4 : 8;
    BinaryCursor cur(text, in.position(), true, name);
    cur.need(size_t(nv) * 3 * width, "point coordinates");
    io_vtk_detail::check_byte_order(text.substr(in.position(), size_t(nv) * 3 * width), width, in);
    for (long long v = 0; v < nv; ++v) {
      r.vertex_where[v] = long(cur.position());
      for (int c = 0; c < 3; ++c) {
        const long at = long(cur.position());
        const double x = width == 4 ? double(cur.read<float>("a point coordinate"))
                                    : cur.read<double>("a point coordinate");
        if (!std::isfinite(x)) in.fail(at, fmt::format("point {} has a non-finite coordinate ({})", v, x));
        r.soup.positions(v, c) = x;
      }
    }
    in.advance(size_t(nv) * 3 * width);
    r.soup.precision = width == 4 ? float_precision(r.soup.positions) : CoordinatePrecision{};
  } else {
    DigitCounter digits;
    for (long long v = 0; v < nv; ++v)
      for (int c = 0; c < 3; ++c) {
        const std::string_view x = in.expect("a point coordinate");
        if (c == 0) r.vertex_where[v] = in.line();
        if (!parse_double(x, r.soup.positions(v, c))) in.fail(in.line(), "bad point coordinate " + quote(x));
        digits.see(x, r.soup.positions(v, c));
      }
    r.soup.precision = digits.precision(r.soup.positions);
  }
  io.skip_metadata();

  in.keyword("CELLS");
  const long cells_where = in.where();
  const long long n_cells_field = in.count("cell count", io.binary ? 4 : 2);
  const long long size = in.count("cell list size", io.binary ? 4 : 2);
  // Cell numbers as flat offsets + entries (point ids, or a polyhedron's face stream), and where
  // each cell starts.
  std::vector<long long> offsets{0};
  std::vector<int> ids;
  std::vector<long> cell_where;
  long long nc = 0;
  long at = 0;
  if (version5) {
    // n_cells_field offsets (n + 1 of them) and `size` connectivity entries.
    if (n_cells_field < 1) in.fail(cells_where, "CELLS needs at least one offset in the version 5 layout");
    nc = n_cells_field - 1;
    in.keyword("OFFSETS");
    const int offset_width = io.integer_width(in.expect("the offset data type"), "offset");
    offsets.clear();
    offsets.reserve(n_cells_field);
    io.begin_array(n_cells_field, offset_width, "offsets");
    for (long long k = 0; k <= nc; ++k) {
      const long long o = io.next("offset", at);
      if ((k == 0 && o != 0) || (k > 0 && o < offsets.back()) || o > size)
        in.fail(at, fmt::format("offset {} out of order (offsets rise from 0 to {})", o, size));
      offsets.push_back(o);
      cell_where.push_back(at);
    }
    io.end_array();
    cell_where.pop_back();
    if (offsets.back() != size)
      in.fail(at, fmt::format("the last offset is {} but CELLS announced {} connectivity entries",
                              offsets.back(), size));
    io.skip_metadata();
    in.keyword("CONNECTIVITY");
    const int width = io.integer_width(in.expect("the connectivity data type"), "connectivity");
    ids.reserve(size);
    io.begin_array(size, width, "connectivity");
    // Polyhedron face streams hold counts besides point ids: range-checked once the type is known.
    for (long long k = 0; k < size; ++k) {
      const long long x = io.next("connectivity entry", at);
      if (x < 0 || x > INT_MAX) in.fail(at, fmt::format("connectivity entry {} out of range", x));
      ids.push_back(int(x));
    }
    io.end_array();
  } else {
    nc = n_cells_field;
    if (nc > size) in.fail(cells_where, fmt::format("{} cells cannot fit in a list of {} numbers", nc, size));
    ids.reserve(size - nc);
    offsets.reserve(nc + 1);
    io.begin_array(size, 4, "cell list");
    long long used = 0;
    for (long long c = 0; c < nc; ++c) {
      if (used >= size)
        in.fail(cells_where,
                fmt::format("CELLS announced {} cells but its list of {} numbers ends after cell {}", nc,
                            size, c - 1));
      const long long k = io.next("cell size", at);
      cell_where.push_back(at);
      if (k < 0 || used + 1 + k > size)
        in.fail(at, fmt::format("cell {} lists {} numbers, beyond the announced list size {}", c, k, size));
      used += 1 + k;
      // Polyhedron face streams hold counts besides point ids: range-checked once the type is known.
      for (long long i = 0; i < k; ++i) {
        const long long x = io.next("cell entry", at);
        if (x < 0 || x > INT_MAX) in.fail(at, fmt::format("cell entry {} out of range", x));
        ids.push_back(int(x));
      }
      offsets.push_back((long long)ids.size());
    }
    if (used != size)
      in.fail(io.binary ? cells_where : in.where(),
              fmt::format("the cells hold {} numbers but CELLS announced {}", used, size));
    io.end_array();
  }
  io.skip_metadata();

  in.keyword("CELL_TYPES");
  const long long nt = in.count("cell type count", io.binary ? 4 : 2);
  if (nt != nc) in.fail(in.where(), fmt::format("CELL_TYPES lists {} types for {} cells", nt, nc));
  std::vector<int> types(nc);
  std::vector<long> type_where(nc);
  io.begin_array(nc, 4, "cell types");
  for (long long c = 0; c < nc; ++c) {
    const long long ty = io.next("cell type", at);
    type_where[c] = at;
    if (vtk_cell_dimension(ty) < 0)
      in.fail(at, fmt::format(
                      "unknown or unsupported cell type {}{} of cell {} (10 tetra, 11 voxel, 12 hexahedron, "
                      "13 wedge, 14 pyramid, 42 polyhedron are read; vertex, line, triangle, quad and "
                      "polygon cells beside them are skipped)",
                      ty, vtk_cell_name(ty)[0] ? fmt::format(" ({})", vtk_cell_name(ty)) : "", c));
    types[c] = int(ty);
  }
  io.end_array();

  PolyhedronSoupBuilder builder(std::move(r.soup.positions));
  for (long long c = 0; c < nc; ++c) {
    const long ln = cell_where[c];
    const std::span<const int> cell(ids.data() + offsets[c], size_t(offsets[c + 1] - offsets[c]));
    const bool skip = vtk_cell_dimension(types[c]) < 3;
    const std::string problem = skip ? vtk_lower_cell_problem(types[c], cell, nv, c)
                                     : add_vtk_volume_cell(builder, types[c], cell, nv, c);
    if (!problem.empty()) in.fail(ln, problem);
    if (skip) {
      ++r.skipped[vtk_cell_name(types[c])];
      continue;
    }
    while (int(r.face_where.size()) < builder.n_faces()) r.face_where.push_back(ln);
    r.cell_where.push_back(ln);
  }
  if (r.cell_where.empty() && nc > 0)
    in.fail(cells_where,
            fmt::format("no volume cells: the file's {} cells are {}", nc, skipped_summary(r.skipped)));
  const CoordinatePrecision precision = r.soup.precision;
  r.soup = builder.take();
  r.soup.precision = precision;
  return r;
}

void check_vtk_int32(const std::string& file, std::string_view what, std::uint64_t value) {
  if (value > std::uint64_t(INT32_MAX))
    throw FileError(file, 0, -1,
                    fmt::format("{} is {}, beyond the 32-bit signed integers of a VTK legacy file (at most {}): "
                                "the mesh is too large for this format",
                                what, value, INT32_MAX));
}

// The classic cell list of the mesh (per cell its count, then its point ids or, for a polyhedron,
// its face stream with outward faces) and the cells' VTK types; a FileError naming `file` as soon
// as the list outgrows the file's int32 counts (which bounds every number in it, a face stream's
// length included).
void vtk_cells(const VolumeMesh& mesh, const std::string& file, std::vector<int>& entries,
               std::vector<int>& types) {
  types.assign(size_t(mesh.n_cells()), 0);
  entries.clear();
  std::array<int, 8> order{};
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const CellShape s = cell_shape(mesh, c, &order);
    const int type = s == CellShape::tetrahedron  ? kVtkTetra
                     : s == CellShape::pyramid    ? kVtkPyramid
                     : s == CellShape::wedge      ? kVtkWedge
                     : s == CellShape::hexahedron ? kVtkHexahedron
                                                  : kVtkPolyhedron;
    types[c] = type;
    if (type == kVtkPolyhedron) {
      const size_t count_at = entries.size();
      entries.push_back(0);
      entries.push_back(mesh.cell_size(c));
      for (int h : mesh.cell(c)) {  // outward faces, as VTK's polyhedra expect
        const auto f = mesh.face(h / 2);
        entries.push_back(int(f.size()));
        entries.push_back(f[0]);
        for (size_t i = 1; i < f.size(); ++i) entries.push_back((h & 1) ? f[f.size() - i] : f[i]);
      }
      entries[count_at] = int(entries.size() - count_at - 1);
    } else {
      const int n = vtk_cell_size(type);
      entries.push_back(n);
      entries.insert(entries.end(), order.begin(), order.begin() + n);
    }
    check_vtk_int32(file, "the CELLS list size (per cell its count and numbers)", entries.size());
  }
}

std::string write_vtk(const VolumeMesh& mesh, const std::string& name, bool binary) {
  const auto& X = mesh.positions();
  std::vector<int> entries, types;
  vtk_cells(mesh, name, entries, types);
  std::string out =
      fmt::format("# vtk DataFile Version 4.2\npolydec volume mesh\n{}\nDATASET UNSTRUCTURED_GRID\n",
                  binary ? "BINARY" : "ASCII");
  out += fmt::format("POINTS {} double\n", mesh.n_vertices());
  if (binary) {
    out.reserve(out.size() + 24 * size_t(mesh.n_vertices()) + 4 * (entries.size() + types.size()) + 64);
    for (int v = 0; v < mesh.n_vertices(); ++v)
      for (int d = 0; d < 3; ++d) put_bytes(out, X(v, d), true);
    out += fmt::format("\nCELLS {} {}\n", mesh.n_cells(), entries.size());
    for (int e : entries) put_bytes(out, std::int32_t(e), true);
    out += fmt::format("\nCELL_TYPES {}\n", mesh.n_cells());
    for (int t : types) put_bytes(out, std::int32_t(t), true);
    out += '\n';
    return out;
  }
  fmt::memory_buffer b;
  auto it = std::back_inserter(b);
  for (int v = 0; v < mesh.n_vertices(); ++v)
    fmt::format_to(it, "{} {} {}\n", num(X(v, 0)), num(X(v, 1)), num(X(v, 2)));
  fmt::format_to(it, "CELLS {} {}\n", mesh.n_cells(), entries.size());
  for (size_t k = 0; k < entries.size();) {
    const size_t n = size_t(entries[k]);
    fmt::format_to(it, "{}", n);
    for (size_t i = 1; i <= n; ++i) fmt::format_to(it, " {}", entries[k + i]);
    b.push_back('\n');
    k += n + 1;
  }
  fmt::format_to(it, "CELL_TYPES {}\n", mesh.n_cells());
  for (int t : types) fmt::format_to(it, "{}\n", t);
  out.append(b.data(), b.size());
  return out;
}

}  // namespace io_detail
}  // namespace polydec
