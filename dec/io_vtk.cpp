// dec/io_vtk.cpp — VTK legacy ASCII unstructured grids: "# vtk DataFile Version N", a title
// line, ASCII, DATASET UNSTRUCTURED_GRID, POINTS, CELLS (the classic layout "n k i_1 .. i_k",
// or version 5's OFFSETS/CONNECTIVITY arrays) and CELL_TYPES; cell types 10 tetra,
// 12 hexahedron, 13 wedge, 14 pyramid (VTK's vertex orders) and 42 polyhedron (classic layout:
// "n n_faces k_1 face_1 .. "). Faces shared by cells are identified by their vertex sets.
// Sections after CELL_TYPES (POINT_DATA, CELL_DATA, FIELD) are ignored.
#include <array>
#include <climits>

#include "polydec/dec/io_common.h"
#include "polydec/dec/io_volume_common.h"
#include "polydec/dec/polyhedron_builder.h"
#include "polydec/dec/volume_cells.h"

namespace polydec {
namespace io_vtk_detail {
namespace {

using namespace io_detail;

const char* type_name(long long t) {
  switch (t) {
    case 1:
      return " (vertex)";
    case 3:
      return " (line)";
    case 5:
      return " (triangle)";
    case 7:
      return " (polygon)";
    case 9:
      return " (quad)";
    case 11:
      return " (voxel)";
    default:
      return "";
  }
}

}  // namespace
}  // namespace io_vtk_detail

namespace io_detail {

PolyhedronRead read_vtk(std::string_view bytes, const std::string& name) {
  VolumeTokens in(strip_bom(bytes), name);
  // Header line, title line, ASCII, DATASET UNSTRUCTURED_GRID.
  std::string_view t;
  if (!in.next(t)) in.fail(0, "empty file (no '# vtk DataFile' header)");
  std::string_view head = in.rest_of_line();
  const std::string header = lower(std::string(t) + std::string(head));
  if (header.rfind("# vtk datafile", 0) != 0 && header.rfind("#vtk datafile", 0) != 0)
    in.fail(1, fmt::format("expected the header '# vtk DataFile Version ...', found {}", quote(t)));
  const bool version5 = header.find("version 5") != std::string::npos;
  in.skip_line();  // end of the header line
  in.skip_line();  // the title line
  const std::string_view format = in.expect("ASCII");
  if (lower(format) == "binary") in.fail(in.line(), "binary VTK files are not supported (only ASCII)");
  if (lower(format) != "ascii") in.fail(in.line(), fmt::format("expected 'ASCII', found {}", quote(format)));
  in.keyword("DATASET");
  const std::string_view dataset = in.expect("a dataset type");
  if (lower(dataset) != "unstructured_grid")
    in.fail(in.line(), fmt::format("dataset {} is not supported (only UNSTRUCTURED_GRID)", quote(dataset)));

  // Optional FIELD data before POINTS is not supported; POINTS must come next.
  in.keyword("POINTS");
  PolyhedronRead r;
  const long long nv = in.count("point count", 6);
  in.expect("the point data type");
  r.soup.positions.resize(nv, 3);
  r.vertex_where.resize(nv);
  for (long long v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c) {
      const std::string_view x = in.expect("a point coordinate");
      if (c == 0) r.vertex_where[v] = in.line();
      if (!parse_double(x, r.soup.positions(v, c))) in.fail(in.line(), "bad point coordinate " + quote(x));
    }

  in.keyword("CELLS");
  const long cells_line = in.line();
  const long long n_cells_field = in.count("cell count", 2);
  const long long size = in.count("cell list size", 2);
  // Cell vertex lists as flat offsets + ids, and each cell's line.
  std::vector<long long> offsets{0};
  std::vector<int> ids;
  std::vector<long> cell_line;
  auto vertex_id = [&](const char* what) {
    const long long i = in.integer(what);
    if (i < 0 || i >= nv) in.fail(in.line(), fmt::format("point index {} out of range [0, {})", i, nv));
    return int(i);
  };
  long long nc = 0;
  if (version5) {
    // n_cells_field offsets (n + 1 of them) and `size` connectivity entries.
    if (n_cells_field < 1) in.fail(cells_line, "CELLS needs at least one offset in the version 5 layout");
    nc = n_cells_field - 1;
    in.keyword("OFFSETS");
    in.expect("the offset data type");
    offsets.clear();
    offsets.reserve(n_cells_field);
    for (long long k = 0; k <= nc; ++k) {
      const long long o = in.integer("offset");
      if ((k == 0 && o != 0) || (k > 0 && o < offsets.back()) || o > size)
        in.fail(in.line(), fmt::format("offset {} out of order (offsets rise from 0 to {})", o, size));
      offsets.push_back(o);
      cell_line.push_back(in.line());
    }
    cell_line.pop_back();
    if (offsets.back() != size)
      in.fail(in.line(), fmt::format("the last offset is {} but CELLS announced {} connectivity entries",
                                     offsets.back(), size));
    in.keyword("CONNECTIVITY");
    in.expect("the connectivity data type");
    ids.reserve(size);
    for (long long k = 0; k < size; ++k) ids.push_back(vertex_id("connectivity entry"));
  } else {
    nc = n_cells_field;
    if (nc > size) in.fail(cells_line, fmt::format("{} cells cannot fit in a list of {} numbers", nc, size));
    ids.reserve(size - nc);
    offsets.reserve(nc + 1);
    long long used = 0;
    for (long long c = 0; c < nc; ++c) {
      const long long k = in.integer("cell size");
      cell_line.push_back(in.line());
      if (k < 0 || used + 1 + k > size)
        in.fail(in.line(),
                fmt::format("cell {} lists {} numbers, beyond the announced list size {}", c, k, size));
      used += 1 + k;
      // Polyhedron face streams hold counts besides point ids: range-checked once the type is known.
      for (long long i = 0; i < k; ++i) {
        const long long x = in.integer("cell entry");
        if (x < 0 || x > INT_MAX) in.fail(in.line(), fmt::format("cell entry {} out of range", x));
        ids.push_back(int(x));
      }
      offsets.push_back((long long)ids.size());
    }
    if (used != size)
      in.fail(in.line(), fmt::format("the cells hold {} numbers but CELLS announced {}", used, size));
  }

  in.keyword("CELL_TYPES");
  const long long nt = in.count("cell type count", 2);
  if (nt != nc) in.fail(in.line(), fmt::format("CELL_TYPES lists {} types for {} cells", nt, nc));
  std::vector<int> types(nc);
  std::vector<long> type_line(nc);
  for (long long c = 0; c < nc; ++c) {
    const long long ty = in.integer("cell type");
    type_line[c] = in.line();
    if (ty != kVtkTetra && ty != kVtkHexahedron && ty != kVtkWedge && ty != kVtkPyramid &&
        ty != kVtkPolyhedron)
      in.fail(in.line(),
              fmt::format("unknown or unsupported cell type {}{} of cell {} (10 tetra, 12 hexahedron, 13 "
                          "wedge, 14 pyramid, 42 polyhedron are read)",
                          ty, io_vtk_detail::type_name(ty), c));
    types[c] = int(ty);
  }

  PolyhedronSoupBuilder builder(std::move(r.soup.positions));
  std::vector<int> poly;
  for (long long c = 0; c < nc; ++c) {
    const long ln = cell_line[c];
    const std::span<const int> cell(ids.data() + offsets[c], size_t(offsets[c + 1] - offsets[c]));
    const int type = types[c];
    if (type == kVtkPolyhedron) {
      if (version5)
        in.fail(type_line[c], "polyhedron cells (type 42) in the version 5 layout are not supported");
      if (cell.empty()) in.fail(ln, fmt::format("polyhedron cell {} is empty", c));
      size_t p = 1;
      for (int f = 0; f < cell[0]; ++f) {
        if (p >= cell.size())
          in.fail(ln, fmt::format("polyhedron cell {}: face {} lies beyond the cell's numbers", c, f));
        const size_t k = size_t(cell[p]);
        if (k > cell.size() - p - 1)
          in.fail(ln, fmt::format("polyhedron cell {}: face {} lists {} points, beyond the cell's numbers", c,
                                  f, k));
        if (k < 3)
          in.fail(ln, fmt::format("polyhedron cell {}: face {} has {} points (at least 3 needed)", c, f, k));
        poly.assign(cell.begin() + p + 1, cell.begin() + p + 1 + k);
        for (int v : poly)
          if (v >= nv) in.fail(ln, fmt::format("point index {} out of range [0, {})", v, nv));
        if (builder.add_polygon(poly) < 0)
          in.fail(ln,
                  fmt::format("polyhedron cell {}: face {} has the points of face {} in another cyclic order",
                              c, f, builder.last_face()));
        while (int(r.face_where.size()) < builder.n_faces()) r.face_where.push_back(ln);
        p += 1 + k;
      }
      if (p != cell.size())
        in.fail(ln, fmt::format("polyhedron cell {}: its {} faces use {} of its {} numbers", c, cell[0], p,
                                cell.size()));
      builder.end_cell();
    } else {
      const int n = vtk_cell_size(type);
      if (int(cell.size()) != n)
        in.fail(ln, fmt::format("cell {} of type {} needs {} points, it lists {}", c, type, n, cell.size()));
      for (int v : cell)
        if (v >= nv) in.fail(ln, fmt::format("point index {} out of range [0, {})", v, nv));
      if (!builder.add_vtk_cell(type, cell))
        in.fail(ln, fmt::format("cell {}: a face has the points of face {} in another cyclic order", c,
                                builder.last_face()));
      while (int(r.face_where.size()) < builder.n_faces()) r.face_where.push_back(ln);
    }
    r.cell_where.push_back(ln);
  }
  r.soup = builder.take();
  return r;
}

std::string write_vtk(const VolumeMesh& mesh) {
  const auto& X = mesh.positions();
  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  fmt::format_to(out, "# vtk DataFile Version 4.2\npolydec volume mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n");
  fmt::format_to(out, "POINTS {} double\n", mesh.n_vertices());
  for (int v = 0; v < mesh.n_vertices(); ++v)
    fmt::format_to(out, "{} {} {}\n", num(X(v, 0)), num(X(v, 1)), num(X(v, 2)));
  std::vector<int> types(mesh.n_cells());
  std::vector<std::array<int, 8>> orders(mesh.n_cells());
  long long size = 0;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const CellShape s = cell_shape(mesh, c, &orders[c]);
    types[c] = s == CellShape::tetrahedron  ? kVtkTetra
               : s == CellShape::pyramid    ? kVtkPyramid
               : s == CellShape::wedge      ? kVtkWedge
               : s == CellShape::hexahedron ? kVtkHexahedron
                                            : kVtkPolyhedron;
    if (types[c] == kVtkPolyhedron) {
      size += 2;
      for (int h : mesh.cell(c)) size += 1 + mesh.face_size(h / 2);
    } else {
      size += 1 + vtk_cell_size(types[c]);
    }
  }
  fmt::format_to(out, "CELLS {} {}\n", mesh.n_cells(), size);
  for (int c = 0; c < mesh.n_cells(); ++c) {
    if (types[c] == kVtkPolyhedron) {
      long long n = 1;
      for (int h : mesh.cell(c)) n += 1 + mesh.face_size(h / 2);
      fmt::format_to(out, "{} {}", n, mesh.cell_size(c));
      for (int h : mesh.cell(c)) {  // outward faces, as VTK's polyhedra expect
        const auto f = mesh.face(h / 2);
        fmt::format_to(out, " {} {}", f.size(), f[0]);
        for (size_t i = 1; i < f.size(); ++i) fmt::format_to(out, " {}", (h & 1) ? f[f.size() - i] : f[i]);
      }
    } else {
      const int n = vtk_cell_size(types[c]);
      fmt::format_to(out, "{}", n);
      for (int i = 0; i < n; ++i) fmt::format_to(out, " {}", orders[c][i]);
    }
    b.push_back('\n');
  }
  fmt::format_to(out, "CELL_TYPES {}\n", mesh.n_cells());
  for (int t : types) fmt::format_to(out, "{}\n", t);
  return fmt::to_string(b);
}

}  // namespace io_detail
}  // namespace polydec
