// dec/io/meshb.cpp — binary MEDIT .meshb (GMF, libMeshb's layout): the code word 1 (its byte order
// is the file's), the version (1: float coordinates, 32-bit integers and positions; 2: double
// coordinates; 3: 64-bit positions; 4: 64-bit integers too), then keywords, each a 32-bit code and
// the position of the next keyword: Dimension (a 32-bit word, 3), Vertices (x y z ref),
// Tetrahedra, Prisms, Pyramids, Hexahedra (vertices + ref, 1-based, MEDIT's orders as the ASCII
// reader's) until End (required: a file without it is taken as truncated). Edges, Triangles and
// Quadrilaterals (after Vertices) are read for their references and counted as skipped; other
// keywords are skipped by their next-keyword position. The references become groups on request
// (MeditGroups). Also the MEDIT cell blocks shared with the ASCII reader (dec/io/medit.cpp) and the
// writer (GMF version 2).
#include <array>
#include <bit>
#include <climits>
#include <cstdint>

#include "polydec/dec/detail/msh_io.h"
#include "polydec/dec/mesh/polyhedron_builder.h"
#include "polydec/dec/mesh/volume_cells.h"

namespace polydec {
namespace io_meshb_detail {
namespace {

using namespace io_detail;

// GMF keyword codes.
enum : int {
  kDimension = 3,
  kVertices = 4,
  kEdges = 5,
  kTriangles = 6,
  kQuadrilaterals = 7,
  kTetrahedra = 8,
  kPrisms = 9,
  kHexahedra = 10,
  kPyramids = 49,
  kEnd = 54
};

int vtk_type_of(int keyword) {
  return keyword == kTetrahedra ? kVtkTetra
         : keyword == kPrisms   ? kVtkWedge
         : keyword == kHexahedra ? kVtkHexahedron
                                 : kVtkPyramid;
}

bool big_endian_code(std::string_view bytes, bool& big) {
  if (bytes.size() < 8) return false;
  std::uint32_t le = 0, be = 0;
  for (int k = 0; k < 4; ++k) {
    le |= std::uint32_t((unsigned char)bytes[k]) << (8 * k);
    be |= std::uint32_t((unsigned char)bytes[k]) << (8 * (3 - k));
  }
  if (le != 1 && be != 1) return false;
  big = be == 1;
  return true;
}

}  // namespace
}  // namespace io_meshb_detail

namespace io_detail {

using namespace io_meshb_detail;

bool looks_like_meshb(std::string_view bytes) {
  bool big = false;
  if (!big_endian_code(bytes, big)) return false;
  BinaryCursor cur(bytes, 4, big, "");
  const std::int32_t version = cur.read<std::int32_t>("version");
  return version >= 1 && version <= 4;
}

PolyhedronRead build_medit_cells(PolyhedronRead r, const std::vector<MeditCells>& blocks, const std::string& name,
                                 bool byte_offsets) {
  const CoordinatePrecision precision = r.soup.precision;
  PolyhedronSoupBuilder builder(std::move(r.soup.positions));
  int cell[8];
  for (const auto& b : blocks) {
    const int n = vtk_cell_size(b.vtk_type);
    for (size_t c = 0; c < b.where.size(); ++c) {
      const int* v = b.vertices.data() + c * n;
      for (int k = 0; k < n; ++k) cell[k] = b.vtk_type == kVtkWedge ? v[kPrismToVtk[k]] : v[k];
      if (!builder.add_vtk_cell(b.vtk_type, {cell, size_t(n)})) {
        const std::string reason = fmt::format(
            "a face of this element has the vertices of face {} in another cyclic order", builder.last_face());
        if (byte_offsets) throw FileError(name, 0, b.where[c], reason);
        throw FileError(name, b.where[c], -1, reason);
      }
      while (int(r.face_where.size()) < builder.n_faces()) r.face_where.push_back(b.where[c]);
      r.cell_where.push_back(b.where[c]);
    }
  }
  r.soup = builder.take();
  r.soup.precision = precision;
  r.where_is_byte_offset = byte_offsets;
  return r;
}

PolyhedronRead read_meshb(std::string_view bytes, const std::string& name, MeshGroups* groups) {
  bool big = false;
  if (!big_endian_code(bytes, big))
    throw FileError(name, 0, 0, "not a binary MEDIT file (the first word is not the code 1 in either byte order)");
  BinaryCursor cur(bytes, 4, big, name);
  const std::int32_t version = cur.read<std::int32_t>("version");
  if (version < 1 || version > 4) throw FileError(name, 0, 4, fmt::format("unknown MEDIT version {}", version));
  const size_t real_size = version == 1 ? 4 : 8, int_size = version == 4 ? 8 : 4;
  const bool long_positions = version >= 3;
  auto fail = [&](size_t at, const std::string& reason) -> void { throw FileError(name, 0, long(at), reason); };
  auto integer = [&](const char* what) -> long long {
    return int_size == 8 ? cur.read<std::int64_t>(what) : cur.read<std::int32_t>(what);
  };

  PolyhedronRead r;
  MeditGroups refs;
  std::map<std::string, long> skipped;
  int n_cells = 0;
  std::vector<MeditCells> blocks;
  bool have_dimension = false, have_vertices = false, ended = false;
  long long nv = 0;
  while (!cur.at_end()) {
    const size_t at = cur.position();
    const std::int32_t keyword = cur.read<std::int32_t>("keyword");
    if ((ended = keyword == kEnd)) break;
    const long long next = long_positions ? cur.read<std::int64_t>("next keyword position")
                                          : cur.read<std::int32_t>("next keyword position");
    // The number of records and their size; fails when they do not fit in the file.
    auto count = [&](const char* what, size_t record) -> long long {
      const size_t here = cur.position();
      const long long n = integer(what);
      if (n < 0 || n > INT_MAX / 2) fail(here, fmt::format("bad {} {}", what, n));
      if (size_t(n) > cur.remaining() / record)
        fail(here, fmt::format("{} {} needs {} bytes but only {} follow", what, n, size_t(n) * record, cur.remaining()));
      return n;
    };
    if (keyword == kDimension) {
      const std::int32_t d = cur.read<std::int32_t>("dimension");
      if (d != 3) fail(at, fmt::format("dimension {} is not supported (volume meshes need 3)", d));
      have_dimension = true;
    } else if (keyword == kVertices) {
      if (!have_dimension) fail(at, "Vertices before the dimension 3");
      if (have_vertices) fail(at, "a second Vertices keyword");
      have_vertices = true;
      nv = count("vertex count", 3 * real_size + int_size);
      r.soup.positions.resize(nv, 3);
      r.vertex_where.resize(nv);
      for (long long v = 0; v < nv; ++v) {
        r.vertex_where[v] = long(cur.position());
        for (int c = 0; c < 3; ++c)
          r.soup.positions(v, c) = real_size == 4 ? double(cur.read<float>("a coordinate")) : cur.read<double>("a coordinate");
        refs.vertex(int(v), integer("vertex reference"));
      }
      if (real_size == 4) r.soup.precision = float_precision(r.soup.positions);
    } else if (keyword == kTetrahedra || keyword == kPrisms || keyword == kPyramids || keyword == kHexahedra) {
      if (!have_vertices) fail(at, "elements before Vertices");
      MeditCells b{vtk_type_of(keyword), {}, {}};
      const int n = vtk_cell_size(b.vtk_type);
      const long long m = count("element count", (n + 1) * int_size);
      b.vertices.reserve(size_t(m) * n);
      b.where.reserve(size_t(m));
      for (long long e = 0; e < m; ++e) {
        b.where.push_back(long(cur.position()));
        for (int k = 0; k < n; ++k) {
          const size_t here = cur.position();
          const long long x = integer("vertex index");
          if (x < 1 || x > nv)
            fail(here, fmt::format("vertex index {} out of range [1, {}] (MEDIT counts from 1)", x, nv));
          b.vertices.push_back(int(x - 1));
        }
        refs.element({b.vertices.data() + b.vertices.size() - n, size_t(n)}, integer("element reference"), n_cells++);
      }
      blocks.push_back(std::move(b));
    } else if (keyword == kEdges || keyword == kTriangles || keyword == kQuadrilaterals) {
      if (!have_vertices) fail(at, "elements before Vertices");
      const int n = keyword == kEdges ? 2 : keyword == kTriangles ? 3 : 4;
      const long long m = count("element count", (n + 1) * int_size);
      skipped[keyword == kEdges ? "lines" : keyword == kTriangles ? "triangles" : "quadrangles"] += long(m);
      int element[4];
      for (long long e = 0; e < m; ++e) {
        for (int k = 0; k < n; ++k) {
          const size_t here = cur.position();
          const long long x = integer("vertex index");
          if (x < 1 || x > nv)
            fail(here, fmt::format("vertex index {} out of range [1, {}] (MEDIT counts from 1)", x, nv));
          element[k] = int(x - 1);
        }
        refs.element({element, size_t(n)}, integer("element reference"), -1);
      }
    } else {
      if (next <= (long long)cur.position() || next > (long long)bytes.size())
        fail(at, fmt::format("keyword {} (not read) has the bad next-keyword position {}", keyword, next));
      cur.skip(size_t(next) - cur.position(), "a keyword's data");
    }
  }
  if (!have_vertices) throw FileError(name, 0, -1, "no Vertices keyword");
  if (!ended) throw FileError(name, 0, long(bytes.size()), "the file ends without the End keyword (truncated?)");
  if (groups) *groups = refs.take(std::move(skipped));
  return build_medit_cells(std::move(r), blocks, name, true);
}

MeditBlocks medit_blocks(const VolumeMesh& mesh, const std::string& name) {
  MeditBlocks b;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    std::array<int, 8> o;
    const CellShape s = cell_shape(mesh, c, &o);
    const int kind = s == CellShape::tetrahedron  ? 0
                     : s == CellShape::wedge      ? 1
                     : s == CellShape::hexahedron ? 2
                     : s == CellShape::pyramid    ? 3
                                                  : -1;
    if (kind < 0)
      throw FileError(name, 0, -1,
                      fmt::format("cell {} is a general polyhedron with {} faces: MEDIT holds tetrahedra, prisms, "
                                  "hexahedra and pyramids only (use .vtk, .vtu or .ovm)",
                                  c, mesh.cell_size(c)));
    for (int k = 0; k < MeditBlocks::kSizes[kind]; ++k)
      b.vertices[size_t(kind)].push_back(kind == 1 ? o[size_t(kPrismToVtk[k])] : o[size_t(k)]);
  }
  return b;
}

std::string write_meshb(const VolumeMesh& mesh, const std::string& name) {
  // The GMF keyword of each of medit_blocks' sections.
  constexpr std::array<int, 4> kKeywords{kTetrahedra, kPrisms, kHexahedra, kPyramids};
  const std::array<std::vector<int>, 4> cells = medit_blocks(mesh, name).vertices;
  // Code word, version, Dimension, Vertices, the cell keywords, End: 32-bit positions must hold the size.
  std::uint64_t size = 8 + 12 + 12 + std::uint64_t(mesh.n_vertices()) * 28 + 8;
  for (size_t k = 0; k < 4; ++k)
    if (!cells[k].empty()) size += 12 + cells[k].size() * 4 + cells[k].size() / vtk_cell_size(vtk_type_of(kKeywords[k])) * 4;
  if (size > std::uint64_t(INT32_MAX))
    throw FileError(name, 0, -1,
                    fmt::format("the file would take {} bytes, beyond the 32-bit positions of GMF version 2 (at "
                                "most {})",
                                size, INT32_MAX));
  std::string s;
  s.reserve(size_t(size));
  auto i32 = [&](long long x) { put_le(s, std::int32_t(x)); };
  // A keyword's code and, once its data is written, the position of the next keyword.
  size_t next = 0;
  auto keyword = [&](int code) {
    i32(code);
    next = s.size();
    i32(0);
  };
  auto close = [&] {
    std::string at;
    put_le(at, std::int32_t(s.size()));
    s.replace(next, 4, at);
  };
  i32(1);
  i32(2);
  keyword(kDimension);
  i32(3);
  close();
  keyword(kVertices);
  i32(mesh.n_vertices());
  const auto& X = mesh.positions();
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    for (int c = 0; c < 3; ++c) put_le(s, X(v, c));
    i32(0);
  }
  close();
  for (size_t k = 0; k < 4; ++k) {
    if (cells[k].empty()) continue;
    const int n = vtk_cell_size(vtk_type_of(kKeywords[k]));
    keyword(kKeywords[k]);
    i32((long long)cells[k].size() / n);
    for (size_t i = 0; i < cells[k].size(); ++i) {
      i32(cells[k][i] + 1);
      if ((i + 1) % size_t(n) == 0) i32(0);
    }
    close();
  }
  i32(kEnd);
  i32(0);
  return s;
}

}  // namespace io_detail
}  // namespace polydec
