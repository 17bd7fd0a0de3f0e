// apps/cli/command.h — the polydec subcommand registry and shared CLI helpers. Each
// subcommand lives in its own file apps/cli/<name>.cpp and registers itself with a static
// RegisterCommand object.
#pragma once

#include <CLI/CLI.hpp>
#include <chrono>
#include <functional>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "polydec/dec/io/mesh_groups.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec::cli {

// Exit codes of the polydec program.
enum ExitCode : int { kOk = 0, kInternalError = 1, kUsageError = 2, kBadInput = 3, kSolverFailure = 4 };

// A subcommand: `setup` adds its options to `app` and sets a callback that does the work.
// The callback returns normally on success and throws on failure (mapped to exit codes in main).
struct Command {
  std::string name;
  std::string description;
  std::function<void(CLI::App& app)> setup;
};

std::vector<Command>& registry();

struct RegisterCommand {
  RegisterCommand(std::string name, std::string description, std::function<void(CLI::App&)> setup) {
    registry().push_back({std::move(name), std::move(description), std::move(setup)});
  }
};

// Prints a JSON object on stdout (one line per object, pretty with 2 spaces).
void print_json(const nlohmann::json& j);

// Reads the mesh at `path` (with the --planarity-tolerance of global_options() applied). With `repair_first`,
// the opt-in repair steps of dec/mesh/repair.h run on the file's polygons before validation (coincident vertices
// merged exactly, invalid and duplicate faces dropped, unreferenced vertices removed), one stderr line per
// step that changed something; `vertex_map` (if given) receives file vertex -> mesh vertex (-1 when removed).
Mesh load_mesh(const std::string& path, bool repair_first, std::vector<int>* vertex_map = nullptr);

// Reads the volume mesh at `path` (.ovm, .vtk, .vtu or .mesh by extension; dec/io/volume_io.h), with
// the global --planarity-tolerance as its precision's planarity_tolerance when one is given; `notes`
// receives what the reader skipped. Throws FileError (exit code 3) for an unreadable or invalid file.
VolumeMesh load_volume_mesh(const std::string& path, VolumeReadNotes* notes = nullptr);

// A command's input mesh, read and parsed once (read_mesh_file, dec/io/mesh_groups.h): a volume mesh
// (with `volume`, or when the file's name or content says so: is_volume_mesh_path) as load_volume_mesh
// reads it, else a surface as load_mesh reads it (with `repair_first`, repaired; vertex_map: file vertex
// -> mesh vertex, -1 when removed). With `groups`, the file's groups (gmsh, MEDIT) are read too.
// The MeshFile with the global --planarity-tolerance applied and never a soup: with `repair_first`
// the file's polygons are repaired into `surface`.
struct InputMesh : MeshFile {
  std::vector<int> vertex_map;  // surfaces only
};
InputMesh load_input_mesh(const std::string& path, bool volume, bool repair_first, bool groups = false);

// Options given before (or, by fall-through, after) the subcommand, for every command.
struct GlobalOptions {
  // --planarity-tolerance: > 0 overrides the coordinate precision that load_mesh() records,
  // so that a face whose out-of-plane extent is at most this fraction of its size counts as planar.
  double planarity_tolerance = 0.0;
  // The mesh file read last (load_mesh, load_volume_mesh): an InvalidMeshError raised after reading
  // (an operator the mesh's scale cannot hold, say) is reported with it.
  std::string last_input;
};
GlobalOptions& global_options();

// The formats the commands read, for help texts: surfaces, and volumes (a .msh or .vtu file is a
// volume when it holds 3-D cells).
inline constexpr const char* kSurfaceFormats = ".obj, .off, .ply, .msh, .vtu";
inline constexpr const char* kVolumeFormats = ".ovm, .vtk, .mesh, .meshb, .msh, .vtu";
inline constexpr const char* kVolumeFlagHelp =
    "read the file as a volume mesh (implied by .ovm, .vtk, .mesh, .meshb, and by .msh and .vtu files with 3-D "
    "cells)";
// "input mesh (SURFACES; volumes: VOLUMES)", or surfaces only.
inline std::string mesh_input_help(bool volumes = true) {
  return std::string("input mesh (") + kSurfaceFormats + (volumes ? std::string("; volumes: ") + kVolumeFormats : "") +
         ")";
}

// Adds the `--repair` flag (see load_mesh) to a subcommand.
void add_repair_flag(CLI::App& app, bool& flag);

// Thrown for wrong command-line usage detected after parsing (exit code 2).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Wall times of a command's phases, reported by every --json as "times_ms": milliseconds of the
// phases that happened, named read, generate (a built-in mesh instead of a file), operators
// (refinement and assembly), factorization, solve (all solves), statistics (mesh measures),
// evaluation (a whole experiment suite), render (pictures, their files included), write, and total
// (from the timer's construction to json(), so at least their sum). A phase timed twice adds up;
// another name is an internal error (std::logic_error).
class PhaseTimer {
 public:
  using Clock = std::chrono::steady_clock;

  // Runs f() and adds its wall time to `phase`; returns what f returns.
  template <class F>
  decltype(auto) time(const char* phase, F&& f) {
    check_phase(phase);
    const Stop stop{*this, phase, Clock::now()};
    return std::forward<F>(f)();
  }

  // Adds the time since `start` to `phase`.
  void add(const char* phase, Clock::time_point start);

  // {"read": ms, ..., "total": ms}.
  nlohmann::json json() const;

 private:
  static void check_phase(const char* phase);
  struct Stop {
    PhaseTimer& timer;
    const char* phase;
    Clock::time_point start;
    ~Stop() { timer.add(phase, start); }
  };
  Clock::time_point start_ = Clock::now();
  std::vector<std::pair<std::string, double>> ms_;
};

// parse(text) of an option's value, its std::invalid_argument turned into a UsageError (exit 2).
template <class Parse>
auto parse_option(Parse parse, const std::string& text) {
  try {
    return parse(text);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace polydec::cli
