// dec/io/ply.cpp — Stanford PLY: ascii, binary_little_endian, binary_big_endian. Vertex x, y, z
// of any numeric type; faces from the list property vertex_indices (or vertex_index) with any
// integer count and index types; every other element and property (lists too) is skipped.
#include <climits>

#include "polydec/dec/detail/io_common.h"

namespace polydec::io_detail {

namespace {

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64 };

bool parse_type(std::string_view s, Type& t) {
  static const std::pair<const char*, Type> names[] = {
      {"char", Type::I8},   {"int8", Type::I8},     {"uchar", Type::U8},   {"uint8", Type::U8},
      {"short", Type::I16}, {"int16", Type::I16},   {"ushort", Type::U16}, {"uint16", Type::U16},
      {"int", Type::I32},   {"int32", Type::I32},   {"uint", Type::U32},   {"uint32", Type::U32},
      {"float", Type::F32}, {"float32", Type::F32}, {"double", Type::F64}, {"float64", Type::F64}};
  for (const auto& [n, ty] : names)
    if (s == n) {
      t = ty;
      return true;
    }
  return false;
}

size_t size_of(Type t) {
  switch (t) {
    case Type::I8:
    case Type::U8:
      return 1;
    case Type::I16:
    case Type::U16:
      return 2;
    case Type::I32:
    case Type::U32:
    case Type::F32:
      return 4;
    case Type::F64:
      return 8;
  }
  return 0;
}

bool is_integer(Type t) { return t != Type::F32 && t != Type::F64; }

struct Property {
  std::string name;
  bool list = false;
  Type count_type = Type::U8, type = Type::F32;
};

struct Element {
  std::string name;
  long long count = 0;
  long line = 0;
  std::vector<Property> props;
};

enum class Format { Ascii, Little, Big };

// Reads one binary value of type t as a double (integers exactly).
double read_value(BinaryCursor& in, Type t, const char* what) {
  switch (t) {
    case Type::I8:
      return in.read<std::int8_t>(what);
    case Type::U8:
      return in.read<std::uint8_t>(what);
    case Type::I16:
      return in.read<std::int16_t>(what);
    case Type::U16:
      return in.read<std::uint16_t>(what);
    case Type::I32:
      return in.read<std::int32_t>(what);
    case Type::U32:
      return in.read<std::uint32_t>(what);
    case Type::F32:
      return in.read<float>(what);
    case Type::F64:
      return in.read<double>(what);
  }
  return 0;
}

// Whitespace-separated tokens of the ascii body, across lines.
class Tokens {
 public:
  Tokens(std::string_view text, size_t start, long first_line) : lines_(text, start, first_line) {}
  // Next token; false at the end of the file.
  bool next(std::string_view& t) {
    while (k_ >= tok_.size()) {
      std::string_view line;
      if (!lines_.next(line)) return false;
      split(line, tok_);
      k_ = 0;
    }
    t = tok_[k_++];
    return true;
  }
  long line() const { return lines_.line(); }

 private:
  LineReader lines_;
  std::vector<std::string_view> tok_;
  size_t k_ = 0;
};

}  // namespace

SoupRead read_ply(std::string_view bytes, const std::string& name) {
  const std::string_view text = strip_bom(bytes);
  const size_t base = bytes.size() - text.size();
  LineReader lines(text);
  std::string_view line;
  std::vector<std::string_view> tok;
  if (!lines.next(line)) throw FileError(name, 0, -1, "empty file (no 'ply' header)");
  split(line, tok);
  if (tok.size() != 1 || tok[0] != "ply")
    throw FileError(name, 1, -1, "not a PLY file (first line is not 'ply')");

  // Header.
  Format format = Format::Ascii;
  bool have_format = false, have_end = false;
  std::vector<Element> elements;
  while (lines.next(line)) {
    const long ln = lines.line();
    split(line, tok);
    if (tok.empty() || tok[0] == "comment" || tok[0] == "obj_info") continue;
    if (tok[0] == "end_header") {
      have_end = true;
      break;
    }
    if (tok[0] == "format") {
      if (tok.size() < 2) throw FileError(name, ln, -1, "format line without a format");
      if (tok[1] == "ascii")
        format = Format::Ascii;
      else if (tok[1] == "binary_little_endian")
        format = Format::Little;
      else if (tok[1] == "binary_big_endian")
        format = Format::Big;
      else
        throw FileError(name, ln, -1, "unknown PLY format " + quote(tok[1]));
      have_format = true;
    } else if (tok[0] == "element") {
      if (tok.size() != 3) throw FileError(name, ln, -1, "expected 'element NAME COUNT'");
      Element e;
      e.name = std::string(tok[1]);
      e.line = ln;
      if (!parse_int(tok[2], e.count)) throw FileError(name, ln, -1, "bad element count " + quote(tok[2]));
      if (e.count < 0) throw FileError(name, ln, -1, fmt::format("negative element count {}", e.count));
      for (const auto& o : elements)
        if (o.name == e.name) throw FileError(name, ln, -1, "element " + quote(e.name) + " declared twice");
      elements.push_back(std::move(e));
    } else if (tok[0] == "property") {
      if (elements.empty()) throw FileError(name, ln, -1, "property before any element");
      Property p;
      if (tok.size() == 5 && tok[1] == "list") {
        p.list = true;
        if (!parse_type(tok[2], p.count_type) || !parse_type(tok[3], p.type))
          throw FileError(name, ln, -1, "unknown property type in " + quote(line));
        if (!is_integer(p.count_type))
          throw FileError(name, ln, -1, "list count type must be an integer type");
        p.name = std::string(tok[4]);
      } else if (tok.size() == 3) {
        if (!parse_type(tok[1], p.type))
          throw FileError(name, ln, -1, "unknown property type " + quote(tok[1]));
        p.name = std::string(tok[2]);
      } else {
        throw FileError(name, ln, -1, "expected 'property TYPE NAME' or 'property list CTYPE TYPE NAME'");
      }
      elements.back().props.push_back(std::move(p));
    } else {
      throw FileError(name, ln, -1, "unknown header line " + quote(line));
    }
  }
  if (!have_end) throw FileError(name, lines.line(), -1, "header has no 'end_header'");
  if (!have_format) throw FileError(name, lines.line(), -1, "header has no 'format' line");

  // Which element and properties carry the mesh.
  int ev = -1, ef = -1, px[3] = {-1, -1, -1}, pf = -1;
  for (int e = 0; e < int(elements.size()); ++e) {
    const Element& el = elements[e];
    if (el.name == "vertex") {
      ev = e;
      for (int p = 0; p < int(el.props.size()); ++p)
        for (int c = 0; c < 3; ++c)
          if (px[c] < 0 && el.props[p].name == std::string(1, char('x' + c))) {
            if (el.props[p].list) throw FileError(name, el.line, -1, "vertex coordinate is a list");
            px[c] = p;
          }
      if (px[0] < 0 || px[1] < 0 || px[2] < 0)
        throw FileError(name, el.line, -1, "vertex element lacks an x, y or z property");
      if (el.count > INT_MAX / 2)
        throw FileError(name, el.line, -1, fmt::format("{} vertices: too many", el.count));
    } else if (el.name == "face") {
      ef = e;
      for (int p = 0; p < int(el.props.size()) && pf < 0; ++p)
        if (el.props[p].name == "vertex_indices" || el.props[p].name == "vertex_index") pf = p;
      if (pf < 0) throw FileError(name, el.line, -1, "face element lacks a vertex_indices list");
      if (!el.props[pf].list || !is_integer(el.props[pf].type))
        throw FileError(name, el.line, -1, "vertex_indices must be a list of an integer type");
      if (el.count > INT_MAX / 2)
        throw FileError(name, el.line, -1, fmt::format("{} faces: too many", el.count));
    }
  }
  if (ev < 0) throw FileError(name, 0, -1, "no vertex element");
  const long long nv = elements[ev].count;

  // Refuse counts the data cannot hold (each ascii value takes at least 2 bytes).
  const size_t data_start = lines.position();
  const long long avail = (long long)(text.size() - data_start) + (format == Format::Ascii ? 1 : 0);
  long long need = 0;
  for (const Element& el : elements) {
    long long rec = 0;
    for (const Property& p : el.props)
      rec += format == Format::Ascii ? 2 : static_cast<long long>(size_of(p.list ? p.count_type : p.type));
    if (rec > 0 && el.count > (avail - need) / rec)
      throw FileError(
          name, el.line, -1,
          fmt::format("element {} claims {} records (at least {} bytes each) but only {} bytes of data "
                      "follow",
                      quote(el.name), el.count, rec, avail - (format == Format::Ascii ? 1 : 0)));
    need += rec * el.count;
  }

  SoupRead r;
  r.where_is_byte = format != Format::Ascii;
  r.soup.positions.resize(nv, 3);
  r.vertex_where.resize(nv);
  if (ef >= 0) {
    r.face_where.reserve(elements[ef].count);
    r.soup.face_offsets.reserve(elements[ef].count + 1);
  }

  if (format == Format::Ascii) {
    DigitCounter digits;
    Tokens in(text, data_start, lines.line() + 1);
    std::string_view t;
    auto next = [&](const Element& el, long long i) {
      if (!in.next(t))
        throw FileError(name, in.line(), -1,
                        fmt::format("unexpected end of file in {} {} of {}", el.name, i, el.count));
      return t;
    };
    for (int e = 0; e < int(elements.size()); ++e) {
      const Element& el = elements[e];
      if (el.props.empty()) continue;
      for (long long i = 0; i < el.count; ++i) {
        for (int p = 0; p < int(el.props.size()); ++p) {
          const Property& pr = el.props[p];
          const std::string_view first = next(el, i);
          if (p == 0 && e == ev) r.vertex_where[i] = in.line();
          if (p == 0 && e == ef) r.face_where.push_back(in.line());
          if (!pr.list) {
            double x;
            if (!parse_double(first, x)) throw FileError(name, in.line(), -1, "bad number " + quote(first));
            if (e == ev)
              for (int c = 0; c < 3; ++c)
                if (p == px[c]) {
                  r.soup.positions(i, c) = x;
                  digits.see(first, x);
                }
            continue;
          }
          long long n;
          if (!parse_int(first, n) || n < 0)
            throw FileError(name, in.line(), -1, "bad list count " + quote(first));
          for (long long k = 0; k < n; ++k) {
            const std::string_view v = next(el, i);
            if (e == ef && p == pf) {
              long long idx;
              if (!parse_int(v, idx)) throw FileError(name, in.line(), -1, "bad vertex index " + quote(v));
              if (idx < 0 || idx >= nv)
                throw FileError(name, in.line(), -1,
                                fmt::format("face {} vertex index {} out of range [0, {})", i, idx, nv));
              if (r.soup.face_indices.size() >= size_t(INT_MAX / 2))
                throw FileError(name, in.line(), -1, "too many face corners");
              r.soup.face_indices.push_back(int(idx));
            } else {
              double x;
              if (!parse_double(v, x)) throw FileError(name, in.line(), -1, "bad number " + quote(v));
            }
          }
          if (e == ef && p == pf) r.soup.face_offsets.push_back(int(r.soup.face_indices.size()));
        }
      }
    }
    r.soup.precision = digits.precision(r.soup.positions);
    return r;
  }

  BinaryCursor in(bytes, base + data_start, format == Format::Big, name);
  for (int e = 0; e < int(elements.size()); ++e) {
    const Element& el = elements[e];
    if (el.props.empty()) continue;
    const std::string what = el.name + " record";
    for (long long i = 0; i < el.count; ++i) {
      if (e == ev) r.vertex_where[i] = long(in.position());
      if (e == ef) r.face_where.push_back(long(in.position()));
      for (int p = 0; p < int(el.props.size()); ++p) {
        const Property& pr = el.props[p];
        if (!pr.list) {
          if (e == ev && (p == px[0] || p == px[1] || p == px[2])) {
            const double x = read_value(in, pr.type, what.c_str());
            for (int c = 0; c < 3; ++c)
              if (p == px[c]) r.soup.positions(i, c) = x;
          } else {
            in.skip(size_of(pr.type), what.c_str());
          }
          continue;
        }
        const long at = long(in.position());
        const double n = read_value(in, pr.count_type, what.c_str());
        const size_t item = size_of(pr.type);
        if (n < 0 || n > double(in.remaining() / item))
          throw FileError(
              name, 0, at,
              fmt::format("{} {}: list of {} items but only {} bytes follow", el.name, i, n, in.remaining()));
        const size_t count = size_t(n);
        if (e == ef && p == pf) {
          if (r.soup.face_indices.size() + count > size_t(INT_MAX / 2))
            throw FileError(name, 0, at, "too many face corners");
          for (size_t k = 0; k < count; ++k) {
            const long iat = long(in.position());
            const double idx = read_value(in, pr.type, what.c_str());
            if (idx < 0 || idx >= double(nv))
              throw FileError(name, 0, iat,
                              fmt::format("face {} vertex index {} out of range [0, {})", i, idx, nv));
            r.soup.face_indices.push_back(int(idx));
          }
          r.soup.face_offsets.push_back(int(r.soup.face_indices.size()));
        } else {
          in.skip(count * item, what.c_str());
        }
      }
    }
  }
  // Binary coordinates resolve their type's precision: float32 2^-24 relative, the rest double
  // round-off (integers are exact).
  for (int c = 0; c < 3; ++c)
    if (elements[ev].props[px[c]].type == Type::F32) r.soup.precision = float_precision(r.soup.positions);
  return r;
}

std::string write_ply(const Mesh& mesh, const VertexScalars& scalars, bool binary) {
  const auto& X = mesh.positions();
  const bool small = mesh.max_face_size() <= 255;
  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  fmt::format_to(out, "ply\nformat {} 1.0\ncomment written by polydec\nelement vertex {}\n",
                 binary ? "binary_little_endian" : "ascii", mesh.n_vertices());
  fmt::format_to(out, "property double x\nproperty double y\nproperty double z\n");
  for (const auto& [name, values] : scalars) fmt::format_to(out, "property double {}\n", name);
  fmt::format_to(out, "element face {}\nproperty list {} int vertex_indices\nend_header\n", mesh.n_faces(),
                 small ? "uchar" : "int");
  std::string s = fmt::to_string(b);
  if (binary) {
    for (int v = 0; v < mesh.n_vertices(); ++v) {
      for (int c = 0; c < 3; ++c) put_le<double>(s, X(v, c));
      for (const auto& [name, values] : scalars) put_le<double>(s, values[v]);
    }
    for (int f = 0; f < mesh.n_faces(); ++f) {
      if (small)
        put_le<std::uint8_t>(s, std::uint8_t(mesh.face_size(f)));
      else
        put_le<std::int32_t>(s, mesh.face_size(f));
      for (int v : mesh.face(f)) put_le<std::int32_t>(s, v);
    }
    return s;
  }
  b.clear();
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    fmt::format_to(out, "{:.17g} {:.17g} {:.17g}", X(v, 0), X(v, 1), X(v, 2));
    for (const auto& [name, values] : scalars) fmt::format_to(out, " {:.17g}", values[v]);
    b.push_back('\n');
  }
  for (int f = 0; f < mesh.n_faces(); ++f) {
    fmt::format_to(out, "{}", mesh.face_size(f));
    for (int v : mesh.face(f)) fmt::format_to(out, " {}", v);
    b.push_back('\n');
  }
  s.append(b.data(), b.size());
  return s;
}

}  // namespace polydec::io_detail
