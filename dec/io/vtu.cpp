// dec/io/vtu.cpp — VTK XML unstructured grids (.vtu). The XML is parsed by expat up to an
// <AppendedData> element (whose raw bytes are not XML); data arrays are ASCII, inline base64
// ("binary") or appended (raw or base64) at their offset, each behind a UInt32 or UInt64 header
// (byte_order LittleEndian or BigEndian), optionally compressed in blocks (header: block count, block
// size, last block size, compressed sizes) by vtkZLibDataCompressor, vtkLZ4DataCompressor (LZ4 block
// format) or vtkLZMADataCompressor (xz streams), inflated by zlib, liblz4 and liblzma.
// Cells: connectivity, offsets, types, and for polyhedra (42) the faces / faceoffsets face
// streams of VTK 9.1 or VTK 9.4's face_connectivity, face_offsets, polyhedron_to_faces and
// polyhedron_offsets; several pieces are concatenated; volume cells (10, 11, 12, 13, 14, 42) with lower-dimensional cells skipped
// and counted, or, with no volume cell, a surface of triangles 5, pixels 8, quads 9 and polygons 7.
// The writer emits one piece, inline base64, ASCII, or appended raw data compressed by zlib.
#include "polydec/dec/io/vtu.h"

#include <expat.h>
#include <lz4.h>
#include <lzma.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <memory>

#include "polydec/dec/detail/io_common.h"
#include "polydec/dec/detail/volume_io_common.h"
#include "polydec/dec/mesh/polyhedron_builder.h"

namespace polydec {
namespace io_vtu_detail {
namespace {

using namespace io_detail;

// One XML element: name, attributes, character data (kept for DataArray only) and the line it
// starts on.
struct Node {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::string text;
  long line = 0;
  std::vector<int> children;

  const std::string* attribute(std::string_view key) const {
    for (const auto& [k, v] : attributes)
      if (k == key) return &v;
    return nullptr;
  }
};

// The parsed file: its elements (0 is the root) and where the appended data starts.
struct Document {
  std::vector<Node> nodes;
  bool appended = false;
  bool appended_base64 = false;
  size_t appended_start = 0;  // the byte after the '_' marker
};

struct ParseState {
  XML_Parser parser = nullptr;
  Document* doc = nullptr;
  std::vector<int> stack;
  bool doctype = false;
  bool appended_tag = false;
  size_t appended_tag_end = 0;
  std::string appended_encoding;
};

void XMLCALL on_start(void* data, const XML_Char* name, const XML_Char** attributes) {
  auto& s = *static_cast<ParseState*>(data);
  if (std::string_view(name) == "AppendedData") {
    // Its content is raw bytes: stop here and read them by offset.
    s.appended_tag = true;
    s.appended_tag_end = size_t(XML_GetCurrentByteIndex(s.parser) + XML_GetCurrentByteCount(s.parser));
    for (int i = 0; attributes[i]; i += 2)
      if (std::string_view(attributes[i]) == "encoding") s.appended_encoding = attributes[i + 1];
    XML_StopParser(s.parser, XML_FALSE);
    return;
  }
  Node n;
  n.name = name;
  n.line = long(XML_GetCurrentLineNumber(s.parser));
  for (int i = 0; attributes[i]; i += 2) n.attributes.emplace_back(attributes[i], attributes[i + 1]);
  const int id = int(s.doc->nodes.size());
  if (!s.stack.empty()) s.doc->nodes[size_t(s.stack.back())].children.push_back(id);
  s.doc->nodes.push_back(std::move(n));
  s.stack.push_back(id);
}

void XMLCALL on_end(void* data, const XML_Char*) {
  auto& s = *static_cast<ParseState*>(data);
  if (!s.stack.empty()) s.stack.pop_back();
}

void XMLCALL on_text(void* data, const XML_Char* text, int length) {
  auto& s = *static_cast<ParseState*>(data);
  if (s.stack.empty()) return;
  Node& n = s.doc->nodes[size_t(s.stack.back())];
  if (n.name == "DataArray") n.text.append(text, size_t(length));
}

void XMLCALL on_doctype(void* data, const XML_Char*, const XML_Char*, const XML_Char*, int) {
  auto& s = *static_cast<ParseState*>(data);
  s.doctype = true;
  XML_StopParser(s.parser, XML_FALSE);
}

Document parse_xml(std::string_view bytes, const std::string& name) {
  if (bytes.size() > size_t(INT_MAX)) throw FileError(name, 0, -1, "file larger than 2 GB: not read");
  Document doc;
  ParseState s;
  s.doc = &doc;
  std::unique_ptr<XML_ParserStruct, void (*)(XML_Parser)> parser(XML_ParserCreate(nullptr), XML_ParserFree);
  if (!parser) throw std::bad_alloc();
  s.parser = parser.get();
  XML_SetUserData(s.parser, &s);
  XML_SetElementHandler(s.parser, on_start, on_end);
  XML_SetCharacterDataHandler(s.parser, on_text);
  XML_SetStartDoctypeDeclHandler(s.parser, on_doctype);
  const XML_Status status = XML_Parse(s.parser, bytes.data(), int(bytes.size()), XML_TRUE);
  const long line = long(XML_GetCurrentLineNumber(s.parser));
  if (s.doctype) throw FileError(name, line, -1, "a DOCTYPE declaration is not accepted in a VTK file");
  if (status != XML_STATUS_OK && !s.appended_tag)
    throw FileError(name, line, -1,
                    fmt::format("not well-formed XML: {}", XML_ErrorString(XML_GetErrorCode(s.parser))));
  if (doc.nodes.empty()) throw FileError(name, line, -1, "no XML element");
  if (s.appended_tag) {
    doc.appended = true;
    const std::string e = lower(s.appended_encoding);
    if (e != "raw" && e != "base64")
      throw FileError(name, line, -1,
                      fmt::format("AppendedData encoding {} is not supported (raw, base64)", quote(e)));
    doc.appended_base64 = e == "base64";
    size_t p = s.appended_tag_end;
    while (p < bytes.size() && (is_space(bytes[p]) || bytes[p] == '\n')) ++p;
    if (p >= bytes.size() || bytes[p] != '_')
      throw FileError(name, line, -1, "AppendedData does not start with the '_' marker");
    doc.appended_start = p + 1;
  }
  return doc;
}

// The compressors of VTK's XML writers.
enum class Compressor { none, zlib, lz4, lzma };

// The file-wide encoding: header word size, byte order, compression.
struct Encoding {
  bool big_endian = false;
  size_t header = 4;
  Compressor compressor = Compressor::none;
};

// The name of a compressor in messages.
const char* compressor_name(Compressor c) {
  return c == Compressor::zlib ? "zlib" : c == Compressor::lz4 ? "LZ4" : "LZMA";
}

// An upper bound on what a compressed block of `size` bytes inflates to: zlib expands at most about
// 1032 to 1, LZ4 about 255 to 1 and xz (LZMA2) about 7000 to 1.
std::uint64_t max_inflated(Compressor c, std::uint64_t size) {
  const std::uint64_t ratio = c == Compressor::zlib ? 1100 : c == Compressor::lz4 ? 256 : 8000;
  return size > (UINT64_MAX - 64) / 8000 ? UINT64_MAX : ratio * size + 64;
}

// The memory liblzma may use to inflate a block (its dictionary): enough for VTK's presets up to 9
// (64 MiB dictionaries), not more, whatever a block's header claims.
constexpr std::uint64_t kLzmaMemoryLimit = std::uint64_t(128) << 20;

// Inflates the blocks of a file's arrays: each `packed` into exactly `want` bytes at `out`, returning
// the problem (empty when there is none). liblzma's decoder, its dictionary included, is set up
// once and reused from block to block and array to array.
class Inflater {
 public:
  explicit Inflater(Compressor c) : c_(c) {}
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;
  ~Inflater() { lzma_end(&lzma_); }

  std::string operator()(const std::string& packed, char* out, size_t want) {
    if (c_ == Compressor::zlib) {
      uLongf got = uLongf(want);
      const int rc = uncompress(reinterpret_cast<Bytef*>(out), &got, reinterpret_cast<const Bytef*>(packed.data()),
                                uLong(packed.size()));
      if (rc != Z_OK) return zError(rc);
      return got == want ? std::string() : fmt::format("{} bytes", got);
    }
    if (c_ == Compressor::lz4) {
      if (packed.size() > size_t(INT_MAX) || want > size_t(INT_MAX)) return "a block beyond LZ4's 2 GB";
      const int got = LZ4_decompress_safe(packed.data(), out, int(packed.size()), int(want));
      if (got < 0) return "corrupt LZ4 data";
      return size_t(got) == want ? std::string() : fmt::format("{} bytes", got);
    }
    lzma_ret rc = lzma_stream_decoder(&lzma_, kLzmaMemoryLimit, 0);
    if (rc == LZMA_OK) {
      lzma_.next_in = reinterpret_cast<const std::uint8_t*>(packed.data());
      lzma_.avail_in = packed.size();
      lzma_.next_out = reinterpret_cast<std::uint8_t*>(out);
      lzma_.avail_out = want;
      rc = lzma_code(&lzma_, LZMA_FINISH);
    }
    switch (rc) {
      case LZMA_STREAM_END:
        return lzma_.avail_out == 0 ? std::string() : fmt::format("{} bytes", want - lzma_.avail_out);
      case LZMA_OK:  // stopped before the stream's end: the block is full, or its bytes ran out
        return lzma_.avail_out == 0 ? "more bytes than the block holds" : "a truncated stream";
      case LZMA_FORMAT_ERROR:
        return "not an xz stream";
      case LZMA_OPTIONS_ERROR:
        return "unsupported xz options";
      case LZMA_DATA_ERROR:
        return "corrupt xz data";
      case LZMA_BUF_ERROR:
        return "a truncated stream";
      case LZMA_MEMLIMIT_ERROR:
        return fmt::format("its dictionary needs more than {} MiB", kLzmaMemoryLimit >> 20);
      default:
        return fmt::format("liblzma error {}", int(rc));
    }
  }

 private:
  Compressor c_;
  lzma_stream lzma_ = LZMA_STREAM_INIT;
};

// The bytes of one binary array: raw (`base64` false) or base64 characters decoded on demand, group
// by group, so that a header encoded apart from its data (padded) and one encoded with it both
// read. Errors name `at`: the DataArray's line (line > 0) or the array's byte offset.
class Bytes {
 public:
  Bytes(std::string_view source, bool base64, const std::string& name, long line, long byte)
      : src_(source), base64_(base64), name_(name), line_(line), byte_(byte) {}

  // An upper bound on the bytes left.
  size_t capacity() const { return base64_ ? (src_.size() - pos_) / 4 * 3 + 3 : src_.size() - pos_; }

  // Appends the next n bytes to out.
  void read(size_t n, std::string& out, const char* what) {
    if (n > capacity())
      fail(fmt::format("truncated {}: {} bytes announced, at most {} follow", what, n, capacity()));
    if (!base64_) {
      out.append(src_.substr(pos_, n));
      pos_ += n;
      return;
    }
    while (n > 0) {
      if (have_ == next_) decode_group(what);
      const size_t k = std::min(n, have_ - next_);
      out.append(group_.data() + next_, k);
      next_ += k, n -= k;
    }
  }
  template <class T>
  T word(const Encoding& e, const char* what) {
    std::string b;
    read(sizeof(T), b, what);
    return BinaryCursor(b, 0, e.big_endian, name_).read<T>(what);
  }
  // A header word (UInt32 or UInt64).
  std::uint64_t header(const Encoding& e, const char* what) {
    return e.header == 8 ? word<std::uint64_t>(e, what) : word<std::uint32_t>(e, what);
  }

  [[noreturn]] void fail(const std::string& reason) const {
    throw FileError(name_, line_ > 0 ? line_ : 0, line_ > 0 ? -1 : byte_, reason);
  }

 private:
  static int value(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  }
  void decode_group(const char* what) {
    std::array<char, 4> q{};
    for (int k = 0; k < 4;) {
      if (pos_ >= src_.size()) fail(fmt::format("truncated base64 data in {}", what));
      const char c = src_[pos_++];
      if (is_space(c) || c == '\n') continue;
      q[size_t(k++)] = c;
    }
    const int pad = q[3] != '=' ? 0 : q[2] != '=' ? 1 : 2;
    std::uint32_t bits = 0;
    for (int k = 0; k < 4; ++k) {
      const int v = k >= 4 - pad ? 0 : value(q[size_t(k)]);
      if (v < 0)
        fail(fmt::format("invalid base64 character {} in {}", quote(std::string_view(&q[size_t(k)], 1)),
                         what));
      bits = (bits << 6) | std::uint32_t(v);
    }
    group_ = {char(bits >> 16), char((bits >> 8) & 0xff), char(bits & 0xff)};
    next_ = 0, have_ = size_t(3 - pad);
  }

  std::string_view src_;
  bool base64_;
  const std::string& name_;
  long line_, byte_;
  size_t pos_ = 0;
  std::array<char, 3> group_{};
  size_t next_ = 0, have_ = 0;
};

// VTK data types: their width, and whether they are floating-point or signed.
struct DataType {
  int width = 0;
  bool floating = false;
  bool is_signed = false;
};
bool data_type(std::string_view t, DataType& d) {
  static const std::array<std::pair<std::string_view, DataType>, 10> kTypes{{{"Int8", {1, false, true}},
                                                                             {"UInt8", {1, false, false}},
                                                                             {"Int16", {2, false, true}},
                                                                             {"UInt16", {2, false, false}},
                                                                             {"Int32", {4, false, true}},
                                                                             {"UInt32", {4, false, false}},
                                                                             {"Int64", {8, false, true}},
                                                                             {"UInt64", {8, false, false}},
                                                                             {"Float32", {4, true, true}},
                                                                             {"Float64", {8, true, true}}}};
  for (const auto& [n, type] : kTypes)
    if (n == t) return d = type, true;
  return false;
}

// One binary value of type t.
double value(BinaryCursor& cur, const DataType& t, const char* what) {
  if (t.floating) return t.width == 4 ? double(cur.read<float>(what)) : cur.read<double>(what);
  switch (t.width) {
    case 1:
      return t.is_signed ? double(cur.read<std::int8_t>(what)) : double(cur.read<std::uint8_t>(what));
    case 2:
      return t.is_signed ? double(cur.read<std::int16_t>(what)) : double(cur.read<std::uint16_t>(what));
    case 4:
      return t.is_signed ? double(cur.read<std::int32_t>(what)) : double(cur.read<std::uint32_t>(what));
    default:
      return t.is_signed ? double(cur.read<std::int64_t>(what)) : double(cur.read<std::uint64_t>(what));
  }
}

// The count of an array read whole: as many values as its data holds.
constexpr size_t kAnyCount = SIZE_MAX;

// Reads the data arrays of a parsed document.
class Arrays {
 public:
  Arrays(std::string_view bytes, const Document& doc, const Encoding& e, const std::string& name)
      : bytes_(bytes), doc_(doc), e_(e), name_(name), inflate_(e.compressor) {}

  [[noreturn]] void fail(const Node& n, const std::string& reason) const {
    throw FileError(name_, n.line, -1, reason);
  }

  // The n values (kAnyCount: as many as it holds) of DataArray `a` as doubles (`integers`: its type
  // must be an integer type), with the digits of ASCII values counted in `digits` and `float32` set
  // for a Float32 array.
  std::vector<double> values(const Node& a, size_t n, const std::string& what, bool integers,
                             DigitCounter* digits = nullptr, bool* float32 = nullptr) const {
    const std::string* type = a.attribute("type");
    DataType t;
    if (!type || !data_type(*type, t))
      fail(a, fmt::format("{} has the unsupported data type {} (Int8..UInt64, Float32, Float64)", what,
                          quote(type ? *type : "(none)")));
    if (integers && t.floating) fail(a, fmt::format("{} must have an integer type, not {}", what, *type));
    if (float32) *float32 = t.floating && t.width == 4;
    const std::string* format = a.attribute("format");
    const std::string f = format ? *format : "ascii";
    std::vector<double> out;
    if (f == "ascii") {
      if (n != kAnyCount && n > a.text.size() / 2 + 1)
        fail(a, fmt::format("{} needs {} values but holds only {} characters", what, n, a.text.size()));
      if (n != kAnyCount) out.reserve(n);
      std::vector<std::string_view> tokens;
      LineReader lines(a.text);
      std::string_view line;
      while (lines.next(line)) {
        split(line, tokens);
        for (std::string_view tok : tokens) {
          double x = 0;
          long long i = 0;
          const bool ok = integers ? parse_int(tok, i) : parse_double(tok, x);
          if (!ok) fail(a, fmt::format("bad value {} in {}", quote(tok), what));
          if (out.size() == n) fail(a, fmt::format("{} holds more than the {} values expected", what, n));
          if (integers) x = double(i);
          if (digits) digits->see(tok, x);
          out.push_back(x);
        }
      }
      if (n != kAnyCount && out.size() != n)
        fail(a, fmt::format("{} holds {} values, {} expected", what, out.size(), n));
      return out;
    }
    std::string raw;
    if (f == "binary") {
      Bytes b(a.text, true, name_, a.line, -1);
      payload(b, n, size_t(t.width), raw, what);
    } else if (f == "appended") {
      if (!doc_.appended) fail(a, fmt::format("{} is appended but the file has no AppendedData", what));
      long long offset = 0;
      const std::string* o = a.attribute("offset");
      if (!o || !parse_int(*o, offset) || offset < 0 || size_t(offset) > bytes_.size() - doc_.appended_start)
        fail(a, fmt::format("{} has a missing or out-of-range appended offset {}", what, quote(o ? *o : "")));
      const size_t start = doc_.appended_start + size_t(offset);
      Bytes b(bytes_.substr(start), doc_.appended_base64, name_, 0, long(start));
      payload(b, n, size_t(t.width), raw, what);
    } else {
      fail(a, fmt::format("{} has the unsupported format {} (ascii, binary, appended)", what, quote(f)));
    }
    out.resize(raw.size() / size_t(t.width));
    BinaryCursor cur(raw, 0, e_.big_endian, name_);
    for (double& x : out) x = value(cur, t, what.c_str());
    return out;
  }

 private:
  // The decoded bytes of one binary array of n values of `width` bytes behind its header: exactly n
  // values, or with kAnyCount a whole number of them.
  void payload(Bytes& b, size_t n, size_t width, std::string& raw, const std::string& what) const {
    const char* w = what.c_str();
    const bool any = n == kAnyCount;
    const size_t expected = any ? 0 : n * width;
    auto wrong_size = [&](std::uint64_t size) { return any ? size % width != 0 : size != expected; };
    auto needs = [&] {
      return any ? fmt::format("a whole number of {}-byte values", width) : fmt::format("{}", expected);
    };
    if (e_.compressor == Compressor::none) {
      const std::uint64_t size = b.header(e_, w);
      if (wrong_size(size))
        b.fail(fmt::format("{}: the header announces {} bytes, the array needs {}", what, size, needs()));
      b.read(size_t(size), raw, w);
      return;
    }
    const std::uint64_t blocks = b.header(e_, w), block_size = b.header(e_, w), last = b.header(e_, w);
    if (blocks > b.capacity() / e_.header)
      b.fail(
          fmt::format("{}: {} compressed blocks announced, the data cannot hold their sizes", what, blocks));
    if (blocks > 0 && (block_size == 0 || last > block_size))
      b.fail(
          fmt::format("{}: block size {} and last block size {} are inconsistent", what, block_size, last));
    const std::uint64_t limit = any ? max_inflated(e_.compressor, b.capacity()) : expected;
    if (blocks > 1 && block_size > limit / (blocks - 1))
      b.fail(fmt::format("{}: {} blocks of {} bytes exceed the array's {} bytes", what, blocks, block_size, limit));
    const std::uint64_t total = blocks == 0 ? 0 : (blocks - 1) * block_size + (last ? last : block_size);
    if (wrong_size(total))
      b.fail(fmt::format("{}: the compressed blocks hold {} bytes, the array needs {}", what, total, needs()));
    // Each block's size, checked before anything is allocated: the compressed bytes must be there,
    // and no larger than its compressor's ratio allows (max_inflated).
    std::vector<std::uint64_t> sizes(blocks);
    std::uint64_t compressed = 0;
    for (std::uint64_t k = 0; k < blocks; ++k) {
      sizes[k] = b.header(e_, w);
      const std::uint64_t want = k + 1 == blocks && last ? last : block_size;
      compressed += std::min<std::uint64_t>(sizes[k], b.capacity() + 1);
      if (compressed > b.capacity() || want > max_inflated(e_.compressor, sizes[k]))
        b.fail(fmt::format("{}: compressed block {} of {} bytes cannot hold {} bytes (or the data ends)",
                           what, k, sizes[k], want));
    }
    raw.resize(size_t(total));
    std::string packed;
    size_t at = 0;
    for (std::uint64_t k = 0; k < blocks; ++k) {
      const size_t want = k + 1 == blocks && last ? size_t(last) : size_t(block_size);
      packed.clear();
      b.read(size_t(sizes[k]), packed, w);
      const std::string problem = inflate_(packed, raw.data() + at, want);
      if (!problem.empty())
        b.fail(fmt::format("{}: compressed block {} is not a {} stream of {} bytes ({})", what, k,
                           compressor_name(e_.compressor), want, problem));
      at += want;
    }
  }

  std::string_view bytes_;
  const Document& doc_;
  Encoding e_;
  const std::string& name_;
  mutable Inflater inflate_;
};

// The first child of n named `name` (for DataArray: with Name="array"), or null.
const Node* child(const Document& doc, const Node& n, std::string_view name, std::string_view array = {}) {
  for (int c : n.children) {
    const Node& k = doc.nodes[size_t(c)];
    const std::string* a = k.attribute("Name");
    if (k.name == name && (array.empty() || (a && *a == array))) return &k;
  }
  return nullptr;
}

// A count attribute of n, in [0, INT_MAX / 2].
long long count(const Node& n, const char* attribute, const std::string& name) {
  const std::string* a = n.attribute(attribute);
  long long x = 0;
  if (!a || !parse_int(*a, x) || x < 0 || x > INT_MAX / 2)
    throw FileError(name, n.line, -1,
                    fmt::format("{} needs {} as a count in [0, {}], found {}", n.name, attribute, INT_MAX / 2,
                                quote(a ? *a : "(none)")));
  return x;
}

// The grid of a .vtu file, its pieces concatenated: points, and cells as point ids (offset by the
// points of the pieces before) with offsets (from 0), types, and the face streams of polyhedra; per
// vertex and per cell the line of its piece's Points or Cells element.
struct Grid {
  Eigen::MatrixX3d points;
  CoordinatePrecision precision;
  std::vector<int> connectivity, types, faces;
  std::vector<long long> offsets{0};
  std::vector<long long> face_begin, face_end;  // per cell its face stream (empty but for polyhedra)
  std::vector<long> vertex_line, cell_line;
  long cells_line = 0;  // the first piece's Cells (or Piece) line, for messages about the whole file
};

// Integer values in [lo, INT_MAX] of DataArray a (n of them; kAnyCount: as many as it holds).
std::vector<int> integers(const Arrays& arrays, const Node& a, size_t n, const std::string& what,
                          long long lo) {
  const std::vector<double> v = arrays.values(a, n, what, true);
  std::vector<int> out(v.size());
  for (size_t k = 0; k < v.size(); ++k) {
    if (!(v[k] >= double(lo) && v[k] <= double(INT_MAX)))
      arrays.fail(a, fmt::format("{} value {} (entry {}) out of range [{}, {}]", what, v[k], k, lo, INT_MAX));
    out[k] = int(v[k]);
  }
  return out;
}

// The file's Piece elements (at least one), after checking the root (VTKFile of type
// UnstructuredGrid) and reading its encoding into e.
std::vector<const Node*> pieces(const Document& doc, Encoding& e, const std::string& name) {
  const Node& root = doc.nodes[0];
  auto fail = [&](const Node& n, const std::string& reason) { throw FileError(name, n.line, -1, reason); };
  const std::string* type = root.attribute("type");
  if (root.name != "VTKFile")
    fail(root, fmt::format("expected the root element VTKFile, found {}", quote(root.name)));
  if (!type || *type != "UnstructuredGrid")
    fail(root, fmt::format("VTKFile type {} is not read (UnstructuredGrid)", quote(type ? *type : "(none)")));
  const std::string* order = root.attribute("byte_order");
  if (order && *order != "LittleEndian" && *order != "BigEndian")
    fail(root, fmt::format("byte_order {} is neither LittleEndian nor BigEndian", quote(*order)));
  e.big_endian = order && *order == "BigEndian";
  const std::string* header = root.attribute("header_type");
  if (header && *header != "UInt32" && *header != "UInt64")
    fail(root, fmt::format("header_type {} is neither UInt32 nor UInt64", quote(*header)));
  e.header = header && *header == "UInt64" ? 8 : 4;
  const std::string* compressor = root.attribute("compressor");
  const std::string c = compressor ? *compressor : "";
  e.compressor = c.empty()                        ? Compressor::none
                 : c == "vtkZLibDataCompressor" ? Compressor::zlib
                 : c == "vtkLZ4DataCompressor"  ? Compressor::lz4
                 : c == "vtkLZMADataCompressor" ? Compressor::lzma
                                                : Compressor::none;
  if (!c.empty() && e.compressor == Compressor::none)
    fail(root, fmt::format("compressor {} is not supported (vtkZLibDataCompressor, vtkLZ4DataCompressor, "
                           "vtkLZMADataCompressor)",
                           quote(c)));
  const Node* grid = child(doc, root, "UnstructuredGrid");
  if (!grid) fail(root, "no UnstructuredGrid element");
  std::vector<const Node*> out;
  for (int c : grid->children)
    if (doc.nodes[size_t(c)].name == "Piece") out.push_back(&doc.nodes[size_t(c)]);
  if (out.empty()) fail(*grid, "no Piece element");
  return out;
}

// Appends one piece to g: its points (coordinates to xyz, their digits to `digits`, `float32` set
// for Float32 points) and its cells, point ids offset by the points before it.
void read_piece(const Document& doc, const Node& piece, const Arrays& arrays, const std::string& name, Grid& g,
                std::vector<double>& xyz, DigitCounter& digits, bool& float32) {
  auto fail = [&](const Node& n, const std::string& reason) { throw FileError(name, n.line, -1, reason); };
  const long long nv = count(piece, "NumberOfPoints", name), nc = count(piece, "NumberOfCells", name);
  const long long base = (long long)(xyz.size() / 3), first = (long long)g.types.size();
  if (base + nv > INT_MAX / 2 || first + nc > INT_MAX / 2)
    fail(piece, fmt::format("the pieces hold more than {} points or cells", INT_MAX / 2));
  const Node* points = child(doc, piece, "Points");
  const Node* x = points ? child(doc, *points, "DataArray") : nullptr;
  if (nv > 0 && !x) fail(piece, "no Points DataArray");
  if (x) {
    const std::string* comps = x->attribute("NumberOfComponents");
    if (!comps || *comps != "3") fail(*x, "the Points DataArray needs NumberOfComponents=\"3\"");
    bool f32 = false;
    const std::vector<double> v = arrays.values(*x, size_t(nv) * 3, "the points", false, &digits, &f32);
    float32 = float32 || f32;
    for (size_t k = 0; k < v.size(); ++k)
      if (!std::isfinite(v[k]))
        fail(*x, fmt::format("point {} has a non-finite coordinate ({})", base + (long long)k / 3, v[k]));
    xyz.insert(xyz.end(), v.begin(), v.end());
    g.vertex_line.resize(size_t(base + nv), x->line);
  }

  const Node* cells = child(doc, piece, "Cells");
  if (g.cells_line == 0) g.cells_line = cells ? cells->line : piece.line;
  if (nc == 0) return;
  if (!cells) fail(piece, "no Cells element");
  const long line = cells->line;
  const Node* connectivity = child(doc, *cells, "DataArray", "connectivity");
  const Node* offsets = child(doc, *cells, "DataArray", "offsets");
  const Node* types = child(doc, *cells, "DataArray", "types");
  if (!connectivity || !offsets || !types)
    fail(*cells, "Cells needs the DataArrays connectivity, offsets and types");
  const std::vector<int> ends = integers(arrays, *offsets, size_t(nc), "offsets", 0);
  for (long long c = 1; c < nc; ++c)
    if (ends[size_t(c)] < ends[size_t(c - 1)])
      fail(*offsets, fmt::format("offset {} of cell {} is below the previous one", ends[size_t(c)], first + c));
  const std::vector<int> ids = integers(arrays, *connectivity, size_t(ends.back()), "connectivity", 0);
  const std::vector<int> kinds = integers(arrays, *types, size_t(nc), "types", 0);
  const long long conn_base = (long long)g.connectivity.size();
  for (long long c = 0, k = 0; c < nc; ++c) {
    for (; k < ends[size_t(c)]; ++k) {
      if (ids[size_t(k)] >= nv)
        throw FileError(name, line, -1,
                        fmt::format("cell {}: point index {} out of range [0, {})", first + c, ids[size_t(k)], nv));
      g.connectivity.push_back(ids[size_t(k)] + int(base));
    }
    g.offsets.push_back(conn_base + ends[size_t(c)]);
  }
  g.types.insert(g.types.end(), kinds.begin(), kinds.end());
  g.cell_line.resize(g.types.size(), line);
  g.face_begin.resize(g.types.size(), 0);
  g.face_end.resize(g.types.size(), 0);
  if (std::find(kinds.begin(), kinds.end(), int(kVtkPolyhedron)) == kinds.end()) return;
  const long long stream_base = (long long)g.faces.size();
  std::vector<int> stream;
  if (const Node* cell_offsets = child(doc, *cells, "DataArray", "polyhedron_offsets")) {
    // VTK 9.4: each cell's faces (its part of polyhedron_to_faces, which polyhedron_offsets ends) are
    // numbers of the faces face_offsets ends in face_connectivity; a face bounds at most two cells.
    const Node* to_faces = child(doc, *cells, "DataArray", "polyhedron_to_faces");
    const Node* face_offsets = child(doc, *cells, "DataArray", "face_offsets");
    const Node* face_points = child(doc, *cells, "DataArray", "face_connectivity");
    if (!to_faces || !face_offsets || !face_points)
      fail(*cells, "polyhedron cells need the DataArrays face_connectivity, face_offsets, polyhedron_to_faces "
                   "and polyhedron_offsets (or faces and faceoffsets)");
    const std::vector<int> cell_ends = integers(arrays, *cell_offsets, size_t(nc), "polyhedron_offsets", 0);
    for (long long c = 1; c < nc; ++c)
      if (cell_ends[size_t(c)] < cell_ends[size_t(c - 1)])
        fail(*cell_offsets, fmt::format("polyhedron_offset {} of cell {} is below the previous one",
                                        cell_ends[size_t(c)], first + c));
    const std::vector<int> cell_faces =
        integers(arrays, *to_faces, size_t(cell_ends.back()), "polyhedron_to_faces", 0);
    const std::vector<int> face_ends = integers(arrays, *face_offsets, kAnyCount, "face_offsets", 0);
    for (size_t f = 1; f < face_ends.size(); ++f)
      if (face_ends[f] < face_ends[f - 1])
        fail(*face_offsets, fmt::format("face_offset {} of face {} is below the previous one", face_ends[f], f));
    const std::vector<int> points =
        integers(arrays, *face_points, face_ends.empty() ? 0 : size_t(face_ends.back()), "face_connectivity", 0);
    std::vector<unsigned char> uses(face_ends.size(), 0);
    for (long long c = 0, begin = 0; c < nc; begin = cell_ends[size_t(c++)]) {
      if (kinds[size_t(c)] != kVtkPolyhedron) continue;
      g.face_begin[size_t(first + c)] = stream_base + (long long)stream.size();
      stream.push_back(int(cell_ends[size_t(c)] - begin));
      for (long long i = begin; i < cell_ends[size_t(c)]; ++i) {
        const int f = cell_faces[size_t(i)];
        if (size_t(f) >= face_ends.size())
          fail(*to_faces, fmt::format("polyhedron cell {}: face {} out of range [0, {})", first + c, f,
                                      face_ends.size()));
        if (++uses[size_t(f)] > 2) fail(*to_faces, fmt::format("face {} bounds more than two polyhedra", f));
        const int from = f == 0 ? 0 : face_ends[size_t(f - 1)];
        stream.push_back(face_ends[size_t(f)] - from);
        for (int k = from; k < face_ends[size_t(f)]; ++k) {
          if (points[size_t(k)] >= nv)
            throw FileError(name, line, -1,
                            fmt::format("polyhedron cell {}: point index {} out of range [0, {})", first + c,
                                        points[size_t(k)], nv));
          stream.push_back(points[size_t(k)] + int(base));
        }
      }
      g.face_end[size_t(first + c)] = stream_base + (long long)stream.size();
    }
    g.faces.insert(g.faces.end(), stream.begin(), stream.end());
    return;
  }
  const Node* faces = child(doc, *cells, "DataArray", "faces");
  const Node* faceoffsets = child(doc, *cells, "DataArray", "faceoffsets");
  if (!faces || !faceoffsets) fail(*cells, "polyhedron cells need the DataArrays faces and faceoffsets (or VTK 9.4's polyhedron_offsets...)");
  const std::vector<int> face_ends = integers(arrays, *faceoffsets, size_t(nc), "faceoffsets", -1);
  long long last = 0;
  for (long long c = 0; c < nc; ++c) {
    const int end = face_ends[size_t(c)];
    if (end < 0) continue;
    if (end < last)
      fail(*faceoffsets, fmt::format("faceoffset {} of cell {} is below the previous one", end, first + c));
    g.face_begin[size_t(first + c)] = stream_base + last, g.face_end[size_t(first + c)] = stream_base + end;
    last = end;
  }
  stream = integers(arrays, *faces, size_t(last), "faces", 0);
  // The point ids of each polyhedron's stream "n_faces, k_1, ids_1, ..." offset by the piece's first
  // point; a stream that overruns its cell is left as it is for add_vtk_volume_cell to report.
  for (long long c = 0; c < nc; ++c) {
    if (kinds[size_t(c)] != kVtkPolyhedron) continue;
    const long long b = g.face_begin[size_t(first + c)] - stream_base, e = g.face_end[size_t(first + c)] - stream_base;
    long long p = b + 1;
    for (int f = 0; b < e && f < stream[size_t(b)] && p < e; ++f) {
      const long long k = stream[size_t(p++)];
      for (long long i = 0; i < k && p < e; ++i, ++p) {
        if (stream[size_t(p)] >= nv)
          throw FileError(name, line, -1,
                          fmt::format("polyhedron cell {}: point index {} out of range [0, {})", first + c,
                                      stream[size_t(p)], nv));
        stream[size_t(p)] += int(base);
      }
    }
  }
  g.faces.insert(g.faces.end(), stream.begin(), stream.end());
}

// A .vtu file parsed once: its XML tree, encoding, pieces and the decoder of its DataArrays (which
// refer to the bytes: they must outlive it). Not copied or moved (the decoder refers to the members).
struct VtuDocument {
  VtuDocument(std::string_view bytes, const std::string& name)
      : text(strip_bom(bytes)), doc(parse_xml(text, name)), parts(pieces(doc, encoding, name)),
        arrays(text, doc, encoding, name) {}
  VtuDocument(const VtuDocument&) = delete;
  VtuDocument& operator=(const VtuDocument&) = delete;
  std::string_view text;
  Document doc;
  Encoding encoding;
  std::vector<const Node*> parts;
  Arrays arrays;
};

Grid read_grid(std::string_view bytes, const std::string& name) {
  const VtuDocument d(bytes, name);
  Grid g;
  std::vector<double> xyz;
  DigitCounter digits;
  bool float32 = false;
  for (const Node* piece : d.parts) read_piece(d.doc, *piece, d.arrays, name, g, xyz, digits, float32);
  g.points.resize(Eigen::Index(xyz.size() / 3), 3);
  for (size_t k = 0; k < xyz.size(); ++k) g.points(Eigen::Index(k / 3), Eigen::Index(k % 3)) = xyz[k];
  g.precision = float32 ? float_precision(g.points) : digits.precision(g.points);
  return g;
}

// The ids of cell c: its point ids, or a polyhedron's face stream.
std::span<const int> cell_ids(const Grid& g, size_t c) {
  if (g.types[c] == kVtkPolyhedron)
    return {g.faces.data() + g.face_begin[c], size_t(g.face_end[c] - g.face_begin[c])};
  return {g.connectivity.data() + g.offsets[c], size_t(g.offsets[c + 1] - g.offsets[c])};
}

// Cell c's type when it is one polydec knows, else a FileError.
int known_type(const Grid& g, size_t c, const std::string& name) {
  const int t = g.types[c];
  if (vtk_cell_dimension(t) < 0)
    throw FileError(
        name, g.cell_line[c], -1,
        fmt::format("unsupported cell type {} of cell {} (10 tetra, 11 voxel, 12 hexahedron, 13 "
                    "wedge, 14 pyramid, 42 polyhedron; without them 5 triangle, 7 polygon, 8 pixel, "
                    "9 quad; vertex, line and poly-line cells are skipped)",
                    t, c));
  return t;
}

// Base64 of bytes (with '=' padding).
std::string base64(std::string_view bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t bits = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) bits |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) bits |= std::uint8_t(bytes[i + 2]);
    out += kDigits[(bits >> 18) & 63];
    out += kDigits[(bits >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(bits >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[bits & 63] : '=';
  }
  return out;
}

// A name as an XML attribute value.
std::string escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '"')
      out += "&quot;";
    else if (c == '\n')
      out += "&#10;";
    else
      out += c;
  }
  return out;
}

// The block size of compressed arrays (VTK's default).
constexpr size_t kZlibBlock = 32768;

// Appends raw in vtkZLibDataCompressor's layout: UInt64 block count, block size, the last block's
// size (0 when it is full) and each block's compressed size, then the zlib streams of the blocks.
void zlib_blocks(std::string_view raw, std::string& out) {
  const size_t n = (raw.size() + kZlibBlock - 1) / kZlibBlock;
  std::string header, blocks;
  put_le(header, std::uint64_t(n));
  put_le(header, std::uint64_t(kZlibBlock));
  put_le(header, std::uint64_t(raw.size() % kZlibBlock));
  std::string packed;
  for (size_t k = 0; k < n; ++k) {
    const std::string_view block = raw.substr(k * kZlibBlock, kZlibBlock);
    uLongf size = compressBound(uLong(block.size()));
    packed.resize(size);
    const int rc = compress2(reinterpret_cast<Bytef*>(packed.data()), &size,
                             reinterpret_cast<const Bytef*>(block.data()), uLong(block.size()), Z_DEFAULT_COMPRESSION);
    if (rc != Z_OK) throw std::runtime_error(fmt::format("zlib compress2 failed ({})", zError(rc)));
    put_le(header, std::uint64_t(size));
    blocks.append(packed.data(), size);
  }
  out += header;
  out += blocks;
}

// Appends a DataArray of `values` of VTK type `type` (Float64, Int64 or UInt8) with `components`
// per tuple: inline base64 of a UInt64 byte count and the little-endian values, or ASCII; with
// `appended`, an appended array at its end, written there in zlib blocks.
template <class T>
void data_array(std::string& out, std::string_view type, std::string_view array_name, int components,
                const std::vector<T>& values, bool binary, std::string* appended) {
  out += fmt::format("        <DataArray type=\"{}\" Name=\"{}\"", type, escape(array_name));
  if (components != 1) out += fmt::format(" NumberOfComponents=\"{}\"", components);
  if (appended) {
    out += fmt::format(" format=\"appended\" offset=\"{}\"/>\n", appended->size());
    std::string raw;
    raw.reserve(values.size() * sizeof(T));
    for (T v : values) put_le(raw, v);
    zlib_blocks(raw, *appended);
    return;
  }
  out += fmt::format(" format=\"{}\">\n          ", binary ? "binary" : "ascii");
  if (binary) {
    std::string raw;
    raw.reserve(8 + values.size() * sizeof(T));
    put_le(raw, std::uint64_t(values.size() * sizeof(T)));
    for (T v : values) put_le(raw, v);
    out += base64(raw);
  } else {
    fmt::memory_buffer b;
    for (size_t k = 0; k < values.size(); ++k) {
      if (k > 0) b.push_back(k % 12 ? ' ' : '\n');
      if constexpr (std::is_floating_point_v<T>)
        fmt::format_to(std::back_inserter(b), "{:.17g}", values[k]);
      else
        fmt::format_to(std::back_inserter(b), "{}", (long long)values[k]);
    }
    out.append(b.data(), b.size());
  }
  out += "\n        </DataArray>\n";
}

// A mesh's cells as the .vtu arrays (faces and faceoffsets empty without polyhedra).
struct Cells {
  std::vector<std::int64_t> connectivity, offsets, faces, faceoffsets;
  std::vector<std::uint8_t> types;
};

// std::invalid_argument for a field without a name or with a row count other than `expected`.
void check_field(std::string_view kind, const std::string& field, long size, long expected) {
  if (field.empty()) throw std::invalid_argument(fmt::format("{} field with an empty name", kind));
  if (size != expected)
    throw std::invalid_argument(
        fmt::format("{} field '{}' has {} rows for {} elements", kind, field, size, expected));
}

// The .vtu text of points X, the cells and the fields (`compressed`: appended raw zlib blocks).
std::string vtu_text(const Eigen::MatrixX3d& X, const Cells& cells, const VtuFields& fields, bool binary,
                     bool compressed) {
  const long nv = long(X.rows()), nc = long(cells.types.size());
  for (const auto& [n, v] : fields.point_scalars) check_field("point", n, long(v.size()), nv);
  for (const auto& [n, v] : fields.point_vectors) check_field("point", n, long(v.rows()), nv);
  for (const auto& [n, v] : fields.cell_scalars) check_field("cell", n, long(v.size()), nc);
  std::string out = fmt::format(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\"{}>\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{}\" "
      "NumberOfCells=\"{}\">\n",
      compressed ? " compressor=\"vtkZLibDataCompressor\"" : "", nv, nc);
  std::string appended;
  std::string* to = compressed ? &appended : nullptr;
  auto column = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  auto rows = [](const Eigen::MatrixX3d& m) {
    std::vector<double> v;
    v.reserve(size_t(m.rows()) * 3);
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      for (int d = 0; d < 3; ++d) v.push_back(m(i, d));
    return v;
  };
  out += "      <PointData>\n";
  for (const auto& [n, v] : fields.point_scalars) data_array(out, "Float64", n, 1, column(v), binary, to);
  for (const auto& [n, v] : fields.point_vectors) data_array(out, "Float64", n, 3, rows(v), binary, to);
  out += "      </PointData>\n      <CellData>\n";
  for (const auto& [n, v] : fields.cell_scalars) data_array(out, "Float64", n, 1, column(v), binary, to);
  out += "      </CellData>\n      <Points>\n";
  data_array(out, "Float64", "Points", 3, rows(X), binary, to);
  out += "      </Points>\n      <Cells>\n";
  data_array(out, "Int64", "connectivity", 1, cells.connectivity, binary, to);
  data_array(out, "Int64", "offsets", 1, cells.offsets, binary, to);
  data_array(out, "UInt8", "types", 1, cells.types, binary, to);
  if (!cells.faces.empty()) {
    data_array(out, "Int64", "faces", 1, cells.faces, binary, to);
    data_array(out, "Int64", "faceoffsets", 1, cells.faceoffsets, binary, to);
  }
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
  if (compressed) {
    out += "  <AppendedData encoding=\"raw\">\n   _";
    out += appended;
    out += "\n  </AppendedData>\n";
  }
  out += "</VTKFile>\n";
  return out;
}

void write_file(const std::string& path, const std::string& data) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw FileError(path, 0, -1, "cannot open file for writing");
  out.write(data.data(), std::streamsize(data.size()));
  out.close();
  if (!out) throw FileError(path, 0, -1, "write failed");
}

}  // namespace
}  // namespace io_vtu_detail

namespace io_detail {

namespace {

using io_vtu_detail::Grid;

// The volume cells of a grid (its lower-dimensional cells skipped and counted).
PolyhedronRead volume_of(Grid g, const std::string& name) {
  using namespace io_vtu_detail;
  PolyhedronRead r;
  const long nv = long(g.points.rows());
  r.vertex_where = std::move(g.vertex_line);
  PolyhedronSoupBuilder builder(std::move(g.points));
  for (size_t c = 0; c < g.types.size(); ++c) {
    const int type = known_type(g, c, name);
    const bool skip = vtk_cell_dimension(type) < 3;
    const std::string problem = skip ? vtk_lower_cell_problem(type, cell_ids(g, c), nv, (long long)c)
                                     : add_vtk_volume_cell(builder, type, cell_ids(g, c), nv, (long long)c);
    if (!problem.empty()) throw FileError(name, g.cell_line[c], -1, problem);
    if (skip) {
      ++r.skipped[vtk_cell_name(type)];
      continue;
    }
    r.face_where.resize(size_t(builder.n_faces()), g.cell_line[c]);
    r.cell_where.push_back(g.cell_line[c]);
  }
  if (r.cell_where.empty())
    throw FileError(
        name, g.cells_line, -1,
        fmt::format("no volume cells (the file's cells: {}); a surface .vtu is read as a surface mesh",
                    skipped_summary(r.skipped)));
  r.soup = builder.take();
  r.soup.precision = g.precision;
  return r;
}

// The polygons of a grid without volume cells.
SoupRead surface_of(Grid g, const std::string& name) {
  using namespace io_vtu_detail;
  SoupRead r;
  r.soup.positions = std::move(g.points);
  r.soup.precision = g.precision;
  r.vertex_where = std::move(g.vertex_line);
  std::array<int, 4> pixel{};
  for (size_t c = 0; c < g.types.size(); ++c) {
    const int type = known_type(g, c, name);
    const std::span<const int> ids = cell_ids(g, c);
    if (vtk_cell_dimension(type) == 3)
      throw FileError(name, g.cell_line[c], -1,
                      fmt::format("cell {} is a {}: the file holds a volume mesh (read it as one)", c,
                                  vtk_cell_name(type)));
    const std::string problem = vtk_lower_cell_problem(type, ids, r.soup.n_vertices(), (long long)c);
    if (!problem.empty()) throw FileError(name, g.cell_line[c], -1, problem);
    if (vtk_cell_dimension(type) < 2) continue;
    if (type == 6)
      throw FileError(name, g.cell_line[c], -1, fmt::format("cell {} is a triangle strip (not read)", c));
    if (type == 8) {  // a pixel's points run x fastest, then y: 0 1 3 2 around
      pixel = {ids[0], ids[1], ids[3], ids[2]};
      r.soup.add_face(pixel);
    } else {
      r.soup.add_face(ids);
    }
    r.face_where.push_back(g.cell_line[c]);
  }
  if (r.soup.n_faces() == 0 && !g.types.empty())
    throw FileError(name, g.cells_line, -1, "no polygon cells (only vertex and line cells)");
  return r;
}

}  // namespace

PolyhedronRead read_vtu(std::string_view bytes, const std::string& name) {
  return volume_of(io_vtu_detail::read_grid(bytes, name), name);
}

SoupRead read_vtu_surface(std::string_view bytes, const std::string& name) {
  return surface_of(io_vtu_detail::read_grid(bytes, name), name);
}

SurfaceOrVolumeRead read_vtu_either(std::string_view bytes, const std::string& name) {
  Grid g = io_vtu_detail::read_grid(bytes, name);
  SurfaceOrVolumeRead r;
  r.volume = g.types.empty() ||
             std::any_of(g.types.begin(), g.types.end(), [](int t) { return vtk_cell_dimension(t) == 3; });
  if (r.volume)
    r.cells = volume_of(std::move(g), name);
  else
    r.surface = surface_of(std::move(g), name);
  return r;
}

bool vtu_holds_volume(std::string_view bytes, const std::string& name) {
  // Only the cell types are decoded; a file that cannot be judged is left to the volume reader.
  try {
    const io_vtu_detail::VtuDocument d(bytes, name);
    bool any_cell = false;
    for (const io_vtu_detail::Node* piece : d.parts) {
      const long long nc = io_vtu_detail::count(*piece, "NumberOfCells", name);
      if (nc == 0) continue;
      any_cell = true;
      const io_vtu_detail::Node* cells = io_vtu_detail::child(d.doc, *piece, "Cells");
      const io_vtu_detail::Node* types = cells ? io_vtu_detail::child(d.doc, *cells, "DataArray", "types") : nullptr;
      if (!types) return true;
      const std::vector<int> kinds = io_vtu_detail::integers(d.arrays, *types, size_t(nc), "types", 0);
      if (std::any_of(kinds.begin(), kinds.end(), [](int t) { return vtk_cell_dimension(t) == 3; })) return true;
    }
    return !any_cell;
  } catch (const FileError&) {
    return true;
  }
}

}  // namespace io_detail

using namespace io_vtu_detail;

std::string write_vtu_to_string(const VolumeMesh& mesh, const VtuFields& fields, bool binary, bool compressed) {
  std::vector<int> entries, types;
  io_detail::vtk_cells(mesh, "(vtu)", entries, types);
  Cells cells;
  std::vector<std::int64_t> seen;
  for (size_t c = 0, k = 0; c < types.size(); ++c) {
    const size_t n = size_t(entries[k]);
    const std::span<const int> ids(entries.data() + k + 1, n);
    k += n + 1;
    cells.types.push_back(std::uint8_t(types[c]));
    if (types[c] != kVtkPolyhedron) {
      cells.connectivity.insert(cells.connectivity.end(), ids.begin(), ids.end());
      cells.faceoffsets.push_back(-1);
    } else {
      // The face stream, and the cell's points once each in their order of appearance.
      cells.faces.insert(cells.faces.end(), ids.begin(), ids.end());
      cells.faceoffsets.push_back(std::int64_t(cells.faces.size()));
      seen.clear();
      for (size_t p = 1; p < n; p += size_t(ids[p]) + 1)
        for (int i = 1; i <= ids[p]; ++i)
          if (std::find(seen.begin(), seen.end(), ids[p + size_t(i)]) == seen.end())
            seen.push_back(ids[p + size_t(i)]);
      cells.connectivity.insert(cells.connectivity.end(), seen.begin(), seen.end());
    }
    cells.offsets.push_back(std::int64_t(cells.connectivity.size()));
  }
  if (cells.faces.empty()) cells.faceoffsets.clear();
  return vtu_text(mesh.positions(), cells, fields, binary, compressed);
}

std::string write_vtu_to_string(const Mesh& mesh, const VtuFields& fields, bool binary, bool compressed) {
  Cells cells;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    cells.connectivity.insert(cells.connectivity.end(), face.begin(), face.end());
    cells.offsets.push_back(std::int64_t(cells.connectivity.size()));
    cells.types.push_back(face.size() == 3 ? 5 : face.size() == 4 ? 9 : 7);
  }
  return vtu_text(mesh.positions(), cells, fields, binary, compressed);
}

void write_vtu(const std::string& path, const VolumeMesh& mesh, const VtuFields& fields, bool binary,
               bool compressed) {
  write_file(path, write_vtu_to_string(mesh, fields, binary, compressed));
}

void write_vtu(const std::string& path, const Mesh& mesh, const VtuFields& fields, bool binary, bool compressed) {
  write_file(path, write_vtu_to_string(mesh, fields, binary, compressed));
}

VtuFields read_vtu_fields_from_memory(std::string_view bytes, const std::string& name) {
  const VtuDocument d(bytes, name);
  const Document& doc = d.doc;
  const std::vector<const Node*>& parts = d.parts;
  const Arrays& arrays = d.arrays;
  // Per section and array name: its components and its values, piece after piece, and in how many
  // pieces it was found (an array missing from a piece is dropped).
  struct Field {
    int components = 0, found = 0, piece = -1;
    std::vector<double> values;
  };
  std::map<std::string, Field> point_fields, cell_fields;
  for (int p = 0; p < int(parts.size()); ++p) {
    const Node* piece = parts[size_t(p)];
    for (const char* section : {"PointData", "CellData"}) {
      const bool point = section[0] == 'P';
      auto& out = point ? point_fields : cell_fields;
      const long long n = count(*piece, point ? "NumberOfPoints" : "NumberOfCells", name);
      const Node* data = child(doc, *piece, section);
      if (!data) continue;
      for (int c : data->children) {
        const Node& a = doc.nodes[size_t(c)];
        const std::string* array_name = a.attribute("Name");
        const std::string* comps = a.attribute("NumberOfComponents");
        const int k = !comps ? 1 : *comps == "1" ? 1 : *comps == "3" ? 3 : 0;
        if (a.name != "DataArray" || !array_name || k == 0 || (!point && k == 3)) continue;
        Field& f = out[*array_name];
        if (f.found > 0 && f.components != k)
          arrays.fail(a, fmt::format("array {} has {} components here and {} in an earlier piece", quote(*array_name),
                                     k, f.components));
        if (f.piece == p) continue;  // a second array of that name in the piece: the first is read
        f.piece = p, f.components = k, ++f.found;
        const std::vector<double> v = arrays.values(a, size_t(n) * size_t(k), "array " + quote(*array_name), false);
        f.values.insert(f.values.end(), v.begin(), v.end());
      }
    }
  }
  VtuFields fields;
  for (auto& [array_name, f] : point_fields) {
    if (f.found != int(parts.size())) continue;
    const Eigen::Index n = Eigen::Index(f.values.size()) / f.components;
    if (f.components == 3) {
      Eigen::MatrixX3d m(n, 3);
      for (Eigen::Index i = 0; i < n * 3; ++i) m(i / 3, i % 3) = f.values[size_t(i)];
      fields.point_vectors[array_name] = m;
    } else {
      fields.point_scalars[array_name] = Eigen::Map<const Eigen::VectorXd>(f.values.data(), n);
    }
  }
  for (auto& [array_name, f] : cell_fields)
    if (f.found == int(parts.size()))
      fields.cell_scalars[array_name] =
          Eigen::Map<const Eigen::VectorXd>(f.values.data(), Eigen::Index(f.values.size()));
  return fields;
}

VtuFields read_vtu_fields(const std::string& path) {
  return read_vtu_fields_from_memory(io_detail::slurp(path), path);
}

}  // namespace polydec
