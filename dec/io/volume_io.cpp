// dec/io/volume_io.cpp — volume format dispatch by extension, read_volume_mesh (validation errors
// mapped back to file lines), the groups of gmsh and MEDIT files, and write_volume_mesh. The formats
// live in ovm.cpp, vtk.cpp, vtu.cpp, medit.cpp, meshb.cpp and msh.cpp.
#include "polydec/dec/io/volume_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "polydec/dec/detail/io_common.h"
#include "polydec/dec/detail/msh_io.h"
#include "polydec/dec/detail/volume_io_common.h"
#include "polydec/dec/io/mesh_groups.h"
#include "polydec/dec/io/vtu.h"

namespace polydec {
namespace io_volume_detail {
namespace {

using namespace io_detail;

constexpr const char* kFormats = "ovm, vtk, vtu, mesh, meshb, msh; surfaces: obj, off, ply, msh, vtu";

bool known(const std::string& f) {
  return f == "ovm" || f == "vtk" || f == "vtu" || f == "mesh" || f == "meshb" || f == "msh";
}

void write_bytes(const std::string& path, const std::string& data) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw FileError(path, 0, -1, "cannot open file for writing");
  out.write(data.data(), std::streamsize(data.size()));
  out.close();
  if (!out) throw FileError(path, 0, -1, "write failed");
}

// True when the bytes start (after a BOM and white space) with MEDIT's "MeshVersionFormatted".
bool looks_like_medit(std::string_view bytes) {
  std::string_view t = strip_bom(bytes);
  while (!t.empty() && (is_space(t.front()) || t.front() == '\n')) t.remove_prefix(1);
  return lower(t.substr(0, 20)) == "meshversionformatted";
}

// The format by extension; for another extension, by the file's first word ("OVM", "# vtk",
// "MeshVersionFormatted"), so that `--volume` can read a file of any name.
std::string checked_format(const std::string& path, std::string_view bytes) {
  const std::string ext = extension(path);
  if (known(ext)) return ext;
  std::string_view t = strip_bom(bytes);
  while (!t.empty() && (is_space(t.front()) || t.front() == '\n')) t.remove_prefix(1);
  const std::string head = lower(t.substr(0, 20));
  if (head.rfind("ovm", 0) == 0) return "ovm";
  if (head.rfind("# vtk", 0) == 0 || head.rfind("#vtk", 0) == 0) return "vtk";
  if (looks_like_medit(bytes)) return "mesh";
  if (looks_like_msh(bytes)) return "msh";
  if (looks_like_meshb(bytes)) return "meshb";
  if (head.rfind("<?xml", 0) == 0 || head.rfind("<vtkfile", 0) == 0) return "vtu";
  throw FileError(
      path, 0, -1,
      fmt::format("unknown volume mesh format '.{}' ({}; nor does the file start like one)", ext, kFormats));
}

PolyhedronRead read_any(std::string_view bytes, std::string_view format, const std::string& name) {
  const std::string f = lower(format);
  if (f == "ovm") return read_ovm(bytes, name);
  if (f == "vtk") return read_vtk(bytes, name);
  if (f == "mesh") return read_medit(bytes, name);
  if (f == "meshb") return read_meshb(bytes, name);
  if (f == "msh") return read_msh_volume(bytes, name);
  if (f == "vtu") return read_vtu(bytes, name);
  throw FileError(name, 0, -1, fmt::format("unknown volume mesh format '{}' ({})", f, kFormats));
}

VolumeMesh validate(PolyhedronRead r, const std::string& name, VolumeReadNotes* notes = nullptr) {
  if (notes) notes->skipped_cells = r.skipped;
  const auto vertex_where = std::move(r.vertex_where);
  const auto face_where = std::move(r.face_where);
  const auto cell_where = std::move(r.cell_where);
  const bool byte_offsets = r.where_is_byte_offset;
  // A file without cells would give empty operators and exit 0: refused, saying what it held.
  if (r.soup.n_cells() == 0)
    throw FileError(name, 0, -1,
                    fmt::format("no volume cells ({} vertices, {} faces): a volume mesh needs at least one cell",
                                r.soup.positions.rows(), r.soup.face_offsets.empty() ? 0 : r.soup.face_offsets.size() - 1));
  try {
    return VolumeMesh(std::move(r.soup));
  } catch (const InvalidMeshError& e) {
    const std::vector<long>* where = e.element == "vertex" ? &vertex_where
                                     : e.element == "face" ? &face_where
                                     : e.element == "cell" ? &cell_where
                                                           : nullptr;
    long at = 0;
    if (where && e.index >= 0 && e.index < long(where->size())) at = (*where)[e.index];
    if (byte_offsets) throw FileError(name, 0, at, e.what());
    throw FileError(name, std::max(at, 0L), -1, e.what());
  }
}

// The bytes read as a volume in `format`, with the groups of a gmsh or MEDIT file (when `groups` is given).
VolumeMesh read_volume_bytes(std::string_view bytes, const std::string& format, const std::string& path,
                             MeshGroups* groups, VolumeReadNotes* notes) {
  if (groups) *groups = {};
  if (groups && format == "msh") return validate(read_msh_volume(bytes, path, groups), path, notes);
  if (groups && format == "meshb") return validate(read_meshb(bytes, path, groups), path, notes);
  if (groups && format == "mesh") return validate(read_medit(bytes, path, groups), path, notes);
  return validate(read_any(bytes, format, path), path, notes);
}

}  // namespace
}  // namespace io_volume_detail

using namespace io_volume_detail;

MeshFile read_mesh_file(const std::string& path, const MeshFileOptions& options) {
  const std::string ext = extension(path);
  MeshFile file;
  MeshGroups* groups = options.groups ? &file.groups : nullptr;
  const auto surface = [&](SoupRead r) {
    if (options.validate_surface)
      file.surface = validate_surface(std::move(r), path);
    else
      file.soup = std::move(r.soup);
  };
  const auto either = [&](SurfaceOrVolumeRead r) {
    if (r.volume)
      file.volume = validate(std::move(r.cells), path, &file.notes);
    else
      surface(std::move(r.surface));
  };
  if (options.volume || (known(ext) && ext != "msh" && ext != "vtu")) {
    const std::string bytes = slurp(path);
    file.volume = read_volume_bytes(bytes, checked_format(path, bytes), path, groups, &file.notes);
  } else if (ext == "msh" || ext == "vtu") {
    const std::string bytes = slurp(path);
    if (ext == "vtu")
      either(read_vtu_either(bytes, path));
    else if (looks_like_msh(bytes))
      either(read_msh_either(bytes, path, groups));
    else
      file.volume = read_volume_bytes(bytes, ext, path, groups, &file.notes);
  } else {
    surface(read_surface_file(path, groups));
  }
  return file;
}

bool is_volume_mesh_path(const std::string& path) {
  const std::string ext = extension(path);
  if (ext != "msh" && ext != "vtu") return known(ext);
  std::string bytes;
  try {
    bytes = slurp(path);
  } catch (const FileError&) {
    return true;  // a file to be written, or an unreadable one (the volume reader says why)
  }
  if (ext == "vtu") return vtu_holds_volume(bytes, path);
  return msh_holds_volume(bytes, path) || !looks_like_msh(bytes);
}

PolyhedronSoup read_polyhedron_soup(const std::string& path) {
  const std::string bytes = slurp(path);
  return read_any(bytes, checked_format(path, bytes), path).soup;
}

PolyhedronSoup read_polyhedron_soup_from_memory(std::string_view bytes, std::string_view format,
                                                const std::string& name) {
  return read_any(bytes, format, name).soup;
}

VolumeMesh read_volume_mesh(const std::string& path, VolumeReadNotes* notes) {
  const std::string bytes = slurp(path);
  return validate(read_any(bytes, checked_format(path, bytes), path), path, notes);
}

VolumeMesh read_volume_mesh_with_groups(const std::string& path, MeshGroups& groups) {
  const std::string bytes = slurp(path);
  return read_volume_bytes(bytes, checked_format(path, bytes), path, &groups, nullptr);
}

MeshGroups read_mesh_groups(const std::string& path) {
  const std::string ext = extension(path);
  if (ext != "msh" && ext != "meshb" && ext != "mesh" && (known(ext) || ext == "obj" || ext == "off" || ext == "ply"))
    return {};
  const std::string bytes = slurp(path);
  MeshGroups groups;
  if (looks_like_msh(bytes))
    groups = read_msh_groups(bytes, path);
  else if (ext == "meshb" || looks_like_meshb(bytes))
    read_meshb(bytes, path, &groups);
  else if (ext == "mesh" || looks_like_medit(bytes))
    read_medit(bytes, path, &groups);
  return groups;
}

VolumeMesh read_volume_mesh_from_memory(std::string_view bytes, std::string_view format,
                                        const std::string& name) {
  return validate(read_any(bytes, format, name), name);
}

std::string write_volume_mesh_to_string(const VolumeMesh& mesh, std::string_view format,
                                        const WriteOptions& options) {
  const std::string f = io_detail::lower(format);
  if (f == "ovm") return io_detail::write_ovm(mesh);
  if (f == "vtk") return io_detail::write_vtk(mesh, "(memory)", options.binary);
  if (f == "mesh") return io_detail::write_medit(mesh, "(memory)");
  if (f == "meshb") return io_detail::write_meshb(mesh, "(memory)");
  if (f == "msh") return io_detail::write_msh(mesh, "(memory)");
  if (f == "vtu") return write_vtu_to_string(mesh, {}, options.binary);
  throw FileError("(memory)", 0, -1, fmt::format("unknown volume mesh format '{}' ({})", f, kFormats));
}

void write_volume_mesh(const VolumeMesh& mesh, const std::string& path, const WriteOptions& options) {
  const std::string f = extension(path);
  if (!known(f))
    throw FileError(path, 0, -1, fmt::format("unknown volume mesh format '.{}' ({})", f, kFormats));
  const std::string data = f == "mesh"  ? io_detail::write_medit(mesh, path)
                           : f == "meshb" ? io_detail::write_meshb(mesh, path)
                           : f == "vtk" ? io_detail::write_vtk(mesh, path, options.binary)
                           : f == "msh" ? io_detail::write_msh(mesh, path)
                                        : write_volume_mesh_to_string(mesh, f, options);
  write_bytes(path, data);
}

void write_volume_vtk_with_point_data(const VolumeMesh& mesh, const std::string& path,
                                      const VertexScalars& scalars) {
  if (extension(path) == "vtu") {
    VtuFields fields;
    fields.point_scalars = scalars;
    return write_vtu(path, mesh, fields);
  }
  if (extension(path) != "vtk") throw FileError(path, 0, -1, "point data needs a VTK file (.vtk or .vtu)");
  std::string data = io_detail::write_vtk(mesh, path);
  if (!scalars.empty()) data += fmt::format("POINT_DATA {}\n", mesh.n_vertices());
  for (const auto& [name, values] : scalars) {
    if (values.size() != mesh.n_vertices())
      throw std::invalid_argument(
          fmt::format("point data '{}': {} values for {} vertices", name, values.size(), mesh.n_vertices()));
    if (name.empty() || name.find_first_of(" \t\n") != std::string::npos)
      throw std::invalid_argument(fmt::format("point data name '{}' is empty or has white space", name));
    data += fmt::format("SCALARS {} double 1\nLOOKUP_TABLE default\n", name);
    for (double v : values) data += fmt::format("{:.17g}\n", v);
  }
  write_bytes(path, data);
}

}  // namespace polydec
