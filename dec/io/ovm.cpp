// dec/io/ovm.cpp — OpenVolumeMesh's ASCII format ("OVM ASCII"): sections Vertices (x y z),
// Edges (vertex pairs), Faces (halfedge cycles; halfedge 2e runs along edge e, 2e+1 against
// it) and Polyhedra (half-face lists; 2f is face f as listed, 2f+1 reversed), each a keyword
// line, a count line and one record per line. Blank lines and '#' comments are skipped, keywords
// are case-insensitive, anything after the Polyhedra records (property sections) is ignored.
#include <algorithm>
#include <array>
#include <climits>

#include "polydec/dec/detail/io_common.h"
#include "polydec/dec/detail/volume_io_common.h"

namespace polydec {
namespace io_ovm_detail {
namespace {

using namespace io_detail;

// Next line that is not blank once its '#' comment is cut; false at the end of the file.
bool next_record(LineReader& lines, std::vector<std::string_view>& tok) {
  std::string_view line;
  while (lines.next(line)) {
    if (const auto h = line.find('#'); h != std::string_view::npos) line = line.substr(0, h);
    split(line, tok);
    if (!tok.empty()) return true;
  }
  return false;
}

class OvmParser {
 public:
  OvmParser(std::string_view text, const std::string& name) : lines_(text), name_(name) {}

  [[noreturn]] void fail(long line, const std::string& reason) const {
    throw FileError(name_, line, -1, reason);
  }

  void header() {
    if (!next_record(lines_, tok_)) fail(0, "empty file (no 'OVM ASCII' header)");
    if (tok_.size() == 2 && lower(tok_[0]) == "ovm" && lower(tok_[1]) == "binary")
      fail(lines_.line(), "OVM BINARY is not supported (only OVM ASCII)");
    if (tok_.size() != 2 || lower(tok_[0]) != "ovm" || lower(tok_[1]) != "ascii")
      fail(lines_.line(), fmt::format("expected the header 'OVM ASCII', found {}", quote(tok_[0])));
  }

  // The section keyword, then its count; `min_bytes` per record bounds the count by the file size.
  long long section(const char* keyword, long long min_bytes) {
    if (!next_record(lines_, tok_))
      fail(lines_.line(), fmt::format("unexpected end of file: expected the section '{}'", keyword));
    if (tok_.size() != 1 || lower(tok_[0]) != lower(keyword))
      fail(lines_.line(), fmt::format("expected the section '{}', found {}", keyword, quote(tok_[0])));
    if (!next_record(lines_, tok_))
      fail(lines_.line(), fmt::format("unexpected end of file: expected the {} count", keyword));
    const long ln = lines_.line();
    long long n;
    if (tok_.size() != 1 || !parse_int(tok_[0], n))
      fail(ln, fmt::format("bad {} count {}", keyword, quote(tok_[0])));
    if (n < 0) fail(ln, fmt::format("negative {} count {}", keyword, n));
    if (n > INT_MAX / 2)
      fail(ln, fmt::format("{} count {} is too large (at most {})", keyword, n, INT_MAX / 2));
    if (n * min_bytes > (long long)lines_.remaining() + 1)
      fail(ln, fmt::format("{} count {} needs at least {} bytes but only {} follow", keyword, n,
                           n * min_bytes, lines_.remaining()));
    return n;
  }

  // The next record of a section: tokens in tok(), its line in line().
  void record(const char* what, long long k, long long n) {
    if (!next_record(lines_, tok_))
      fail(lines_.line(), fmt::format("unexpected end of file after {} of {} {}", k, n, what));
  }
  const std::vector<std::string_view>& tok() const { return tok_; }
  long line() const { return lines_.line(); }

  long long integer(std::string_view t, const char* what) const {
    long long x;
    if (!parse_int(t, x)) fail(line(), fmt::format("bad {} {}", what, quote(t)));
    return x;
  }

  // A record "k a_1 .. a_k": checks the count against the line and returns k.
  long long list_length(const char* what) const {
    const long long k = integer(tok_[0], "count");
    if (k < 0) fail(line(), fmt::format("negative {} count {}", what, k));
    if (k != (long long)tok_.size() - 1)
      fail(line(),
           fmt::format("the record lists {} {} but the line has {} more numbers", k, what, tok_.size() - 1));
    return k;
  }

 private:
  LineReader lines_;
  const std::string& name_;
  std::vector<std::string_view> tok_;
};

}  // namespace
}  // namespace io_ovm_detail

namespace io_detail {

PolyhedronRead read_ovm(std::string_view bytes, const std::string& name) {
  using io_ovm_detail::OvmParser;
  OvmParser p(strip_bom(bytes), name);
  p.header();
  PolyhedronRead r;

  const long long nv = p.section("Vertices", 6);
  r.soup.positions.resize(nv, 3);
  r.vertex_where.resize(nv);
  DigitCounter digits;
  for (long long v = 0; v < nv; ++v) {
    p.record("vertices", v, nv);
    r.vertex_where[v] = p.line();
    if (p.tok().size() != 3)
      p.fail(p.line(), fmt::format("a vertex needs 3 coordinates, the line has {} numbers", p.tok().size()));
    for (int c = 0; c < 3; ++c) {
      if (!parse_double(p.tok()[c], r.soup.positions(v, c)))
        p.fail(p.line(), "bad vertex coordinate " + quote(p.tok()[c]));
      digits.see(p.tok()[c], r.soup.positions(v, c));
    }
  }
  r.soup.precision = digits.precision(r.soup.positions);

  const long long ne = p.section("Edges", 4);
  std::vector<std::array<int, 2>> edges(ne);
  for (long long e = 0; e < ne; ++e) {
    p.record("edges", e, ne);
    if (p.tok().size() != 2)
      p.fail(p.line(),
             fmt::format("an edge needs 2 vertex indices, the line has {} numbers", p.tok().size()));
    for (int c = 0; c < 2; ++c) {
      const long long i = p.integer(p.tok()[c], "edge vertex index");
      if (i < 0 || i >= nv) p.fail(p.line(), fmt::format("edge vertex index {} out of range [0, {})", i, nv));
      edges[e][c] = int(i);
    }
  }

  const long long nf = p.section("Faces", 4);
  r.soup.face_offsets.reserve(nf + 1);
  r.face_where.reserve(nf);
  std::vector<int> face;
  for (long long f = 0; f < nf; ++f) {
    p.record("faces", f, nf);
    const long long k = p.list_length("halfedges");
    face.clear();
    int first_source = -1, prev_target = -1;
    for (long long i = 1; i <= k; ++i) {
      const long long h = p.integer(p.tok()[i], "halfedge");
      if (h < 0 || h >= 2 * ne) p.fail(p.line(), fmt::format("halfedge {} out of range [0, {})", h, 2 * ne));
      const auto& e = edges[h / 2];
      const int s = e[h & 1], t = e[1 - (h & 1)];
      if (prev_target >= 0 && s != prev_target)
        p.fail(p.line(), fmt::format("halfedge {} starts at vertex {} but the previous one ends at vertex {}",
                                     h, s, prev_target));
      if (first_source < 0) first_source = s;
      face.push_back(s);
      prev_target = t;
    }
    if (k > 0 && prev_target != first_source)
      p.fail(p.line(),
             fmt::format("the halfedges do not close: the last ends at vertex {}, the first starts at {}",
                         prev_target, first_source));
    r.soup.add_face(face);
    r.face_where.push_back(p.line());
  }

  const long long nc = p.section("Polyhedra", 4);
  r.soup.cell_offsets.reserve(nc + 1);
  r.cell_where.reserve(nc);
  std::vector<int> cell;
  for (long long c = 0; c < nc; ++c) {
    p.record("polyhedra", c, nc);
    const long long k = p.list_length("half-faces");
    cell.clear();
    for (long long i = 1; i <= k; ++i) {
      const long long h = p.integer(p.tok()[i], "half-face");
      if (h < 0 || h >= 2 * nf) p.fail(p.line(), fmt::format("half-face {} out of range [0, {})", h, 2 * nf));
      cell.push_back(int(h));
    }
    r.soup.add_cell(cell);
    r.cell_where.push_back(p.line());
  }
  return r;
}

std::string write_ovm(const VolumeMesh& mesh) {
  const auto& X = mesh.positions();
  const auto& E = mesh.edges();
  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  fmt::format_to(out, "OVM ASCII\nVertices\n{}\n", mesh.n_vertices());
  for (int v = 0; v < mesh.n_vertices(); ++v)
    fmt::format_to(out, "{} {} {}\n", num(X(v, 0)), num(X(v, 1)), num(X(v, 2)));
  fmt::format_to(out, "Edges\n{}\n", E.rows());
  for (Eigen::Index e = 0; e < E.rows(); ++e) fmt::format_to(out, "{} {}\n", E(e, 0), E(e, 1));
  // Halfedge of the directed edge (a, b): edges are sorted lexicographically by (min, max).
  auto halfedge = [&](int a, int b) {
    const int lo = std::min(a, b), hi = std::max(a, b);
    Eigen::Index first = 0, count = E.rows();
    while (count > 0) {
      const Eigen::Index step = count / 2, mid = first + step;
      if (E(mid, 0) < lo || (E(mid, 0) == lo && E(mid, 1) < hi)) {
        first = mid + 1;
        count -= step + 1;
      } else {
        count = step;
      }
    }
    return 2 * first + (a < b ? 0 : 1);
  };
  fmt::format_to(out, "Faces\n{}\n", mesh.n_faces());
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto vs = mesh.face(f);
    fmt::format_to(out, "{}", vs.size());
    for (size_t i = 0; i < vs.size(); ++i)
      fmt::format_to(out, " {}", halfedge(vs[i], vs[(i + 1) % vs.size()]));
    b.push_back('\n');
  }
  fmt::format_to(out, "Polyhedra\n{}\n", mesh.n_cells());
  for (int c = 0; c < mesh.n_cells(); ++c) {
    fmt::format_to(out, "{}", mesh.cell_size(c));
    for (int h : mesh.cell(c)) fmt::format_to(out, " {}", h);
    b.push_back('\n');
  }
  return fmt::to_string(b);
}

}  // namespace io_detail
}  // namespace polydec
