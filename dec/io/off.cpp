// dec/io/off.cpp — Object File Format. ASCII: header OFF (also COFF, NOFF, CNOFF, STOFF...,
// extra per-vertex and per-face fields ignored), counts on the header line or the next,
// '#' comments and blank lines anywhere; one vertex or face per line. Binary: "OFF BINARY"
// as pmp-library writes it (little-endian int32 counts, float32 positions, per face an
// int32 valence and int32 indices, no colors).
#include <climits>

#include "polydec/dec/detail/io_common.h"

namespace polydec::io_detail {

namespace {

// Next line that is not blank once its '#' comment is cut; false at the end of the file.
bool next_significant(LineReader& lines, std::vector<std::string_view>& tok) {
  std::string_view line;
  while (lines.next(line)) {
    if (const auto h = line.find('#'); h != std::string_view::npos) line = line.substr(0, h);
    split(line, tok);
    if (!tok.empty()) return true;
  }
  return false;
}

long long count(std::string_view t, const char* what, const std::string& name, long ln) {
  long long n;
  if (!parse_int(t, n)) throw FileError(name, ln, -1, fmt::format("bad {} count {}", what, quote(t)));
  if (n < 0) throw FileError(name, ln, -1, fmt::format("negative {} count {}", what, n));
  if (n > INT_MAX / 2)
    throw FileError(name, ln, -1, fmt::format("{} count {} is too large (at most {})", what, n, INT_MAX / 2));
  return n;
}

std::uint32_t byteswap32(std::uint32_t x) {
  return (x >> 24) | ((x >> 8) & 0xff00u) | ((x << 8) & 0xff0000u) | (x << 24);
}

SoupRead read_off_binary(std::string_view bytes, size_t start, const std::string& name) {
  BinaryCursor in(bytes, start, false, name);
  const std::int32_t nv = in.read<std::int32_t>("header counts");
  const std::int32_t nf = in.read<std::int32_t>("header counts");
  in.read<std::int32_t>("header counts");
  const long long need = 12LL * std::max(nv, 0) + 4LL * std::max(nf, 0);
  if (nv < 0 || nf < 0 || need > (long long)in.remaining()) {
    const std::int32_t snv = std::int32_t(byteswap32(std::uint32_t(nv)));
    const std::int32_t snf = std::int32_t(byteswap32(std::uint32_t(nf)));
    const bool swapped = snv >= 0 && snf >= 0 && 12LL * snv + 4LL * snf <= (long long)in.remaining();
    const std::string hint =
        swapped ? fmt::format(
                      " (read big-endian they would be {} and {}: polydec reads OFF BINARY as "
                      "little-endian, the layout pmp-library writes)",
                      snv, snf)
                : "";
    if (nv < 0 || nf < 0)
      throw FileError(name, 0, long(start),
                      fmt::format("negative counts {} vertices, {} faces{}", nv, nf, hint));
    throw FileError(
        name, 0, long(start),
        fmt::format("header claims {} vertices and {} faces (at least {} bytes) but only {} bytes "
                    "follow{}",
                    nv, nf, need, in.remaining(), hint));
  }
  SoupRead r;
  r.where_is_byte = true;
  r.soup.positions.resize(nv, 3);
  r.vertex_where.resize(nv);
  for (int v = 0; v < nv; ++v) {
    r.vertex_where[v] = long(in.position());
    for (int c = 0; c < 3; ++c) r.soup.positions(v, c) = in.read<float>("vertex record");
  }
  r.soup.precision = float_precision(r.soup.positions);  // float32 positions
  r.face_where.reserve(nf);
  r.soup.face_offsets.reserve(size_t(nf) + 1);
  r.soup.face_indices.reserve(std::min<size_t>(size_t(nf) * 6, in.remaining() / 4));
  for (int f = 0; f < nf; ++f) {
    r.face_where.push_back(long(in.position()));
    const std::int32_t n = in.read<std::int32_t>("face record");
    if (n < 0 || size_t(n) > in.remaining() / 4)
      throw FileError(
          name, 0, r.face_where.back(),
          fmt::format("face {} claims {} vertices but only {} bytes follow", f, n, in.remaining()));
    for (int k = 0; k < n; ++k) {
      const long at = long(in.position());
      const std::int32_t i = in.read<std::int32_t>("face record");
      if (i < 0 || i >= nv)
        throw FileError(name, 0, at, fmt::format("face {} vertex index {} out of range [0, {})", f, i, nv));
      r.soup.face_indices.push_back(i);
    }
    r.soup.face_offsets.push_back(int(r.soup.face_indices.size()));
  }
  return r;
}

}  // namespace

SoupRead read_off(std::string_view bytes, const std::string& name) {
  const std::string_view text = strip_bom(bytes);
  const size_t base = bytes.size() - text.size();
  std::vector<std::string_view> tok;
  LineReader lines(text);
  if (!next_significant(lines, tok)) throw FileError(name, 0, -1, "empty file (no OFF header)");
  const long head_line = lines.line();
  std::string_view key = tok[0];
  const std::string_view full_key = key;
  if (key.substr(0, 2) == "ST") key.remove_prefix(2);
  if (key.substr(0, 1) == "C") key.remove_prefix(1);
  if (key.substr(0, 1) == "N") key.remove_prefix(1);
  if (key == "4OFF" || key == "nOFF")
    throw FileError(name, head_line, -1,
                    fmt::format("{} (non-3D vertices) is not supported", quote(full_key)));
  if (key != "OFF")
    throw FileError(name, head_line, -1, fmt::format("expected an OFF header, found {}", quote(full_key)));
  if (tok.size() >= 2 && tok[1] == "BINARY") {
    if (full_key != "OFF")
      throw FileError(name, head_line, -1,
                      fmt::format("{} BINARY is not supported (only plain OFF BINARY)", quote(full_key)));
    return read_off_binary(bytes, base + lines.position(), name);
  }
  long count_line = head_line;
  if (tok.size() == 1) {
    if (!next_significant(lines, tok)) throw FileError(name, head_line, -1, "header only: no counts");
    count_line = lines.line();
  } else {
    tok.erase(tok.begin());
  }
  if (tok.size() < 2) throw FileError(name, count_line, -1, "expected vertex and face counts");
  const long long nv = count(tok[0], "vertex", name, count_line);
  const long long nf = count(tok[1], "face", name, count_line);
  const long long need = 6 * nv + 2 * nf;
  if (need > (long long)lines.remaining() + 1)
    throw FileError(
        name, count_line, -1,
        fmt::format("header claims {} vertices and {} faces (at least {} bytes) but only {} bytes "
                    "follow",
                    nv, nf, need, lines.remaining()));
  SoupRead r;
  r.soup.positions.resize(nv, 3);
  r.vertex_where.resize(nv);
  DigitCounter digits;
  for (long long v = 0; v < nv; ++v) {
    if (!next_significant(lines, tok))
      throw FileError(name, lines.line(), -1,
                      fmt::format("unexpected end of file after {} of {} vertices", v, nv));
    const long ln = r.vertex_where[v] = lines.line();
    if (tok.size() < 3)
      throw FileError(name, ln, -1, fmt::format("vertex needs 3 coordinates, found {}", tok.size()));
    for (int c = 0; c < 3; ++c) {
      if (!parse_double(tok[c], r.soup.positions(v, c)))
        throw FileError(name, ln, -1, "bad vertex coordinate " + quote(tok[c]));
      digits.see(tok[c], r.soup.positions(v, c));
    }
  }
  r.soup.precision = digits.precision(r.soup.positions);
  r.face_where.reserve(nf);
  r.soup.face_offsets.reserve(nf + 1);
  std::vector<int> face;
  for (long long f = 0; f < nf; ++f) {
    if (!next_significant(lines, tok))
      throw FileError(name, lines.line(), -1,
                      fmt::format("unexpected end of file after {} of {} faces", f, nf));
    const long ln = lines.line();
    long long n;
    if (!parse_int(tok[0], n) || n < 0) throw FileError(name, ln, -1, "bad face valence " + quote(tok[0]));
    if (n > (long long)tok.size() - 1)
      throw FileError(
          name, ln, -1,
          fmt::format("face lists {} vertices but the line has {} more numbers", n, tok.size() - 1));
    face.clear();
    for (long long k = 1; k <= n; ++k) {
      long long i;
      if (!parse_int(tok[k], i)) throw FileError(name, ln, -1, "bad face index " + quote(tok[k]));
      if (i < 0 || i >= nv)
        throw FileError(name, ln, -1, fmt::format("face vertex index {} out of range [0, {})", i, nv));
      face.push_back(int(i));
    }
    if (r.soup.face_indices.size() + face.size() > size_t(INT_MAX / 2))
      throw FileError(name, ln, -1, "too many face corners");
    r.soup.add_face(face);
    r.face_where.push_back(ln);
  }
  return r;
}

std::string write_off(const Mesh& mesh, bool binary) {
  const auto& X = mesh.positions();
  if (binary) {
    std::string out = "OFF BINARY\n";
    put_le<std::int32_t>(out, mesh.n_vertices());
    put_le<std::int32_t>(out, mesh.n_faces());
    put_le<std::int32_t>(out, 0);
    for (int v = 0; v < mesh.n_vertices(); ++v)
      for (int c = 0; c < 3; ++c) put_le<float>(out, float(X(v, c)));
    for (int f = 0; f < mesh.n_faces(); ++f) {
      put_le<std::int32_t>(out, mesh.face_size(f));
      for (int v : mesh.face(f)) put_le<std::int32_t>(out, v);
    }
    return out;
  }
  fmt::memory_buffer b;
  fmt::format_to(std::back_inserter(b), "OFF\n{} {} 0\n", mesh.n_vertices(), mesh.n_faces());
  for (int v = 0; v < mesh.n_vertices(); ++v)
    fmt::format_to(std::back_inserter(b), "{:.17g} {:.17g} {:.17g}\n", X(v, 0), X(v, 1), X(v, 2));
  for (int f = 0; f < mesh.n_faces(); ++f) {
    fmt::format_to(std::back_inserter(b), "{}", mesh.face_size(f));
    for (int v : mesh.face(f)) fmt::format_to(std::back_inserter(b), " {}", v);
    b.push_back('\n');
  }
  return fmt::to_string(b);
}

}  // namespace polydec::io_detail
