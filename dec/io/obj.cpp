// dec/io/obj.cpp — Wavefront OBJ: `v` and `f` statements (face entries i, i/t, i//n, i/t/n,
// negative = relative indices); every other statement, comments, CRLF and a UTF-8 BOM are
// accepted and ignored.
#include <climits>
#include <cstring>

#include "polydec/dec/detail/io_common.h"

namespace polydec::io_detail {

namespace {

// Checks the "/t", "//n", "/t/n" tail of a face entry: integers or empty, at most two slashes.
bool valid_tail(std::string_view tail) {
  int slashes = 0;
  size_t i = 0;
  while (i < tail.size()) {
    if (tail[i] != '/' || ++slashes > 2) return false;
    const size_t b = ++i;
    while (i < tail.size() && tail[i] != '/') ++i;
    long long x;
    if (i > b && !parse_int(tail.substr(b, i - b), x)) return false;
  }
  return true;
}

}  // namespace

SoupRead read_obj(std::string_view bytes, const std::string& name) {
  if (std::memchr(bytes.data(), '\0', bytes.size()))
    throw FileError(
        name, 0, long(static_cast<const char*>(std::memchr(bytes.data(), '\0', bytes.size())) - bytes.data()),
        "NUL byte: binary data, not an OBJ text file");
  const std::string_view text = strip_bom(bytes);
  SoupRead r;
  std::vector<double> xyz;
  DigitCounter digits;
  std::vector<long long> raw;  // 1-based or resolved positive indices, checked at the end
  std::vector<int> face;
  std::vector<std::string_view> tok;
  LineReader lines(text);
  std::string_view line;
  while (lines.next(line)) {
    const long ln = lines.line();
    if (const auto h = line.find('#'); h != std::string_view::npos) line = line.substr(0, h);
    split(line, tok);
    if (tok.empty()) continue;
    if (tok[0] == "v") {
      if (tok.size() < 4)
        throw FileError(name, ln, -1, fmt::format("vertex needs 3 coordinates, found {}", tok.size() - 1));
      for (int c = 1; c <= 3; ++c) {
        double x;
        if (!parse_double(tok[c], x)) throw FileError(name, ln, -1, "bad vertex coordinate " + quote(tok[c]));
        digits.see(tok[c], x);
        xyz.push_back(x);
      }
      if (xyz.size() / 3 > size_t(INT_MAX / 2)) throw FileError(name, ln, -1, "too many vertices");
      r.vertex_where.push_back(ln);
    } else if (tok[0] == "f") {
      const long long nv_so_far = static_cast<long long>(xyz.size() / 3);
      for (size_t k = 1; k < tok.size(); ++k) {
        const std::string_view t = tok[k];
        const size_t slash = t.find('/');
        const std::string_view head = t.substr(0, slash);
        long long i;
        if (!parse_int(head, i) || (slash != std::string_view::npos && !valid_tail(t.substr(slash))))
          throw FileError(name, ln, -1, "bad face entry " + quote(t) + " (expected i, i/t, i//n or i/t/n)");
        if (i == 0) throw FileError(name, ln, -1, "face index 0 (OBJ indices start at 1)");
        if (i < 0) {
          if (i < -nv_so_far)
            throw FileError(
                name, ln, -1,
                fmt::format("relative face index {} reaches before the first vertex ({} vertices so far)", i,
                            nv_so_far));
          i = nv_so_far + i + 1;
        }
        if (i > INT_MAX / 2) throw FileError(name, ln, -1, fmt::format("face index {} out of range", i));
        raw.push_back(i);
      }
      if (raw.size() > size_t(INT_MAX / 2)) throw FileError(name, ln, -1, "too many face corners");
      r.soup.face_offsets.push_back(int(raw.size()));
      r.face_where.push_back(ln);
    }
  }
  if (xyz.empty()) throw FileError(name, 0, -1, "no vertices ('v' lines): empty or not an OBJ file");
  const long long nv = static_cast<long long>(xyz.size() / 3);
  r.soup.face_indices.resize(raw.size());
  for (int f = 0; f < r.soup.n_faces(); ++f)
    for (int k = r.soup.face_offsets[f]; k < r.soup.face_offsets[f + 1]; ++k) {
      if (raw[k] > nv)
        throw FileError(name, r.face_where[f], -1,
                        fmt::format("face index {} out of range (the file has {} vertices)", raw[k], nv));
      r.soup.face_indices[k] = int(raw[k] - 1);
    }
  r.soup.positions =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(xyz.data(), nv, 3);
  r.soup.precision = digits.precision(r.soup.positions);
  return r;
}

std::string write_obj(const Mesh& mesh) {
  fmt::memory_buffer b;
  const auto& X = mesh.positions();
  for (int v = 0; v < mesh.n_vertices(); ++v)
    fmt::format_to(std::back_inserter(b), "v {:.17g} {:.17g} {:.17g}\n", X(v, 0), X(v, 1), X(v, 2));
  for (int f = 0; f < mesh.n_faces(); ++f) {
    b.push_back('f');
    for (int v : mesh.face(f)) fmt::format_to(std::back_inserter(b), " {}", v + 1);
    b.push_back('\n');
  }
  return fmt::to_string(b);
}

}  // namespace polydec::io_detail
