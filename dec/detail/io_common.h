// dec/detail/io_common.h — internal helpers shared by the file readers and writers (not installed API):
// the reader result with element locations, a line splitter, strict number parsing, and a
// bounds-checked binary cursor.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

#include "polydec/dec/io/mesh_io.h"

namespace polydec {
struct MeshGroups;
}

namespace polydec::io_detail {

// A reader's result: the soup plus where each vertex and face came from, so that a validation
// error found later by Mesh can name the file position. Text formats store 1-based lines,
// binary formats byte offsets.
struct SoupRead {
  PolygonSoup soup;
  std::vector<long> vertex_where, face_where;
  bool where_is_byte = false;
};

SoupRead read_obj(std::string_view bytes, const std::string& name);
SoupRead read_off(std::string_view bytes, const std::string& name);
SoupRead read_ply(std::string_view bytes, const std::string& name);
// The triangles, quads, pixels and polygons of a .vtu file without volume cells (dec/io/vtu.cpp).
SoupRead read_vtu_surface(std::string_view bytes, const std::string& name);

// A surface file (format by extension, else by content as read_mesh) read but not validated;
// `groups` (if given) receives a .msh file's groups. Throws FileError.
SoupRead read_surface_file(const std::string& path, MeshGroups* groups);
// Mesh(r.soup), an InvalidMeshError about a vertex or face reported as a FileError naming its line or
// byte offset.
Mesh validate_surface(SoupRead r, const std::string& name);

std::string write_obj(const Mesh& mesh);
std::string write_off(const Mesh& mesh, bool binary);
std::string write_ply(const Mesh& mesh, const VertexScalars& scalars, bool binary);

// Lower-case copy.
std::string lower(std::string_view s);
// The file name's extension after the last dot, lower case ("" when none).
std::string extension(const std::string& path);
// The whole file as bytes; FileError (line 0) for a directory, an unopenable file or a read error.
std::string slurp(const std::string& path);

// Drops a leading UTF-8 byte-order mark.
inline std::string_view strip_bom(std::string_view s) {
  if (s.size() >= 3 && s.substr(0, 3) == "\xEF\xBB\xBF") s.remove_prefix(3);
  return s;
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Splits text into lines ('\n' separated, a trailing '\r' dropped), counting them from 1.
class LineReader {
 public:
  explicit LineReader(std::string_view text, size_t start = 0, long first_line = 1)
      : text_(text), pos_(start), line_(first_line - 1) {}
  bool next(std::string_view& out) {
    if (pos_ >= text_.size()) return false;
    const size_t e = text_.find('\n', pos_);
    const size_t end = e == std::string_view::npos ? text_.size() : e;
    out = text_.substr(pos_, end - pos_);
    if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
    pos_ = e == std::string_view::npos ? text_.size() : e + 1;
    ++line_;
    return true;
  }
  long line() const { return line_; }       // number of the line last returned (0 before the first)
  size_t position() const { return pos_; }  // byte offset of the next line
  size_t remaining() const { return text_.size() - pos_; }

 private:
  std::string_view text_;
  size_t pos_;
  long line_;
};

// Splits one line into whitespace-separated tokens (spaces, tabs, CR, VT, FF).
inline void split(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const size_t b = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > b) tokens.push_back(line.substr(b, i - b));
  }
}

// Strict parses: the whole token must be a number. A leading '+' is accepted.
inline bool parse_double(std::string_view t, double& x) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  if (t.empty()) return false;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}
inline bool parse_int(std::string_view t, long long& x) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  if (t.empty()) return false;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

// The precision a text file's coordinates carry, from their digits: the most significant digits
// S and the most decimal places D (after the exponent is applied) any coordinate shows. A file
// written with a fixed number of decimals resolves 0.5 10^-D everywhere, one written with a fixed
// number of significant digits half a unit of the S-th digit of each value; the larger of the two
// at the largest |x| of a non-integer token bounds both. Integers (no '.', no exponent) are taken as exact; a
// file of integers only, or with 17 or more significant digits, carries the doubles themselves (noise 0: only
// their round-off).
class DigitCounter {
 public:
  // Counts the digits of token t, whose value is x.
  void see(std::string_view t, double x) {
    if (!t.empty() && (t[0] == '+' || t[0] == '-')) t.remove_prefix(1);
    const size_t e = t.find_first_of("eE");
    const std::string_view mantissa = t.substr(0, e);
    long long exponent = 0;
    if (e != std::string_view::npos && !parse_int(t.substr(e + 1), exponent)) return;
    const size_t dot = mantissa.find('.');
    if (dot == std::string_view::npos && e == std::string_view::npos) return;  // an integer: exact
    int significant = 0, decimals = 0;
    bool leading = true;
    for (size_t i = 0; i < mantissa.size(); ++i) {
      const char c = mantissa[i];
      if (c == '.') continue;
      if (c < '0' || c > '9') return;  // inf, nan: no decimal digits to count
      if (dot != std::string_view::npos && i > dot) ++decimals;
      if (leading && c == '0') continue;
      leading = false;
      ++significant;
    }
    exponent = std::clamp<long long>(exponent, -400, 400);
    seen_ = true;
    if (std::isfinite(x)) largest_ = std::max(largest_, std::abs(x));
    significant_ = std::max(significant_, significant);
    decimals_ = std::max(decimals_, decimals - int(exponent));
  }
  // The recorded precision of the coordinates X: the absolute bound above over rms_radius of X.
  CoordinatePrecision precision(const Eigen::MatrixX3d& X) const {
    CoordinatePrecision p;
    if (!seen_ || significant_ >= 17 || X.rows() == 0) return p;
    const double largest = largest_;
    const double absolute = decimals_ >= 330 ? 0.0 : 0.5 * std::pow(10.0, -decimals_);
    // S significant digits of the largest value: its last digit is 10^(floor(log10 |x|) + 1 - S).
    const double leading = largest > 0 ? std::floor(std::log10(largest)) : 0.0;
    const double noise = std::max(absolute, 0.5 * std::pow(10.0, leading + 1 - std::max(significant_, 1)));
    const Eigen::RowVector3d c = X.colwise().mean();
    const double radius = std::sqrt((X.rowwise() - c).rowwise().squaredNorm().mean());
    if (!(radius > 0) || !std::isfinite(noise)) return p;
    p.noise = std::min(noise / radius, 0.5);  // Mesh accepts [0, 1)
    return p;
  }

 private:
  bool seen_ = false;
  int significant_ = 0, decimals_ = -400;
  double largest_ = 0;  // the largest |x| of a non-integer token
};

// The precision of float32 coordinates X: half a float ulp of the largest, over rms_radius of X.
inline CoordinatePrecision float_precision(const Eigen::MatrixX3d& X) {
  CoordinatePrecision p;
  if (X.rows() == 0) return p;
  const Eigen::RowVector3d c = X.colwise().mean();
  const double radius = std::sqrt((X.rowwise() - c).rowwise().squaredNorm().mean());
  const double noise = 0x1p-24 * X.cwiseAbs().maxCoeff();
  if (radius > 0 && std::isfinite(noise)) p.noise = std::min(noise / radius, 0.5);
  return p;
}

// Shortens a token for an error message (a 1 MB token is not quoted in full).
inline std::string quote(std::string_view t) {
  std::string s;
  for (char c : t.substr(0, 40))
    s += (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) >= 127) ? '?' : c;
  if (t.size() > 40) s += "...";
  return "'" + s + "'";
}

// Bounds-checked reads of little- or big-endian scalars from a byte buffer.
class BinaryCursor {
 public:
  BinaryCursor(std::string_view data, size_t start, bool big_endian, const std::string& name)
      : data_(data), pos_(start), big_(big_endian), name_(name) {}
  size_t position() const { return pos_; }
  size_t remaining() const { return data_.size() - pos_; }
  bool at_end() const { return pos_ >= data_.size(); }

  // Throws a FileError naming `what` when fewer than n bytes are left.
  void need(size_t n, const char* what) const {
    if (remaining() < n)
      throw FileError(
          name_, 0, long(pos_),
          fmt::format("truncated {}: needs {} bytes, the file ends after {}", what, n, remaining()));
  }
  template <class T>
  T read(const char* what) {
    need(sizeof(T), what);
    unsigned char b[sizeof(T)];
    std::memcpy(b, data_.data() + pos_, sizeof(T));
    if (big_ != (std::endian::native == std::endian::big))
      for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    T x;
    std::memcpy(&x, b, sizeof(T));
    pos_ += sizeof(T);
    return x;
  }
  void skip(size_t n, const char* what) {
    need(n, what);
    pos_ += n;
  }

 private:
  std::string_view data_;
  size_t pos_;
  bool big_;
  const std::string& name_;
};

// Appends the bytes of a scalar, big-endian (VTK legacy) or little-endian.
template <class T>
void put_bytes(std::string& out, T x, bool big_endian) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &x, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big))
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}
// Appends the bytes of a little-endian scalar.
template <class T>
void put_le(std::string& out, T x) {
  put_bytes(out, x, false);
}

// 17 significant digits: every double reads back bit-exactly.
inline std::string num(double x) { return fmt::format("{:.17g}", x); }

}  // namespace polydec::io_detail
