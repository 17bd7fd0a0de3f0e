// dec/io/mesh_io.cpp — FileError, format dispatch by extension, read_mesh (validation errors mapped
// back to file positions) and write_mesh. The formats live in obj.cpp, off.cpp,
// ply.cpp and matrix_market.cpp.
#include "polydec/dec/io/mesh_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/detail/io_common.h"
#include "polydec/dec/detail/msh_io.h"
#include "polydec/dec/io/vtu.h"

namespace polydec {

using namespace io_detail;

FileError::FileError(std::string file_, long line_, long byte_offset_, std::string reason_)
    : std::runtime_error(line_ > 0           ? fmt::format("{}:{}: {}", file_, line_, reason_)
                         : byte_offset_ >= 0 ? fmt::format("{}: byte {}: {}", file_, byte_offset_, reason_)
                                             : fmt::format("{}: {}", file_, reason_)),
      file(std::move(file_)),
      line(line_),
      byte_offset(byte_offset_),
      reason(std::move(reason_)) {}

namespace io_detail {

std::string lower(std::string_view s) {
  std::string e(s);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

std::string extension(const std::string& path) {
  const std::string file = std::filesystem::path(path).filename().string();
  const auto dot = file.find_last_of('.');
  return dot == std::string::npos ? "" : lower(file.substr(dot + 1));
}

std::string slurp(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw FileError(path, 0, -1, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, 0, -1, "cannot open file");
  std::string data;
  // A regular file is read in one piece into storage of its size, advised for huge pages: growing
  // the string by appends would copy and first-touch about twice the file. Whatever the file holds
  // beyond that size by now is appended below; a file that shrank ends at what was read.
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > 0 && size < data.max_size()) {
    data.reserve(size_t(size));
    advise_huge_pages(data.data(), size_t(size));
    data.resize(size_t(size));
    in.read(data.data(), std::streamsize(size));
    data.resize(size_t(in.gcount()));
  }
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) data.append(buf, size_t(in.gcount()));
  if (in.bad()) throw FileError(path, 0, -1, "read error");
  return data;
}

}  // namespace io_detail

namespace mesh_io_detail {
namespace {

using namespace io_detail;

// Every format polydec reads, for the "unknown format" messages.
constexpr const char* kFormats = "surfaces: obj, off, ply, msh, vtu; volumes: ovm, vtk, vtu, mesh, meshb, msh";

SoupRead read_any(std::string_view bytes, std::string_view format, const std::string& name) {
  const std::string f = lower(format);
  if (f == "obj") return read_obj(bytes, name);
  if (f == "off") return read_off(bytes, name);
  if (f == "ply") return read_ply(bytes, name);
  if (f == "msh") return read_msh_surface(bytes, name);
  if (f == "vtu") return read_vtu_surface(bytes, name);
  throw FileError(name, 0, -1, fmt::format("unknown mesh format '{}' ({})", f, kFormats));
}

// The file's bytes and format: by extension, else by content (gmsh's "$MeshFormat", VTK XML's
// "<?xml" or "<VTKFile").
std::pair<std::string, std::string> read_file(const std::string& path) {
  const std::string ext = extension(path);
  if (ext == "obj" || ext == "off" || ext == "ply" || ext == "msh" || ext == "vtu") return {slurp(path), ext};
  const FileError unknown(path, 0, -1, fmt::format("unknown mesh format '.{}' ({})", ext, kFormats));
  std::string bytes;
  try {
    bytes = slurp(path);
  } catch (const FileError&) {
    throw unknown;
  }
  if (looks_like_msh(bytes)) return {std::move(bytes), "msh"};
  std::string_view t = strip_bom(bytes);
  while (!t.empty() && (is_space(t.front()) || t.front() == '\n')) t.remove_prefix(1);
  const std::string head = lower(t.substr(0, 20));
  if (head.rfind("<?xml", 0) == 0 || head.rfind("<vtkfile", 0) == 0) return {std::move(bytes), "vtu"};
  throw unknown;
}

// Validates; an InvalidMeshError about a vertex or face names its line or byte offset.
Mesh validate(SoupRead r, const std::string& name) {
  const auto vertex_where = std::move(r.vertex_where);
  const auto face_where = std::move(r.face_where);
  try {
    return Mesh(std::move(r.soup));
  } catch (const InvalidMeshError& e) {
    const std::vector<long>* where = e.element == "vertex" ? &vertex_where
                                     : e.element == "face" ? &face_where
                                                           : nullptr;
    long at = -1;
    if (where && e.index >= 0 && e.index < long(where->size())) at = (*where)[e.index];
    if (r.where_is_byte) throw FileError(name, 0, at, e.what());
    throw FileError(name, std::max(at, 0L), -1, e.what());
  }
}

}  // namespace
}  // namespace mesh_io_detail


namespace io_detail {

SoupRead read_surface_file(const std::string& path, MeshGroups* groups) {
  const auto [bytes, format] = mesh_io_detail::read_file(path);
  if (format == "msh") return read_msh_surface(bytes, path, groups);
  return mesh_io_detail::read_any(bytes, format, path);
}

Mesh validate_surface(SoupRead r, const std::string& name) { return mesh_io_detail::validate(std::move(r), name); }

}  // namespace io_detail

PolygonSoup read_polygon_soup(const std::string& path) {
  const auto [bytes, format] = mesh_io_detail::read_file(path);
  return mesh_io_detail::read_any(bytes, format, path).soup;
}

PolygonSoup read_polygon_soup_from_memory(std::string_view bytes, std::string_view format,
                                          const std::string& name) {
  return mesh_io_detail::read_any(bytes, format, name).soup;
}

Mesh read_mesh(const std::string& path) {
  const auto [bytes, format] = mesh_io_detail::read_file(path);
  return mesh_io_detail::validate(mesh_io_detail::read_any(bytes, format, path), path);
}

Mesh read_mesh_with_groups(const std::string& path, MeshGroups& groups) {
  const auto [bytes, format] = mesh_io_detail::read_file(path);
  groups = {};
  if (format != "msh") return mesh_io_detail::validate(mesh_io_detail::read_any(bytes, format, path), path);
  return mesh_io_detail::validate(io_detail::read_msh_surface(bytes, path, &groups), path);
}

Mesh read_mesh_from_memory(std::string_view bytes, std::string_view format, const std::string& name) {
  return mesh_io_detail::validate(mesh_io_detail::read_any(bytes, format, name), name);
}

void write_mesh(const std::string& path, const Mesh& mesh, const VertexScalars& scalars,
                const WriteOptions& options) {
  const std::string ext = io_detail::extension(path);
  std::string data;
  if ((ext == "obj" || ext == "off") && !scalars.empty())
    throw FileError(path, 0, -1,
                    fmt::format("{} cannot hold the vertex scalars ({} of them): write .ply or .vtu",
                                ext == "obj" ? "OBJ" : "OFF", scalars.size()));
  if (ext == "obj") {
    data = io_detail::write_obj(mesh);
  } else if (ext == "off") {
    data = io_detail::write_off(mesh, options.binary);
  } else if (ext == "ply") {
    for (const auto& [name, values] : scalars) {
      if (name.empty() || std::any_of(name.begin(), name.end(), [](char c) { return c <= ' ' || c == 127; }))
        throw FileError(path, 0, -1,
                        fmt::format("scalar property name {} is empty or has whitespace", io_detail::quote(name)));
      if (values.size() != mesh.n_vertices())
        throw FileError(path, 0, -1,
                        fmt::format("scalar property '{}' has {} values for {} vertices", name, values.size(),
                                    mesh.n_vertices()));
    }
    data = io_detail::write_ply(mesh, scalars, options.binary);
  } else if (ext == "msh") {
    data = io_detail::write_msh(mesh, path);
  } else if (ext == "vtu") {
    VtuFields fields;
    fields.point_scalars = scalars;
    try {
      data = write_vtu_to_string(mesh, fields, options.binary);
    } catch (const std::invalid_argument& e) {
      throw FileError(path, 0, -1, e.what());
    }
  } else {
    throw FileError(path, 0, -1, fmt::format("unknown mesh format '.{}' (obj, off, ply, msh, vtu)", ext));
  }
  std::ofstream out(path, std::ios::binary);
  if (!out) throw FileError(path, 0, -1, "cannot open file for writing");
  out.write(data.data(), std::streamsize(data.size()));
  out.close();
  if (!out) throw FileError(path, 0, -1, "write failed");
}

}  // namespace polydec
