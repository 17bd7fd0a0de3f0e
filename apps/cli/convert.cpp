// apps/cli/convert.cpp — `polydec convert IN OUT [--dual] [--subdivide N] [--unit-sphere]`:
// format conversion and the generators' transformations, applied in this order: dual, then
// N Catmull-Clark steps; with --unit-sphere every vertex is projected to the unit sphere after
// each of these steps (so `--dual --subdivide 1 --unit-sphere` on unit-sphere.off builds the
// paper's FINE SPHERE, `--dual --unit-sphere` its HEX SPHERE). Volume meshes (.ovm, .vtk, .mesh,
// .meshb, a .msh or .vtu with 3-D cells, or --volume) convert between the volume formats (written:
// .ovm, .vtk, .vtu, .mesh, .meshb, .msh), or with --boundary to their boundary surface (any surface
// format).
// --binary writes OUT in its binary form: VTK legacy BINARY (.vtk), PLY binary_little_endian
// (.ply), OFF BINARY (.off, float32 positions), inline base64 (.vtu); --compress a .vtu as appended
// raw data in zlib blocks (ParaView's default).
#include "polydec/apps/cli/command.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/io/vtu.h"

#include <fmt/format.h>

#include <cctype>

namespace polydec::cli::convert_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string in, out;
  bool dual = false, unit_sphere = false, json = false;
  int subdivide = 0;
  bool volume = false, boundary = false;  // --volume, --boundary
  bool binary = false;                    // --binary
  bool compress = false;                  // --compress
};

// The write options of OUT; --binary for a format without a binary form is a usage error.
WriteOptions write_options(const Options& o) {
  WriteOptions w;
  w.binary = o.binary;
  const std::string out = o.out.size() >= 4 ? o.out.substr(o.out.size() - 4) : o.out;
  std::string ext;
  for (char c : out) ext += char(std::tolower(static_cast<unsigned char>(c)));
  if (o.binary && ext != ".vtk" && ext != ".vtu" && ext != ".ply" && ext != ".off")
    throw UsageError(
        fmt::format("--binary: {} has no binary form here (.vtk, .vtu, .ply, .off have)", o.out));
  if (o.compress && ext != ".vtu") throw UsageError(fmt::format("--compress: {} is not a .vtu file", o.out));
  return w;
}

// Writes a surface or volume mesh to OUT: by its extension, or a compressed .vtu with --compress.
template <class M>
void write_out(const Options& o, const M& mesh) {
  const WriteOptions w = write_options(o);
  if (o.compress)
    write_vtu(o.out, mesh, {}, true, true);
  else if constexpr (std::is_same_v<M, Mesh>)
    write_mesh(o.out, mesh, {}, w);
  else
    write_volume_mesh(mesh, o.out, w);
}

// A .msh or .vtu path: either a surface or a volume (is_volume_mesh_path judges an existing file by
// its content, a new one as a volume), so OUT's kind follows from --boundary.
bool is_either_kind(const std::string& path) {
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : path;
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".msh" || ext == ".vtu";
}

void run_volume(const Options& o, const VolumeMesh& m, PhaseTimer& timer) {
  if (o.dual || o.subdivide != 0 || o.unit_sphere || o.repair)
    throw UsageError("--dual, --subdivide, --unit-sphere and --repair apply to surface meshes only");
  nlohmann::json j = {{"in", o.in}, {"out", o.out}};
  if (o.boundary) {
    if (!is_either_kind(o.out) && is_volume_mesh_path(o.out))
      throw UsageError(fmt::format("--boundary writes a surface mesh ({})", kSurfaceFormats));
    const Mesh b = m.boundary_surface();
    timer.time("write", [&] { write_out(o, b); });
    j["vertices"] = b.n_vertices();
    j["faces"] = b.n_faces();
    j["boundary"] = true;
    if (!o.json)
      fmt::print("wrote {}: boundary surface, {} vertices ({} interior ones unreferenced), {} faces\n", o.out,
                 b.n_vertices(), b.n_unreferenced_vertices(), b.n_faces());
  } else {
    if (!is_either_kind(o.out) && !is_volume_mesh_path(o.out))
      throw UsageError(fmt::format(
          "{}: a volume mesh is written as .ovm, .vtk, .vtu, .mesh, .meshb or .msh (or use --boundary)", o.out));
    timer.time("write", [&] { write_out(o, m); });
    j["vertices"] = m.n_vertices();
    j["faces"] = m.n_faces();
    j["cells"] = m.n_cells();
    if (!o.json)
      fmt::print("wrote {}: {} vertices, {} faces, {} cells\n", o.out, m.n_vertices(), m.n_faces(),
                 m.n_cells());
  }
  j["times_ms"] = timer.json();
  if (o.json) print_json(j);
}

void run(const Options& o) {
  PhaseTimer timer;
  InputMesh in = timer.time("read", [&] { return load_input_mesh(o.in, o.volume, o.repair); });
  if (in.volume) return run_volume(o, *in.volume, timer);
  if (o.boundary)
    throw UsageError(fmt::format("--boundary applies to volume meshes ({}, or --volume)", kVolumeFormats));
  if (o.subdivide < 0) throw UsageError("--subdivide takes a non-negative count");
  Mesh mesh = std::move(*in.surface);
  auto project = [&](Mesh m) { return o.unit_sphere ? project_to_unit_sphere(m) : m; };
  if (o.dual) mesh = project(dual(mesh));
  for (int k = 0; k < o.subdivide; ++k) mesh = project(catmull_clark(mesh));
  if (!o.dual && o.subdivide == 0) mesh = project(mesh);
  timer.time("write", [&] { write_out(o, mesh); });
  const nlohmann::json j = {{"in", o.in},
                            {"out", o.out},
                            {"vertices", mesh.n_vertices()},
                            {"faces", mesh.n_faces()},
                            {"times_ms", timer.json()}};
  if (o.json)
    print_json(j);
  else
    fmt::print("wrote {}: {} vertices, {} faces\n", o.out, mesh.n_vertices(), mesh.n_faces());
}

const RegisterCommand reg("convert", "Convert between formats; optionally dual, Catmull-Clark, projection to the unit sphere; volume formats and their boundary",
                          [](CLI::App& app) {
                            auto o = std::make_shared<Options>();
                            app.add_option("in", o->in, mesh_input_help())->required();
                            app.add_option("out", o->out, "output mesh (same kinds)")->required();
                            app.add_flag("--dual", o->dual, "replace the mesh by its dual (dual vertex at the face centroid)");
                            app.add_option("--subdivide", o->subdivide, "number of Catmull-Clark steps");
                            app.add_flag("--unit-sphere", o->unit_sphere, "project to the unit sphere (after each step)");
                            app.add_flag("--volume", o->volume, kVolumeFlagHelp);
                            app.add_flag("--boundary", o->boundary, "volume IN: write its boundary surface to OUT (" + std::string(kSurfaceFormats) + ")");
                            app.add_flag("--binary", o->binary,
                                         "write OUT in binary form: VTK legacy BINARY (.vtk), PLY binary (.ply), "
                                         "OFF BINARY (.off, float32), inline base64 (.vtu)");
                            app.add_flag("--compress", o->compress,
                                         "write OUT (.vtu) as appended raw data in zlib-compressed blocks, as "
                                         "ParaView does by default");
                            app.add_flag("--json", o->json, "print one JSON object instead of text");
                            add_repair_flag(app, o->repair);
                            app.callback([o] { run(*o); });
                          });

}  // namespace
}  // namespace polydec::cli::convert_command
