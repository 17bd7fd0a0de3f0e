// apps/cli/command.cpp — shared CLI helpers: loading a mesh with the opt-in `--repair`, loading a
// volume mesh, the phases' times of --json.
#include "polydec/apps/cli/command.h"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <stdexcept>

#include "polydec/dec/io/mesh_groups.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/repair.h"

namespace polydec::cli {

GlobalOptions& global_options() {
  static GlobalOptions options;
  return options;
}

namespace load_detail {

// The mesh (surface or volume) with the user's planarity tolerance, if one was given.
template <class AnyMesh>
AnyMesh with_global_options(AnyMesh mesh) {
  const double t = global_options().planarity_tolerance;
  if (t <= 0) return mesh;
  CoordinatePrecision p = mesh.precision();
  p.planarity_tolerance = t;
  return mesh.with_precision(p);
}

}  // namespace load_detail

namespace load_detail {

// The mesh of a file's polygons after the opt-in repair steps (load_mesh).
Mesh repaired(const std::string& path, PolygonSoup soup, std::vector<int>* vertex_map) {
  RepairOptions options;
  options.merge_vertices = true;  // exactly coincident vertices only (tolerance 0)
  const RepairReport report = repair(soup, options);
  for (const std::string& line : report.summary()) fmt::print(stderr, "polydec: --repair {}: {}\n", path, line);
  if (vertex_map) *vertex_map = report.vertex_map;
  try {
    return with_global_options(Mesh(std::move(soup)));
  } catch (const InvalidMeshError& e) {
    throw InvalidMeshError(e.element, e.index, fmt::format("{}: still invalid after --repair: {}", path, e.what()));
  }
}

// 0, 1, ..., n - 1.
std::vector<int> identity_map(int n) {
  std::vector<int> map(static_cast<size_t>(n));
  for (int v = 0; v < n; ++v) map[size_t(v)] = v;
  return map;
}

}  // namespace load_detail

Mesh load_mesh(const std::string& path, bool repair_first, std::vector<int>* vertex_map) {
  global_options().last_input = path;
  if (!repair_first) {
    const Mesh mesh = load_detail::with_global_options(read_mesh(path));
    if (vertex_map) *vertex_map = load_detail::identity_map(mesh.n_vertices());
    return mesh;
  }
  return load_detail::repaired(path, read_polygon_soup(path), vertex_map);
}

VolumeMesh load_volume_mesh(const std::string& path, VolumeReadNotes* notes) {
  global_options().last_input = path;
  return load_detail::with_global_options(read_volume_mesh(path, notes));
}

InputMesh load_input_mesh(const std::string& path, bool volume, bool repair_first, bool groups) {
  global_options().last_input = path;
  MeshFileOptions options;
  options.volume = volume;
  options.validate_surface = !repair_first;
  options.groups = groups;
  InputMesh in;
  static_cast<MeshFile&>(in) = read_mesh_file(path, options);
  if (in.volume) {
    in.volume = load_detail::with_global_options(std::move(*in.volume));
  } else if (in.soup) {
    in.surface = load_detail::repaired(path, std::move(*in.soup), &in.vertex_map);
    in.soup.reset();
  } else {
    in.surface = load_detail::with_global_options(std::move(*in.surface));
    in.vertex_map = load_detail::identity_map(in.surface->n_vertices());
  }
  return in;
}

void PhaseTimer::check_phase(const char* phase) {
  static const char* const kPhases[] = {"read",       "generate", "operators", "factorization", "solve",
                                         "statistics", "evaluation", "render", "write"};
  if (std::find_if(std::begin(kPhases), std::end(kPhases), [&](const char* p) { return std::string(p) == phase; }) ==
      std::end(kPhases))
    throw std::logic_error(fmt::format("PhaseTimer: unknown phase '{}'", phase));
}

void PhaseTimer::add(const char* phase, Clock::time_point start) {
  check_phase(phase);
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  for (auto& [name, total] : ms_)
    if (name == phase) {
      total += ms;
      return;
    }
  ms_.emplace_back(phase, ms);
}

nlohmann::json PhaseTimer::json() const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, ms] : ms_) j[name] = ms;
  j["total"] = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  return j;
}

void add_repair_flag(CLI::App& app, bool& flag) {
  app.add_flag("--repair", flag,
               "repair the mesh first (merge coincident vertices, drop invalid and duplicate faces, remove "
               "unreferenced vertices; what changed goes to stderr); vertex indices are the repaired mesh's");
}

}  // namespace polydec::cli
