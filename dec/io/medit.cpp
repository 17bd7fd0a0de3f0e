// dec/io/medit.cpp — MEDIT ASCII .mesh (INRIA): MeshVersionFormatted, Dimension 3, then sections
// in any order: Vertices (x y z ref), Tetrahedra (4 indices + ref), Hexahedra (8 indices + ref;
// both in VTK's vertex order), Prisms (6 + ref; the first triangle's normal points to the second,
// as gmsh's) and Pyramids (5 + ref; VTK's order), 1-based; the references become groups on request
// (MeditGroups). Edges, Triangles and Quadrilaterals (after Vertices) are read for their references
// and counted as skipped; Corners, Ridges, Required*, Normals, Tangents ... are skipped; "End" or
// the end of the file ends it; '#' starts a comment.
#include <array>
#include <climits>

#include "polydec/dec/detail/io_common.h"
#include "polydec/dec/detail/msh_io.h"
#include "polydec/dec/detail/volume_io_common.h"
#include "polydec/dec/mesh/polyhedron_builder.h"
#include "polydec/dec/mesh/volume_cells.h"

namespace polydec {
namespace io_medit_detail {
namespace {

using namespace io_detail;

// Numbers per record of the sections that are skipped unread (lower-case keyword).
int skipped_record_size(const std::string& k) {
  if (k == "corners" || k == "ridges" || k == "requiredvertices" || k == "requirededges" ||
      k == "requiredtriangles" || k == "requiredquadrilaterals")
    return 1;
  if (k == "normals" || k == "tangents") return 3;
  if (k == "normalatvertices" || k == "tangentatvertices") return 2;
  return 0;
}

}  // namespace
}  // namespace io_medit_detail

namespace io_detail {

PolyhedronRead read_medit(std::string_view bytes, const std::string& name) { return read_medit(bytes, name, nullptr); }

PolyhedronRead read_medit(std::string_view bytes, const std::string& name, MeshGroups* groups) {
  VolumeTokens in(strip_bom(bytes), name, true);
  std::string_view t;
  if (!in.next(t)) in.fail(0, "empty file (no MeshVersionFormatted)");
  if (lower(t) != "meshversionformatted")
    in.fail(in.line(), fmt::format("expected 'MeshVersionFormatted', found {}", quote(t)));
  const long long version = in.integer("version");
  if (version < 1 || version > 4) in.fail(in.line(), fmt::format("unknown MEDIT version {}", version));

  PolyhedronRead r;
  bool have_vertices = false, have_dimension = false;
  long long nv = 0;
  int n_cells = 0;
  std::vector<MeditCells> blocks;
  MeditGroups refs;
  std::map<std::string, long> skipped;
  while (in.next(t)) {
    const std::string k = lower(t);
    const long kline = in.line();
    if (k == "end") break;
    if (k == "dimension") {
      const long long d = in.integer("dimension");
      if (d != 3) in.fail(in.line(), fmt::format("dimension {} is not supported (volume meshes need 3)", d));
      have_dimension = true;
    } else if (k == "vertices") {
      if (!have_dimension) in.fail(kline, "Vertices before 'Dimension 3'");
      if (have_vertices) in.fail(kline, "a second Vertices section");
      have_vertices = true;
      nv = in.count("Vertices count", 8);
      r.soup.positions.resize(nv, 3);
      r.vertex_where.resize(nv);
      DigitCounter digits;
      for (long long v = 0; v < nv; ++v) {
        for (int c = 0; c < 3; ++c) {
          const std::string_view x = in.expect("a vertex coordinate");
          if (c == 0) r.vertex_where[v] = in.line();
          if (!parse_double(x, r.soup.positions(v, c)))
            in.fail(in.line(), "bad vertex coordinate " + quote(x));
          digits.see(x, r.soup.positions(v, c));
        }
        refs.vertex(int(v), in.integer("vertex reference"));
      }
      r.soup.precision = digits.precision(r.soup.positions);
    } else if (k == "tetrahedra" || k == "hexahedra" || k == "prisms" || k == "pyramids") {
      if (!have_vertices) in.fail(kline, fmt::format("{} before Vertices", t));
      const int type = k == "tetrahedra" ? kVtkTetra
                       : k == "hexahedra" ? kVtkHexahedron
                       : k == "prisms"    ? kVtkWedge
                                          : kVtkPyramid;
      const int n = vtk_cell_size(type);
      const std::string section(t);
      const long long count = in.count(section + " count", 2LL * (n + 1));
      MeditCells b{type, {}, {}};
      b.vertices.reserve(count * n);
      b.where.reserve(count);
      for (long long c = 0; c < count; ++c) {
        for (int i = 0; i < n; ++i) {
          const long long x = in.integer("vertex index");
          if (i == 0) b.where.push_back(in.line());
          if (x < 1 || x > nv)
            in.fail(in.line(),
                    fmt::format("vertex index {} out of range [1, {}] (MEDIT counts from 1)", x, nv));
          b.vertices.push_back(int(x - 1));
        }
        refs.element({b.vertices.data() + b.vertices.size() - n, size_t(n)}, in.integer("element reference"),
                     n_cells++);
      }
      blocks.push_back(std::move(b));
    } else if (k == "edges" || k == "triangles" || k == "quadrilaterals") {
      if (!have_vertices) in.fail(kline, fmt::format("{} before Vertices", t));
      const int n = k == "edges" ? 2 : k == "triangles" ? 3 : 4;
      const std::string section(t);
      const long long count = in.count(section + " count", 2LL * (n + 1));
      int element[4];
      for (long long c = 0; c < count; ++c) {
        for (int i = 0; i < n; ++i) {
          const long long x = in.integer("vertex index");
          if (x < 1 || x > nv)
            in.fail(in.line(),
                    fmt::format("vertex index {} out of range [1, {}] (MEDIT counts from 1)", x, nv));
          element[i] = int(x - 1);
        }
        refs.element({element, size_t(n)}, in.integer("element reference"), -1);
      }
      skipped[k == "edges" ? "lines" : k == "triangles" ? "triangles" : "quadrangles"] += long(count);
    } else if (const int m = io_medit_detail::skipped_record_size(k); m > 0) {
      const long long count = in.count(std::string(t) + " count", 2LL * m);
      for (long long i = 0; i < count * m; ++i) in.expect("a number");
    } else {
      in.fail(kline, fmt::format("unknown MEDIT keyword {}", quote(t)));
    }
  }
  if (!have_vertices) in.fail(0, "no Vertices section");
  if (groups) *groups = refs.take(std::move(skipped));
  return build_medit_cells(std::move(r), blocks, name, false);
}

std::string write_medit(const VolumeMesh& mesh, const std::string& name) {
  const MeditBlocks blocks = medit_blocks(mesh, name);
  const auto& X = mesh.positions();
  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  fmt::format_to(out, "MeshVersionFormatted 2\nDimension 3\nVertices\n{}\n", mesh.n_vertices());
  for (int v = 0; v < mesh.n_vertices(); ++v)
    fmt::format_to(out, "{} {} {} 0\n", num(X(v, 0)), num(X(v, 1)), num(X(v, 2)));
  for (size_t k = 0; k < 4; ++k) {
    const std::vector<int>& cells = blocks.vertices[k];
    const size_t n = size_t(MeditBlocks::kSizes[k]);
    if (cells.empty()) continue;
    fmt::format_to(out, "{}\n{}\n", MeditBlocks::kNames[k], cells.size() / n);
    for (size_t i = 0; i < cells.size(); ++i) fmt::format_to(out, "{}{}", cells[i] + 1, (i + 1) % n == 0 ? " 0\n" : " ");
  }
  fmt::format_to(out, "End\n");
  return fmt::to_string(b);
}

}  // namespace io_detail
}  // namespace polydec
