// dec/io/msh.cpp — gmsh .msh files, versions 2.2 and 4.1, ASCII and binary (data size 8; the
// binary endianness marker must read 1, i.e. the file was written in this machine's byte order).
// Linear elements are read: triangles (2) and quadrangles (3) as a surface's faces; tetrahedra
// (4), hexahedra (5), prisms (6) and pyramids (7) as a volume's cells, in gmsh's node order (a
// prism's first triangle faces its second: VTK's wedge reversed). A file with 3-D elements is a
// volume, else a surface; the elements of lower dimension (points 15, lines 1, boundary faces) are
// skipped and counted. Higher-order element types are refused. Node tags may be sparse and in any
// order; vertices keep the file's node order. Physical groups ($PhysicalNames; in 4.1 the
// $Entities' physical tags) become named vertex and element sets (dec/io/mesh_groups.h). Other
// sections ($NodeData, $Periodic, ...) are skipped to their $End line.
#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cstdint>
#include <map>
#include <optional>
#include <set>

#include "polydec/dec/detail/msh_io.h"
#include "polydec/dec/mesh/polyhedron_builder.h"
#include "polydec/dec/mesh/volume_cells.h"

namespace polydec {
namespace io_msh_detail {
namespace {

using namespace io_detail;

constexpr const char* kReadTypes =
    "15 point, 1 line, 2 triangle, 3 quadrangle, 4 tetrahedron, 5 hexahedron, 6 prism, 7 pyramid";

// Nodes of the linear element types read (0 for any other type).
int type_nodes(long long t) {
  switch (t) {
    case 15:
      return 1;
    case 1:
      return 2;
    case 2:
      return 3;
    case 3:
    case 4:
      return 4;
    case 5:
      return 8;
    case 6:
      return 6;
    case 7:
      return 5;
    default:
      return 0;
  }
}
int type_dimension(int t) { return t == 15 ? 0 : t == 1 ? 1 : t <= 3 ? 2 : 3; }
// The plural name of a skipped kind (in MeshGroups::skipped).
const char* kind_name(int t) {
  static const char* names[] = {"",           "lines",      "triangles", "quadrangles", "tetrahedra",
                                "hexahedra",  "prisms",     "pyramids"};
  return t == 15 ? "points" : names[t];
}
// The name of a type that is not read, for the message refusing it.
std::string refused_type(long long t) {
  static const std::map<long long, const char*> names{
      {8, "3-node second-order line"},          {9, "6-node second-order triangle"},
      {10, "9-node second-order quadrangle"},   {11, "10-node second-order tetrahedron"},
      {12, "27-node second-order hexahedron"},  {13, "18-node second-order prism"},
      {14, "14-node second-order pyramid"},     {16, "8-node second-order quadrangle"},
      {17, "20-node second-order hexahedron"},  {18, "15-node second-order prism"},
      {19, "13-node second-order pyramid"},     {20, "9-node third-order incomplete triangle"},
      {21, "10-node third-order triangle"},     {26, "4-node third-order line"},
      {29, "20-node third-order tetrahedron"},  {92, "64-node third-order hexahedron"}};
  const auto it = names.find(t);
  return it != names.end() ? fmt::format("element type {} ({})", t, it->second)
                           : fmt::format("element type {}", t);
}

// Everything parsed from the file before it becomes a surface or a volume.
struct Parsed {
  Eigen::MatrixX3d positions;
  std::vector<long> vertex_where;
  CoordinatePrecision precision;
  bool byte_offsets = false;
  // Elements: type, group set, where, vertices (offsets + indices).
  std::vector<unsigned char> type;
  std::vector<int> group_set;
  std::vector<long> where;
  std::vector<int> offsets{0}, vertices;
  // Distinct lists of physical groups (dimension, tag); set 0 is empty.
  std::vector<std::vector<std::pair<int, int>>> group_sets{{}};
  std::map<std::pair<int, int>, std::string> names;
};

// Fields of a section: whitespace tokens in ASCII files, native-endian int32 / uint64 / double
// in binary ones (whose payload starts after the section's header line).
class Fields {
 public:
  Fields(VolumeTokens& in, std::string_view text, const std::string& name, bool binary)
      : in_(in), text_(text), name_(name), binary_(binary) {}

  bool binary() const { return binary_; }
  // Bytes left after the fields read.
  size_t remaining() const { return binary_ ? cur_->remaining() : in_.remaining(); }
  void begin(const char* what) {
    if (!binary_) return;
    in_.end_line(what);
    cur_.emplace(text_, in_.position(), std::endian::native == std::endian::big, name_);
  }
  void end() {
    if (binary_) in_.advance(cur_->position() - in_.position());
    cur_.reset();
  }
  // Where the field last read starts: its line, or its byte offset.
  long last() const { return binary_ ? last_ : in_.line(); }
  [[noreturn]] void fail(long at, const std::string& reason) const { in_.fail(at, reason); }

  long long integer(const char* what) {
    if (!binary_) return in_.integer(what);
    last_ = long(cur_->position());
    return cur_->read<std::int32_t>(what);
  }
  // A size_t count in 4.1 (an integer token in ASCII) of records needing at least `text_bytes`
  // (ASCII) or `binary_bytes` (binary) each; at most INT_MAX / 2 and what the file can hold.
  long long count(const char* what, long long text_bytes, long long binary_bytes) {
    if (!binary_) return in_.count(what, text_bytes);
    last_ = long(cur_->position());
    const std::uint64_t n = cur_->read<std::uint64_t>(what);
    if (n > std::uint64_t(INT_MAX / 2)) fail(last_, fmt::format("{} {} is too large (at most {})", what, n, INT_MAX / 2));
    if ((long long)n * binary_bytes > (long long)cur_->remaining())
      fail(last_, fmt::format("{} {} needs at least {} bytes but only {} follow", what, n,
                              (long long)n * binary_bytes, cur_->remaining()));
    return (long long)n;
  }
  // A tag: size_t in 4.1 binary files (int32 with `int32`), an integer token in ASCII.
  long long tag(const char* what, bool int32 = false) {
    if (!binary_) return in_.integer(what);
    last_ = long(cur_->position());
    if (int32) return cur_->read<std::int32_t>(what);
    const std::uint64_t t = cur_->read<std::uint64_t>(what);
    return t > std::uint64_t(LLONG_MAX) ? -1 : (long long)t;
  }
  double real(const char* what, DigitCounter* digits = nullptr) {
    if (binary_) {
      last_ = long(cur_->position());
      return cur_->read<double>(what);
    }
    const std::string_view t = in_.expect(what);
    double x;
    if (!parse_double(t, x)) fail(in_.line(), fmt::format("bad {} {}", what, quote(t)));
    if (digits) digits->see(t, x);
    return x;
  }

 private:
  VolumeTokens& in_;
  std::string_view text_;
  const std::string& name_;
  bool binary_;
  std::optional<BinaryCursor> cur_;
  long last_ = 0;
};

class Reader {
 public:
  Reader(std::string_view text, const std::string& name) : text_(text), name_(name), in_(text, name) {}

  Parsed parse() {
    std::string_view t;
    if (!in_.next(t)) in_.fail(0, "empty file (no $MeshFormat)");
    if (t != "$MeshFormat") in_.fail(in_.line(), fmt::format("expected '$MeshFormat', found {}", quote(t)));
    const std::string_view version = in_.expect("the format version");
    if (version == "2" || version == "2.0" || version == "2.1" || version == "2.2")
      v4_ = false;
    else if (version == "4.1")
      v4_ = true;
    else
      in_.fail(in_.line(), fmt::format("gmsh format version {} is not supported (2.2 and 4.1 are read)", quote(version)));
    const long long file_type = in_.integer("file type");
    if (file_type != 0 && file_type != 1) in_.fail(in_.line(), fmt::format("bad file type {} (0 ASCII, 1 binary)", file_type));
    const long long data_size = in_.integer("data size");
    if (data_size != 8)
      in_.fail(in_.line(), fmt::format("data size {} is not supported (8: double coordinates, 64-bit sizes)", data_size));
    fields_.emplace(in_, text_, name_, file_type == 1);
    if (file_type == 1) {
      in_.use_byte_offsets();
      p_.byte_offsets = true;
      fields_->begin("the endianness marker");
      const long at = long(in_.position());
      const long long one = fields_->integer("the endianness marker");
      if (one == 0x01000000)
        in_.fail(at, "the endianness marker reads 16777216 instead of 1: the file was written on a machine of the "
                     "other byte order (not supported)");
      if (one != 1) in_.fail(at, fmt::format("bad endianness marker {} (expected 1)", one));
      fields_->end();
    }
    in_.keyword("$EndMeshFormat");
    bool nodes = false, elements = false;
    while (in_.next(t)) {
      if (t.empty() || t[0] != '$')
        in_.fail(in_.where(), fmt::format("expected a section such as $Nodes or $Elements, found {}", quote(t)));
      const long at = in_.where();
      if (t == "$PhysicalNames") {
        physical_names();
      } else if (t == "$Entities" && v4_) {
        if (nodes) in_.fail(at, "$Entities after $Nodes");
        entities();
      } else if (t == "$Nodes") {
        if (nodes) in_.fail(at, "a second $Nodes section");
        v4_ ? nodes_v4() : nodes_v2();
        nodes = true;
      } else if (t == "$Elements") {
        if (!nodes) in_.fail(at, "$Elements before $Nodes");
        if (elements) in_.fail(at, "a second $Elements section");
        v4_ ? elements_v4() : elements_v2();
        elements = true;
      } else {
        skip_section(t);
      }
    }
    if (!nodes) in_.fail(0, "no $Nodes section");
    if (!elements) in_.fail(0, "no $Elements section");
    return std::move(p_);
  }

 private:
  std::string_view text_;
  const std::string& name_;
  VolumeTokens in_;
  std::optional<Fields> fields_;
  bool v4_ = false;
  Parsed p_;
  std::vector<std::pair<long long, int>> tags_;  // node tag -> vertex, sorted by tag
  std::map<std::pair<int, int>, int> entity_set_;  // 4.1 (dimension, entity tag) -> group set
  std::map<std::vector<std::pair<int, int>>, int> set_index_;  // group set -> its index

  // Skips an unknown section to its "$End..." line.
  void skip_section(std::string_view t) {
    const std::string end = "$End" + std::string(t.substr(1));
    const long at = in_.where();
    in_.skip_line();
    while (in_.remaining() > 0) {
      if (in_.next_is(end)) {
        in_.keyword(end.c_str());
        return;
      }
      in_.skip_line();
    }
    in_.fail(at, fmt::format("section {} has no {} line", quote(t), end));
  }

  void physical_names() {
    const long long n = in_.count("physical name count", 6);
    for (long long k = 0; k < n; ++k) {
      const long long dim = in_.integer("physical group dimension");
      if (dim < 0 || dim > 3) in_.fail(in_.where(), fmt::format("bad physical group dimension {}", dim));
      const long long tag = in_.integer("physical group tag");
      if (tag < INT_MIN || tag > INT_MAX) in_.fail(in_.where(), fmt::format("physical tag {} out of range", tag));
      std::string_view s = in_.rest_of_line();
      while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
      while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
      if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
      if (s.empty()) in_.fail(in_.here(), "empty physical name");
      p_.names[{int(dim), int(tag)}] = std::string(s);
    }
    in_.keyword("$EndPhysicalNames");
  }

  // The group set of a list of physical groups (interned).
  int intern(std::vector<std::pair<int, int>> set) {
    if (set.empty()) return 0;
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    const auto [it, added] = set_index_.emplace(set, int(p_.group_sets.size()));
    if (added) p_.group_sets.push_back(std::move(set));
    return it->second;
  }

  int checked_int(long long x, const char* what) {
    if (x < INT_MIN || x > INT_MAX) fields_->fail(fields_->last(), fmt::format("{} {} out of range", what, x));
    return int(x);
  }

  // 4.1: points (tag, x y z), curves, surfaces, volumes (tag, bounding box, ..., bounding entities).
  void entities() {
    Fields& f = *fields_;
    f.begin("the entity data");
    long long counts[4];
    for (int d = 0; d < 4; ++d) counts[d] = f.count("entity count", 4, d == 0 ? 36 : 68);
    for (int d = 0; d < 4; ++d)
      for (long long e = 0; e < counts[d]; ++e) {
        const int tag = checked_int(f.integer("entity tag"), "entity tag");
        for (int k = 0; k < (d == 0 ? 3 : 6); ++k) f.real("entity coordinate");
        const long long n_physical = f.count("physical tag count", 2, 4);
        std::vector<std::pair<int, int>> set;
        for (long long k = 0; k < n_physical; ++k) set.push_back({d, checked_int(f.integer("physical tag"), "physical tag")});
        if (d > 0) {
          const long long n_bounding = f.count("bounding entity count", 2, 4);
          for (long long k = 0; k < n_bounding; ++k) f.integer("bounding entity tag");
        }
        entity_set_[{d, tag}] = intern(std::move(set));
      }
    f.end();
    in_.keyword("$EndEntities");
  }

  // One node: its tag (already read), where, coordinates.
  void add_node(long long tag, long where, int v, const double* x) {
    if (tag < 1) fields_->fail(where, fmt::format("bad node tag {} (tags are positive)", tag));
    tags_.push_back({tag, v});
    p_.vertex_where[v] = where;
    for (int c = 0; c < 3; ++c) p_.positions(v, c) = x[c];
  }

  // Sorts the tags; a tag given twice is an error at its second node.
  void finish_nodes() {
    std::sort(tags_.begin(), tags_.end());
    for (size_t k = 1; k < tags_.size(); ++k)
      if (tags_[k].first == tags_[k - 1].first) {
        const int a = std::min(tags_[k].second, tags_[k - 1].second), b = std::max(tags_[k].second, tags_[k - 1].second);
        fields_->fail(p_.vertex_where[b], fmt::format("node tag {} is defined twice (first at {} {})", tags_[k].first,
                                                      p_.byte_offsets ? "byte" : "line", p_.vertex_where[a]));
      }
  }

  void nodes_v2() {
    Fields& f = *fields_;
    const long long n = in_.count("node count", f.binary() ? 32 : 8);
    p_.positions.resize(n, 3);
    p_.vertex_where.resize(n);
    DigitCounter digits;
    f.begin("the node data");
    for (long long v = 0; v < n; ++v) {
      const long long tag = f.tag("node tag", true);
      const long where = f.last();
      double x[3];
      for (double& c : x) c = f.real("node coordinate", &digits);
      add_node(tag, where, int(v), x);
    }
    f.end();
    if (!f.binary()) p_.precision = digits.precision(p_.positions);
    finish_nodes();
    in_.keyword("$EndNodes");
  }

  void nodes_v4() {
    Fields& f = *fields_;
    f.begin("the node data");
    const long long blocks = f.count("node block count", 8, 20);
    const long long n = f.count("node count", 8, 32);
    f.tag("minimum node tag");
    f.tag("maximum node tag");
    p_.positions.resize(n, 3);
    p_.vertex_where.resize(n);
    DigitCounter digits;
    long long v = 0;
    std::vector<std::pair<long long, long>> block_tags;
    for (long long b = 0; b < blocks; ++b) {
      const long long dim = f.integer("entity dimension");
      if (dim < 0 || dim > 3) f.fail(f.last(), fmt::format("bad entity dimension {}", dim));
      f.integer("entity tag");
      const long long parametric = f.integer("parametric flag");
      if (parametric != 0 && parametric != 1) f.fail(f.last(), fmt::format("bad parametric flag {}", parametric));
      const int extra = parametric ? int(dim) : 0;
      const long long m = f.count("node count of the block", 8, 8 * (4 + extra));
      if (m > n - v) f.fail(f.last(), fmt::format("the node blocks hold more than the {} nodes announced", n));
      block_tags.clear();
      for (long long k = 0; k < m; ++k) {
        const long long tag = f.tag("node tag");
        block_tags.push_back({tag, f.last()});
      }
      for (long long k = 0; k < m; ++k) {
        double x[3];
        for (int c = 0; c < 3; ++c) x[c] = f.real("node coordinate", &digits);
        for (int c = 0; c < extra; ++c) f.real("parametric coordinate");
        add_node(block_tags[k].first, f.binary() ? block_tags[k].second : f.last(), int(v++), x);
      }
    }
    if (v != n) f.fail(f.last(), fmt::format("the node blocks hold {} nodes, the header announces {}", v, n));
    f.end();
    if (!f.binary()) p_.precision = digits.precision(p_.positions);
    finish_nodes();
    in_.keyword("$EndNodes");
  }

  // The vertex of node tag `tag` of an element at `where`.
  int vertex(long long tag, long where) {
    const auto it = std::lower_bound(tags_.begin(), tags_.end(), std::pair<long long, int>{tag, INT_MIN});
    if (it == tags_.end() || it->first != tag)
      fields_->fail(where, fmt::format("the element refers to node tag {}, which $Nodes does not define", tag));
    return it->second;
  }

  void check_type(long long type, long where) {
    if (type_nodes(type) == 0)
      fields_->fail(where, fmt::format("{} is not supported: polydec reads the linear elements ({})", refused_type(type),
                                       kReadTypes));
  }

  void add_element(int type, int set, long where) {
    p_.type.push_back((unsigned char)type);
    p_.group_set.push_back(set);
    p_.where.push_back(where);
    p_.offsets.push_back(int(p_.vertices.size()));
  }

  void elements_v2() {
    Fields& f = *fields_;
    const long long n = in_.count("element count", 8);
    f.begin("the element data");
    long long e = 0;
    while (e < n) {
      long long type = 0, follow = 1, n_tags = 0;
      if (f.binary()) {  // a block header: type, elements following, tags per element
        type = f.integer("element type");
        check_type(type, f.last());
        follow = f.integer("element count of the block");
        if (follow < 1 || follow > n - e) f.fail(f.last(), fmt::format("bad element count {} of a block", follow));
        n_tags = f.integer("tag count");
        if (n_tags < 0 || n_tags > 64) f.fail(f.last(), fmt::format("bad tag count {}", n_tags));
        if (follow * (1 + n_tags + type_nodes(type)) * 4 > (long long)f.remaining())
          f.fail(f.last(), fmt::format("a block of {} elements does not fit in the file", follow));
      }
      for (long long k = 0; k < follow; ++k, ++e) {
        f.integer("element number");
        const long where = f.last();
        if (!f.binary()) {
          type = f.integer("element type");
          check_type(type, where);
          n_tags = f.integer("tag count");
          if (n_tags < 0 || n_tags > 64) f.fail(where, fmt::format("bad tag count {}", n_tags));
        }
        std::vector<std::pair<int, int>> set;
        for (long long j = 0; j < n_tags; ++j) {
          const long long t = f.integer("element tag");
          if (j == 0 && t != 0) set.push_back({type_dimension(int(type)), checked_int(t, "physical tag")});
        }
        for (int j = 0; j < type_nodes(type); ++j) p_.vertices.push_back(vertex(f.tag("node tag", true), where));
        add_element(int(type), intern(std::move(set)), where);
      }
    }
    f.end();
    in_.keyword("$EndElements");
  }

  void elements_v4() {
    Fields& f = *fields_;
    f.begin("the element data");
    const long long blocks = f.count("element block count", 8, 20);
    const long long n = f.count("element count", 4, 16);
    f.tag("minimum element tag");
    f.tag("maximum element tag");
    long long e = 0;
    for (long long b = 0; b < blocks; ++b) {
      const long long dim = f.integer("entity dimension");
      const long where_block = f.last();
      const long long entity = f.integer("entity tag");
      const long long type = f.integer("element type");
      check_type(type, f.last());
      if (dim != type_dimension(int(type)))
        f.fail(where_block, fmt::format("a block of entity dimension {} holds elements of type {} (dimension {})", dim,
                                        type, type_dimension(int(type))));
      const int nodes = type_nodes(type);
      const long long m = f.count("element count of the block", 2 * (nodes + 1), 8 * (nodes + 1));
      if (m > n - e) f.fail(f.last(), fmt::format("the element blocks hold more than the {} elements announced", n));
      const auto it = entity_set_.find({int(dim), int(std::clamp<long long>(entity, INT_MIN, INT_MAX))});
      const int set = it == entity_set_.end() ? 0 : it->second;
      for (long long k = 0; k < m; ++k, ++e) {
        f.tag("element tag");
        const long where = f.last();
        for (int j = 0; j < nodes; ++j) p_.vertices.push_back(vertex(f.tag("node tag"), where));
        add_element(int(type), set, where);
      }
    }
    if (e != n) f.fail(f.last(), fmt::format("the element blocks hold {} elements, the header announces {}", e, n));
    f.end();
    in_.keyword("$EndElements");
  }
};

int top_dimension(const Parsed& p) {
  int top = -1;
  for (unsigned char t : p.type) top = std::max(top, type_dimension(t));
  return top;
}

// The groups and the skipped elements, with the mesh of dimension `top` (its elements numbered in
// file order).
MeshGroups groups_of(const Parsed& p, int top) {
  MeshGroups g;
  std::map<std::string, std::set<int>> vertices;
  int index = 0;
  for (size_t e = 0; e < p.type.size(); ++e) {
    const int dim = type_dimension(p.type[e]);
    if (dim < top) ++g.skipped[kind_name(p.type[e])];
    for (const auto& key : p.group_sets[p.group_set[e]]) {
      const auto it = p.names.find(key);
      const std::string name = it != p.names.end() ? it->second : std::to_string(key.second);
      vertices[name].insert(p.vertices.begin() + p.offsets[e], p.vertices.begin() + p.offsets[e + 1]);
      if (dim == top) g.elements[name].push_back(index);
    }
    index += dim == top;
  }
  for (auto& [name, set] : vertices) g.vertices[name].assign(set.begin(), set.end());
  for (auto& [name, list] : g.elements) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return g;
}

// "3 tetrahedra, 2 prisms": the elements of dimension `dim`.
std::string census(const Parsed& p, int dim) {
  std::map<int, long> counts;
  for (unsigned char t : p.type)
    if (type_dimension(t) == dim) ++counts[t];
  std::string s;
  for (const auto& [t, c] : counts) s += fmt::format("{}{} {}", s.empty() ? "" : ", ", c, kind_name(t));
  return s;
}

Parsed parse(std::string_view bytes, const std::string& name) { return Reader(strip_bom(bytes), name).parse(); }

// The vertices of a cell in gmsh's order -> VTK's (the prism's triangles reversed).
int vtk_type(int gmsh_type) {
  return gmsh_type == 4 ? kVtkTetra : gmsh_type == 5 ? kVtkHexahedron : gmsh_type == 6 ? kVtkWedge : kVtkPyramid;
}

}  // namespace
}  // namespace io_msh_detail

namespace io_detail {

using namespace io_msh_detail;

bool looks_like_msh(std::string_view bytes) {
  std::string_view t = strip_bom(bytes);
  while (!t.empty() && (is_space(t.front()) || t.front() == '\n')) t.remove_prefix(1);
  return t.rfind("$MeshFormat", 0) == 0;
}

bool msh_holds_volume(std::string_view bytes, const std::string& name) {
  try {
    return top_dimension(parse(bytes, name)) == 3;
  } catch (const FileError&) {
    return false;
  }
}

MeshGroups read_msh_groups(std::string_view bytes, const std::string& name) {
  const Parsed p = parse(bytes, name);
  return groups_of(p, top_dimension(p));
}

namespace {

// The surface of a parsed file (its triangles and quadrangles).
SoupRead surface_of(Parsed p, const std::string& name, MeshGroups* groups) {
  const int top = top_dimension(p);
  if (top == 3)
    throw FileError(name, 0, -1, fmt::format("the file holds 3-D elements ({}): read it as a volume mesh (--volume)",
                                             census(p, 3)));
  if (top < 2) throw FileError(name, 0, -1, "the file holds no triangles or quadrangles (gmsh types 2, 3)");
  if (groups) *groups = groups_of(p, top);
  SoupRead r;
  r.where_is_byte = p.byte_offsets;
  r.vertex_where = std::move(p.vertex_where);
  r.soup.positions = std::move(p.positions);
  r.soup.precision = p.precision;
  for (size_t e = 0; e < p.type.size(); ++e) {
    if (type_dimension(p.type[e]) != 2) continue;
    r.soup.add_face({p.vertices.data() + p.offsets[e], size_t(p.offsets[e + 1] - p.offsets[e])});
    r.face_where.push_back(p.where[e]);
  }
  return r;
}

// The volume of a parsed file (its tetrahedra, hexahedra, prisms and pyramids).
PolyhedronRead volume_of(Parsed p, const std::string& name, MeshGroups* groups) {
  const int top = top_dimension(p);
  if (top < 3)
    throw FileError(name, 0, -1,
                    "the file holds no 3-D elements (gmsh types 4 tetrahedron, 5 hexahedron, 6 prism, 7 pyramid): "
                    "read it as a surface mesh");
  if (groups) *groups = groups_of(p, top);
  PolyhedronRead r;
  r.where_is_byte_offset = p.byte_offsets;
  r.vertex_where = std::move(p.vertex_where);
  const CoordinatePrecision precision = p.precision;
  PolyhedronSoupBuilder builder(std::move(p.positions));
  int cell[8];
  for (size_t e = 0; e < p.type.size(); ++e) {
    if (type_dimension(p.type[e]) != 3) continue;
    const int* v = p.vertices.data() + p.offsets[e];
    const int n = p.offsets[e + 1] - p.offsets[e];
    for (int k = 0; k < n; ++k) cell[k] = p.type[e] == 6 ? v[kPrismToVtk[k]] : v[k];
    if (!builder.add_vtk_cell(vtk_type(p.type[e]), {cell, size_t(n)})) {
      const long at = p.where[e];
      const std::string reason = fmt::format(
          "a face of this element has the vertices of face {} in another cyclic order", builder.last_face());
      if (p.byte_offsets) throw FileError(name, 0, at, reason);
      throw FileError(name, at, -1, reason);
    }
    while (int(r.face_where.size()) < builder.n_faces()) r.face_where.push_back(p.where[e]);
    r.cell_where.push_back(p.where[e]);
  }
  r.soup = builder.take();
  r.soup.precision = precision;
  return r;
}

}  // namespace

SoupRead read_msh_surface(std::string_view bytes, const std::string& name, MeshGroups* groups) {
  return surface_of(parse(bytes, name), name, groups);
}

PolyhedronRead read_msh_volume(std::string_view bytes, const std::string& name, MeshGroups* groups) {
  return volume_of(parse(bytes, name), name, groups);
}

SurfaceOrVolumeRead read_msh_either(std::string_view bytes, const std::string& name, MeshGroups* groups) {
  Parsed p = parse(bytes, name);
  SurfaceOrVolumeRead r;
  r.volume = top_dimension(p) == 3;
  if (r.volume)
    r.cells = volume_of(std::move(p), name, groups);
  else
    r.surface = surface_of(std::move(p), name, groups);
  return r;
}

namespace {

// The $MeshFormat header, one entity of dimension `dim` holding every element (its bounding box),
// and the nodes.
void write_header(fmt::memory_buffer& b, const Eigen::MatrixX3d& X, int dim) {
  auto out = std::back_inserter(b);
  fmt::format_to(out, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n");
  const Eigen::RowVector3d lo = X.rows() ? Eigen::RowVector3d(X.colwise().minCoeff()) : Eigen::RowVector3d::Zero();
  const Eigen::RowVector3d hi = X.rows() ? Eigen::RowVector3d(X.colwise().maxCoeff()) : Eigen::RowVector3d::Zero();
  fmt::format_to(out, "0 0 {} {}\n1 {} {} {} {} {} {} 0 0\n$EndEntities\n", int(dim == 2), int(dim == 3), num(lo[0]),
                 num(lo[1]), num(lo[2]), num(hi[0]), num(hi[1]), num(hi[2]));
  const long n = X.rows();
  fmt::format_to(out, "$Nodes\n1 {} 1 {}\n{} 1 0 {}\n", n, n, dim, n);
  for (long v = 0; v < n; ++v) fmt::format_to(out, "{}\n", v + 1);
  for (long v = 0; v < n; ++v) fmt::format_to(out, "{} {} {}\n", num(X(v, 0)), num(X(v, 1)), num(X(v, 2)));
  fmt::format_to(out, "$EndNodes\n");
}

// The elements in their order, one block per run of elements of one gmsh type (so that the file
// reads back with the same numbering): types[e] and the 0-based vertices of element e.
void write_elements(fmt::memory_buffer& b, int dim, const std::vector<int>& types,
                    const std::vector<std::vector<int>>& elements) {
  auto out = std::back_inserter(b);
  size_t blocks = 0;
  for (size_t e = 0; e < types.size(); ++e) blocks += e == 0 || types[e] != types[e - 1];
  fmt::format_to(out, "$Elements\n{} {} 1 {}\n", blocks, types.size(), types.size());
  for (size_t e = 0; e < types.size(); ++e) {
    if (e == 0 || types[e] != types[e - 1]) {
      size_t run = 1;
      while (e + run < types.size() && types[e + run] == types[e]) ++run;
      fmt::format_to(out, "{} 1 {} {}\n", dim, types[e], run);
    }
    fmt::format_to(out, "{}", e + 1);
    for (int v : elements[e]) fmt::format_to(out, " {}", v + 1);
    fmt::format_to(out, "\n");
  }
  fmt::format_to(out, "$EndElements\n");
}

}  // namespace

std::string write_msh(const Mesh& mesh, const std::string& name) {
  std::vector<int> types;
  std::vector<std::vector<int>> faces;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto vs = mesh.face(f);
    if (vs.size() != 3 && vs.size() != 4)
      throw FileError(name, 0, -1,
                      fmt::format("face {} has {} vertices: gmsh .msh holds triangles and quadrangles only (use .obj, "
                                  ".off or .ply)",
                                  f, vs.size()));
    types.push_back(vs.size() == 3 ? 2 : 3);
    faces.emplace_back(vs.begin(), vs.end());
  }
  fmt::memory_buffer b;
  write_header(b, mesh.positions(), 2);
  write_elements(b, 2, types, faces);
  return fmt::to_string(b);
}

std::string write_msh(const VolumeMesh& mesh, const std::string& name) {
  std::vector<int> types;
  std::vector<std::vector<int>> cells;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    std::array<int, 8> o;
    const CellShape s = cell_shape(mesh, c, &o);
    if (s == CellShape::other)
      throw FileError(name, 0, -1,
                      fmt::format("cell {} is a general polyhedron with {} faces: gmsh .msh holds tetrahedra, "
                                  "hexahedra, prisms and pyramids only (use .vtk or .ovm)",
                                  c, mesh.cell_size(c)));
    // gmsh types 4 tetrahedron, 5 hexahedron, 6 prism, 7 pyramid.
    const int type = s == CellShape::tetrahedron ? 4 : s == CellShape::hexahedron ? 5 : s == CellShape::wedge ? 6 : 7;
    std::vector<int> one(o.begin(), o.begin() + type_nodes(type));
    if (type == 6)
      for (int i = 0; i < 6; ++i) one[i] = o[kPrismToVtk[i]];
    types.push_back(type);
    cells.push_back(std::move(one));
  }
  fmt::memory_buffer b;
  write_header(b, mesh.positions(), 3);
  write_elements(b, 3, types, cells);
  return fmt::to_string(b);
}

}  // namespace io_detail
}  // namespace polydec
