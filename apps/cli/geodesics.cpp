// apps/cli/geodesics.cpp — `polydec geodesics MESH --source V [...] [--source-group NAME] --out FILE.ply`: heat-method
// distances (paper section 5.5) written as a per-vertex PLY property and/or a picture (--png);
// --per-source: one distance field per source, written as a dense |V| x k Matrix Market file; on a
// volume mesh (.ovm, .vtk, .mesh or --volume) with the volume operators (operators/registry/volume_laplacians.h),
// written as VTK point data and pictured on a planar cut (apps/pictures/volume_cut.h).
#include "polydec/apps/applications/geodesics.h"

#include <fmt/format.h>

#include <cmath>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/cli/engine.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/apps/pictures/volume_cut.h"
#include "polydec/dec/io/mesh_groups.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/operators/registry/volume_laplacians.h"

namespace polydec::cli::geodesics_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, out, png;
  std::vector<int> sources;
  std::vector<std::string> source_groups;  // --source-group
  bool json = false, euclidean = false, delta_source = false, volume = false, per_source = false;
  std::string mass = "lumped", laplacian = "ours", time_step_edges = "input";
  double time_factor = 1.0;  // --time-factor
  EngineOptions engine;  // --engine, --solver, --petsc-options
};

void report(const Options& o, const LazyMesh& mesh, const std::vector<int>& sources, const Eigen::VectorXd& d,
            const std::string& laplacian, double time_step, const HeatDiagnostics& heat, const FanQuality& quality,
            const nlohmann::json* engine, PhaseTimer& timer);

// The heat step's reach into the JSON summary, and a warning (on stderr) when it fell short.
void report_heat(const Options& o, const HeatDiagnostics& heat, int n_vertices, double extent, nlohmann::json& j) {
  const double suggested = suggested_time_factor(o.time_factor, heat, extent);
  j["time_factor"] = o.time_factor;
  j["heat_unresolved_vertices"] = heat.unresolved_vertices;
  j["heat_resolved_radius"] = heat.resolved_radius;
  if (heat.unresolved_vertices == 0) return;
  j["suggested_time_factor"] = suggested;
  fmt::print(stderr,
             "polydec: warning: the heat step's solution lies below the solve's resolution at {} of {} vertices, "
             "beyond a distance of about {:.4g} from the sources (the heat decays like exp(-d / sqrt(t))): "
             "distances there are wrong. A larger time step reaches further: --time-factor {:.3g} should cover "
             "the bounding-box diagonal {:.4g} (distances near the sources get smoother)\n",
             heat.unresolved_vertices, n_vertices, heat.resolved_radius, suggested, extent);
}

// --engine petsc: the distributed run (apps/cli/engine.h); rank 0 reports as the serial run does.
void run_petsc(const Options& o) {
  PhaseTimer timer;  // the engine's phases are its own (engine.per_rank); total and write here
  if (o.laplacian != "ours") throw UsageError("--engine petsc computes the paper's Laplacian only (--laplacian ours)");
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  if (o.time_step_edges != "input" && o.time_step_edges != "operator")
    throw UsageError("--time-step-edges must be input or operator");
#ifdef POLYDEC_HAVE_PETSC
  petsc_geodesics(o.mesh, o.repair, o.sources, o.mass == "lumped", !o.delta_source, o.time_factor, o.engine,
                  [&](const EngineGeodesics& r) {
                    report(o, r.mesh, r.sources, r.distance, "ours", r.time_step, r.heat, r.quality, &r.summary, timer);
                  });
#else
  throw UsageError("--engine petsc: this polydec was built without PETSc (configure with -DPOLYDEC_WITH_PETSC=ON)");
#endif
}

// Distance statistics over the finite values: min, max, mean, number of infinite ones.
struct Stats {
  double min = INFINITY, max = -INFINITY, mean = 0;
  int unreached = 0;
};
Stats stats(const Eigen::VectorXd& d) {
  Stats st;
  double sum = 0;
  int finite = 0;
  for (int v = 0; v < d.size(); ++v)
    if (std::isfinite(d[v])) {
      st.min = std::min(st.min, d[v]);
      st.max = std::max(st.max, d[v]);
      sum += d[v];
      ++finite;
    }
  st.mean = finite ? sum / finite : 0.0;
  st.unreached = int(d.size()) - finite;
  return st;
}

// RMSE of d against the Euclidean distance from `source`, shifted to minimum 0.
double euclidean_rmse(const Eigen::MatrixX3d& X, int source, const Eigen::VectorXd& d) {
  const Eigen::VectorXd e = (X.rowwise() - X.row(source)).rowwise().norm();
  return rmse(d, e.array() - e.minCoeff());
}

// --per-source: the distance field of every source (HeatGeodesics::distances, blocks of
// right-hand sides), |file vertices| x k in file vertex order (rows of vertices --repair removed,
// and of vertices no source reaches, hold inf), written as a dense Matrix Market file.
void run_per_source(const Options& o, const HeatGeodesics& heat, const std::vector<int>& sources,
                    const std::vector<int>& vertex_map, PhaseTimer& timer) {
  const Eigen::MatrixXd D = timer.time("solve", [&] { return heat.distances(sources); });
  Eigen::MatrixXd out = Eigen::MatrixXd::Constant(long(vertex_map.size()), D.cols(), INFINITY);
  for (size_t v = 0; v < vertex_map.size(); ++v)
    if (vertex_map[v] >= 0) out.row(long(v)) = D.row(vertex_map[v]);
  timer.time("write", [&] { write_dense_matrix_market(o.out, out); });
  long unreached = 0;
  double mx = 0;
  for (long i = 0; i < out.size(); ++i) {
    if (std::isfinite(out.data()[i]))
      mx = std::max(mx, out.data()[i]);
    else
      ++unreached;
  }
  const nlohmann::json j = {{"mesh", o.mesh},
                            {"laplacian", heat.operators().name},
                            {"sources", o.sources},
                            {"per_source", true},
                            {"rows", out.rows()},
                            {"columns", out.cols()},
                            {"time_step", heat.time_step()},
                            {"max", mx},
                            {"unreached_entries", unreached},
                            {"out", o.out},
                            {"times_ms", timer.json()}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: distances from {} sources, {} x {} (max {:.6g}, {} unreached entries)\n", o.mesh,
             sources.size(), out.rows(), out.cols(), mx, unreached);
  fmt::print("wrote {} (Matrix Market array, one column per source, file vertex order)\n", o.out);
}

// A volume mesh: the volume operators, VTK point data, a picture of a cut through the centre.
void run_volume(const Options& o, const VolumeMesh& mesh, PhaseTimer& timer) {
  if (o.repair) throw UsageError("--repair applies to surface meshes only");
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  if (o.time_step_edges != "input")
    throw UsageError("--time-step-edges: volume meshes use the input's edges only");
  for (int s : o.sources)
    if (s < 0 || s >= mesh.n_vertices())
      throw std::out_of_range(
          fmt::format("source vertex {} is out of range (the mesh has {} vertices)", s, mesh.n_vertices()));
  HeatGeodesicsOptions hopt;
  hopt.lumped_mass = o.mass == "lumped";
  hopt.mass_weighted_source = !o.delta_source;
  hopt.time_step_factor = o.time_factor;
  // The operators keep their refinement for the picture (only with --png).
  OperatorSet ops = timer.time("operators", [&] {
    return build_volume_operators(mesh, parse_volume_laplacian(o.laplacian), {.keep_refinement = !o.png.empty()});
  });
  const HeatGeodesics heat = timer.time("factorization", [&] {
    return HeatGeodesics(take_operators(ops), mesh.mean_edge_length(), hopt);
  });
  const SubTetQuality& quality = heat.operators().sub_tet_quality;
  HeatDiagnostics diagnostics;
  const Eigen::VectorXd d = timer.time("solve", [&] { return heat.distance(o.sources, &diagnostics); });
  const Stats st = stats(d);
  nlohmann::json j = {{"mesh", o.mesh},
                      {"laplacian", heat.operators().name},
                      {"sources", o.sources},
                      {"time_step", heat.time_step()},
                      {"min", st.min},
                      {"max", st.max},
                      {"mean", st.mean},
                      {"unreached", st.unreached},
                      {"vertices", mesh.n_vertices()},
                      {"cells", mesh.n_cells()},
                      {"subtet_degenerate", quality.n_degenerate},
                      {"subtet_inverted", quality.n_inverted}};
  report_heat(o, diagnostics, mesh.n_vertices(), mesh.bounding_box_diagonal(), j);
  if (o.euclidean) j["rmse_vs_euclidean"] = euclidean_rmse(mesh.positions(), o.sources[0], d);
  const auto t_write = PhaseTimer::Clock::now();
  if (!o.out.empty()) {
    write_volume_vtk_with_point_data(mesh, o.out, {{"distance", d}});
    j["out"] = o.out;
  }
  if (!o.png.empty()) {
    RenderOptions ropt;
    ropt.isolines = 15;
    ropt.scalar_label = "distance";
    ropt.title = fmt::format("heat geodesics in the volume ({})", heat.operators().name);
    render_volume_cut_png(o.png, mesh, *heat.operators().volume_refinement, d,
                          centre_plane(mesh, Eigen::Vector3d::UnitZ()), ropt);
    j["png"] = o.png;
  }
  timer.add("write", t_write);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} cells (volume), time step {:.6g}\n", o.mesh, mesh.n_vertices(),
             mesh.n_cells(), heat.time_step());
  fmt::print("distance: min {:.6g}, max {:.6g}, mean {:.6g}\n", st.min, st.max, st.mean);
  if (o.euclidean)
    fmt::print("RMSE against Euclidean distance: {:.6g}\n", j["rmse_vs_euclidean"].get<double>());
  if (!o.out.empty()) fmt::print("wrote {} (VTK point data 'distance')\n", o.out);
  if (!o.png.empty()) fmt::print("wrote {}\n", o.png);
}

std::vector<int> all_sources(const Options& o, const MeshGroups& groups);

// The file read once (its groups with --source-group); the distributed engine reads it itself, so
// there only its kind is judged here.
void run(const Options& given) {
  if (given.per_source) {
    if (given.volume || given.engine.engine != "serial")
      throw UsageError("--per-source: surface meshes on the serial engine");
    if (given.out.size() < 4 || given.out.substr(given.out.size() - 4) != ".mtx")
      throw UsageError("--per-source writes a Matrix Market file: --out FILE.mtx");
    if (!given.png.empty() || given.euclidean) throw UsageError("--per-source: no --png or --euclidean");
  }
  if (given.sources.empty() && given.source_groups.empty())
    throw UsageError("geodesics needs --source V or --source-group NAME");
  Options o = given;
  if (o.engine.engine != "serial") {
    if (o.volume || is_volume_mesh_path(o.mesh))
      throw UsageError("--engine petsc: volume meshes run on the serial engine only");
    if (o.engine.engine != "petsc") throw UsageError("--engine must be serial or petsc");
    o.sources = all_sources(given, o.source_groups.empty() ? MeshGroups{} : read_mesh_groups(o.mesh));
    return run_petsc(o);
  }
  PhaseTimer timer;
  const InputMesh in =
      timer.time("read", [&] { return load_input_mesh(o.mesh, o.volume, o.repair, !o.source_groups.empty()); });
  o.sources = all_sources(given, in.groups);
  if (in.volume) {
    if (o.per_source) throw UsageError("--per-source: surface meshes on the serial engine");
    return run_volume(o, *in.volume, timer);
  }
  const Mesh& mesh = *in.surface;
  const std::vector<int>& vertex_map = in.vertex_map;
  // Sources are file vertices; --repair may renumber or remove them.
  std::vector<int> sources = o.sources;
  for (int& s : sources) {
    if (s < 0 || s >= int(vertex_map.size()))
      throw std::out_of_range(fmt::format("source vertex {} is out of range (the mesh has {} vertices)", s,
                                          vertex_map.size()));
    if (vertex_map[s] < 0) throw std::out_of_range(fmt::format("source vertex {} was removed by --repair", s));
    s = vertex_map[s];
  }
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  HeatGeodesicsOptions hopt;
  hopt.lumped_mass = o.mass == "lumped";
  hopt.mass_weighted_source = !o.delta_source;
  hopt.time_step_factor = o.time_factor;
  if (o.time_step_edges != "input" && o.time_step_edges != "operator")
    throw UsageError("--time-step-edges must be input or operator");
  OperatorSet ops = timer.time("operators", [&] {
    return build_operators(mesh, parse_laplacian(o.laplacian), {.gradient_with_refinement = false});
  });
  const double h = o.time_step_edges == "input" ? mesh.mean_edge_length() : ops.mean_edge_length;
  const HeatGeodesics heat =
      timer.time("factorization", [&] { return HeatGeodesics(take_operators(ops), h, hopt); });
  if (o.per_source) return run_per_source(o, heat, sources, vertex_map, timer);
  HeatDiagnostics diagnostics;
  const Eigen::VectorXd d = timer.time("solve", [&] { return heat.distance(sources, &diagnostics); });
  report(o, LazyMesh::of(mesh), sources, d, heat.operators().name, heat.time_step(), diagnostics,
         heat.operators().quality, nullptr, timer);
}

// The outputs of both engines: text or JSON (with the engine's summary), the PLY, the picture.
void report(const Options& o, const LazyMesh& mesh, const std::vector<int>& sources, const Eigen::VectorXd& d,
            const std::string& laplacian, double time_step, const HeatDiagnostics& heat, const FanQuality& quality,
            const nlohmann::json* engine, PhaseTimer& timer) {
  const auto t_write = PhaseTimer::Clock::now();
  const Stats st = stats(d);
  const double mn = st.min, mx = st.max;
  nlohmann::json j = {{"mesh", o.mesh},
                      {"laplacian", laplacian},
                      {"sources", o.sources},
                      {"time_step", time_step},
                      {"min", mn},
                      {"max", mx},
                      {"mean", st.mean},
                      {"unreached", st.unreached},
                      {"fan_degenerate", quality.n_degenerate},
                      {"fan_inverted", quality.n_inverted}};
  report_heat(o, heat, mesh.n_vertices, mesh.extent, j);
  if (engine) j["engine"] = *engine;
  if (o.euclidean) {
    // Error against the Euclidean distance from the first source, shifted to minimum 0 (planar meshes).
    j["rmse_vs_euclidean"] = euclidean_rmse(mesh.get().positions(), sources[0], d);
  }
  if (!o.out.empty()) {
    write_mesh(o.out, mesh.get(), {{"distance", d}});
    j["out"] = o.out;
  }
  if (!o.png.empty()) {
    RenderOptions ropt;
    ropt.isolines = 15;
    ropt.scalar_label = "distance";
    ropt.title = fmt::format("heat geodesics ({})", laplacian);
    ropt.view_direction = view_facing_vertex(mesh.get(), sources[0]);
    render_png(o.png, mesh.get(), d, ropt);
    j["png"] = o.png;
  }
  timer.add("write", t_write);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces, time step {:.6g}\n", o.mesh, mesh.n_vertices, mesh.n_faces, time_step);
  if (engine)
    fmt::print("engine petsc: {} ranks, solver {}\n", (*engine)["ranks"].get<int>(),
               (*engine)["solver"].get<std::string>());
  fmt::print("distance: min {:.6g}, max {:.6g}, mean {:.6g}\n", mn, mx, st.mean);
  if (o.euclidean) fmt::print("RMSE against Euclidean distance: {:.6g}\n", j["rmse_vs_euclidean"].get<double>());
  if (!o.out.empty()) fmt::print("wrote {} (property 'distance')\n", o.out);
  if (!o.png.empty()) fmt::print("wrote {}\n", o.png);
}

// --source and the vertices of every --source-group (the file's named vertex sets, e.g. gmsh
// physical groups; dec/io/mesh_groups.h), file vertex indices.
std::vector<int> all_sources(const Options& o, const MeshGroups& groups) {
  std::vector<int> sources = o.sources;
  if (!o.source_groups.empty()) {
    for (const std::string& name : o.source_groups) {
      const auto it = groups.vertices.find(name);
      if (it == groups.vertices.end()) {
        std::vector<std::string> names;
        for (const auto& [n, vs] : groups.vertices) names.push_back("'" + n + "'");
        throw UsageError(fmt::format("--source-group: {} has no group '{}' ({})", o.mesh, name,
                                     names.empty() ? "it has no groups" : "groups " + fmt::format("{}", fmt::join(names, ", "))));
      }
      sources.insert(sources.end(), it->second.begin(), it->second.end());
    }
  }
  if (sources.empty()) throw UsageError("geodesics needs --source V or --source-group NAME");
  return sources;
}

const RegisterCommand reg("geodesics", "Geodesic distances by the heat method (paper section 5.5)", [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("mesh", o->mesh, mesh_input_help())->required();
  app.add_option("--source", o->sources, "source vertex (0-based; repeat for several)");
  app.add_option("--source-group", o->source_groups,
                 "every vertex of this named group of the file (gmsh physical group) is a source; repeatable, "
                 "combines with --source");
  app.add_option("--out", o->out,
                 "output mesh with a 'distance' vertex property (.ply or .vtu; volumes: .vtk with POINT_DATA "
                 "'distance', or .vtu with point data 'distance')");
  app.add_option(
      "--png", o->png,
      "picture of the distance with isolines and a colour bar (.png; volumes: the solid cut by the plane "
      "z = centre, front half removed)");
  app.add_option("--mass", o->mass, "lumped (default) or unlumped mass in the heat step");
  app.add_option("--time-factor", o->time_factor,
                 "time step t = factor x (mean edge length)^2 (default 1, the paper's); larger reaches further "
                 "(meshes more than ~650 edges across need it; the run suggests a value when needed)")
      ->check(CLI::PositiveNumber);
  app.add_option("--laplacian", o->laplacian,
                 "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")) +
                     " (volumes: " + fmt::format("{}", fmt::join(volume_laplacian_names(), ", ")) + ")");
  app.add_flag("--volume", o->volume, kVolumeFlagHelp);
  app.add_flag("--delta-source", o->delta_source,
               "heat step (M - t S) u = delta instead of M delta (as the paper authors' program; matters with --mass unlumped)");
  app.add_option("--time-step-edges", o->time_step_edges,
                 "mean edge length of the time step: input (default; the polygon mesh) or operator (the operator's mesh, "
                 "e.g. a triangulation's, as libigl)");
  app.add_flag("--euclidean", o->euclidean, "also report the RMSE against the Euclidean distance (planar meshes)");
  app.add_flag("--per-source", o->per_source,
               "one distance field per source (not the distance to the set): --out FILE.mtx gets the |V| x k "
               "distances (Matrix Market array, one column per --source, file vertex order)");
  app.add_flag("--json", o->json, "print one JSON object instead of text (with the phases' times, times_ms)");
  add_repair_flag(app, o->repair);
  add_engine_options(app, o->engine);
  app.callback([o] { run(*o); });
});

}  // namespace
}  // namespace polydec::cli::geodesics_command
