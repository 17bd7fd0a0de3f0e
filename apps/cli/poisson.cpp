// apps/cli/poisson.cpp — `polydec poisson`: the convergence study of the paper's section 5.8
// (Figure 9), Franke's function on triangle, quad and hexagon grids of the unit square; with --volume
// the 3D Franke study on the shared polyhedral cubes or generated grids of the unit cube; with --order 2
// the study with quadratic elements (apps/applications/quadratic.h), L2 and H1 errors.
#include "polydec/apps/applications/poisson.h"

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "polydec/apps/applications/quadratic.h"
#include "polydec/apps/applications/volume/poisson.h"
#include "polydec/apps/cli/command.h"
#include "polydec/apps/pictures/plot.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/operators/registry/volume_laplacians.h"

namespace polydec::cli::poisson_command {
namespace {

struct Options {
  std::vector<int> resolutions{8, 16, 32, 64};
  std::string plot, png, mass = "lumped", laplacian = "ours";
  bool json = false;
  int order = 1;
  // --volume
  bool volume = false;
  std::string family = "hex", data;
  std::vector<std::string> surface_families{"triangles", "quads", "hexagons"};  // --family without --volume
  std::vector<int> levels{1, 2, 3};
};

// The 3D study: the shared cube files DIR/cube_<name>_<level>.ovm with --data, else generated grids
// (resolutions n: n^3 cubes; truncated: truncated_octahedra_volume(n)).
void run_volume(const Options& o) {
  static const std::map<std::string, std::string> files{{"hex", "cube_hexahedron"},
                                                        {"pyramids", "cube_pyramids"},
                                                        {"truncated", "cube_truncated"},
                                                        {"cuboctahedra", "cube_truncated"},
                                                        {"tetrahedra", "cube_tetrahedron"}};
  const auto it = files.find(o.family);
  if (it == files.end())
    throw UsageError("--family must be hex, pyramids, truncated, cuboctahedra or tetrahedra");
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  const bool lumped = o.mass == "lumped";
  PhaseTimer timer;  // "read": the --data files or the generated grids; "solve": the study (operators included)
  const auto t_read = PhaseTimer::Clock::now();
  std::vector<VolumeMesh> meshes;
  std::vector<std::string> labels;
  if (!o.data.empty()) {
    for (int l : o.levels) {
      const std::string name = fmt::format("{}_{}.ovm", it->second, l);
      meshes.push_back(load_volume_mesh(o.data + "/" + name));
      labels.push_back(name);
    }
  } else {
    for (int n : o.resolutions) {
      if (n < 1) throw UsageError("--resolutions must be >= 1");
      meshes.push_back(o.family == "hex"         ? hex_grid_volume(n, n, n)
                       : o.family == "pyramids"  ? pyramid_grid_volume(n, n, n)
                       : o.family == "truncated" ? truncated_octahedra_volume(n)
                       : o.family == "cuboctahedra" ? cuboctahedra_volume(n)
                                                 : tet_grid_volume(n, n, n));
      labels.push_back(fmt::format("n = {}", n));
    }
  }
  timer.add("read", t_read);
  if (meshes.size() < 2) throw UsageError("the study needs two or more levels");
  const LaplacianChoice laplacian = parse_volume_laplacian(o.laplacian);
  const VolumeConvergenceSeries s = timer.time(
      "solve", [&] { return volume_franke_convergence(o.family, meshes, labels, lumped, laplacian); });
  nlohmann::json rows = nlohmann::json::array();
  for (size_t i = 0; i < s.errors.size(); ++i) {
    const auto& e = s.errors[i];
    nlohmann::json r = {{"level", s.levels[i]},   {"vertices", e.n_vertices},
                        {"cells", e.n_cells},     {"h", e.h},
                        {"l2_error", e.l2_error}, {"rms_error", e.rms_error}};
    if (i > 0 && std::isfinite(s.l2_slopes[i - 1])) {
      r["l2_slope"] = s.l2_slopes[i - 1];
      r["rms_slope"] = s.rms_slopes[i - 1];
    }
    rows.push_back(r);
  }
  const nlohmann::json j = {{"problem", "3D Franke, Dirichlet boundary vertices, unit cube"},
                            {"family", o.family},
                            {"source", o.data.empty() ? "generated" : o.data},
                            {"mass", o.mass},
                            {"laplacian", laplacian.canonical_name()},
                            {"levels", rows},
                            {"times_ms", timer.json()}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print(
      "Poisson problem Delta f = b, 3D Franke function, Dirichlet boundary vertices, unit cube; {} ({}), {} "
      "mass, Laplacian {}\n",
      o.family, o.data.empty() ? "generated" : o.data, o.mass, laplacian.canonical_name());
  for (size_t i = 0; i < s.errors.size(); ++i) {
    const auto& e = s.errors[i];
    fmt::print("  {:24s} |V| = {:7d}  |C| = {:7d}  h = {:.5f}  L2 = {:.6e}  RMS = {:.6e}", s.levels[i],
               e.n_vertices, e.n_cells, e.h, e.l2_error, e.rms_error);
    if (i > 0 && std::isfinite(s.l2_slopes[i - 1]))
      fmt::print("  slopes {:.3f} / {:.3f}", s.l2_slopes[i - 1], s.rms_slopes[i - 1]);
    fmt::print("\n");
  }
}

// --order 2: the study with quadratic elements on four families (Galerkin mass for the load).
void run_quadratic(const Options& o) {
  PhaseTimer timer;  // "solve": the study (generated grids and operators included); "write": the plot
  const auto series = timer.time("solve", [&] { return franke_convergence_quadratic(o.resolutions); });
  nlohmann::json fam = nlohmann::json::object();
  for (const auto& s : series) {
    nlohmann::json rows = nlohmann::json::array();
    for (size_t i = 0; i < s.errors.size(); ++i)
      rows.push_back({{"n", s.resolutions[i]},
                      {"dofs", s.errors[i].n_dofs},
                      {"h", s.errors[i].h},
                      {"l2_error", s.errors[i].l2_error},
                      {"h1_error", s.errors[i].h1_error}});
    fam[s.family] = {{"l2_slope", s.l2_slope}, {"h1_slope", s.h1_slope}, {"levels", rows}};
  }
  nlohmann::json j = {{"laplacian", "quadratic"}, {"order", 2}, {"mass", "unlumped"}, {"families", fam}};
  if (!o.plot.empty()) {
    std::vector<PlotSeries> ps;
    for (const auto& s : series) {
      PlotSeries l2{s.family + " L2", {}, {}}, h1{s.family + " H1", {}, {}};
      for (const auto& e : s.errors) {
        l2.x.push_back(e.h);
        l2.y.push_back(e.l2_error);
        h1.x.push_back(e.h);
        h1.y.push_back(e.h1_error);
      }
      ps.push_back(l2);
      ps.push_back(h1);
    }
    PlotOptions popt;
    popt.title = "Poisson, Franke function, quadratic elements: errors vs h";
    popt.x_label = "h (mean edge length)";
    popt.y_label = "L2 and H1 errors";
    timer.time("write", [&] { write_plot(o.plot, ps, popt); });
    j["plot"] = o.plot;
  }
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print(
      "Poisson problem Delta f = b, Franke function, Dirichlet boundary, unit square; quadratic elements (order 2), "
      "Galerkin mass\n");
  for (const auto& s : series) {
    fmt::print("{}: fitted slopes of log(error) vs log(h): L2 {:.3f}, H1 {:.3f}\n", s.family, s.l2_slope, s.h1_slope);
    for (size_t i = 0; i < s.errors.size(); ++i)
      fmt::print("  n = {:4d}  dofs = {:7d}  h = {:.5f}  L2 error = {:.6e}  H1 error = {:.6e}\n", s.resolutions[i],
                 s.errors[i].n_dofs, s.errors[i].h, s.errors[i].l2_error, s.errors[i].h1_error);
  }
}

void run(const Options& o) {
  if (o.order != 1 && o.order != 2) throw UsageError("--order must be 1 or 2");
  if (o.order == 2) {
    if (o.volume) throw UsageError("--order 2: surface study only (volumes: docs/extensions.md)");
    if (!o.png.empty()) throw UsageError("--png: order 1 only");
    return run_quadratic(o);
  }
  if (o.volume) return run_volume(o);
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  ConvergenceOptions copt;
  copt.resolutions = o.resolutions;
  copt.lumped_mass = o.mass == "lumped";
  copt.laplacian = parse_laplacian(o.laplacian);
  copt.families = o.surface_families;
  PhaseTimer timer;  // "solve": the study (generated grids and operators included); "write": plot and picture
  const auto series = timer.time("solve", [&] { return franke_convergence(copt); });
  nlohmann::json fam = nlohmann::json::object();
  for (const auto& s : series) {
    nlohmann::json rows = nlohmann::json::array();
    for (size_t i = 0; i < s.errors.size(); ++i)
      rows.push_back({{"n", s.resolutions[i]},
                      {"vertices", s.errors[i].n_vertices},
                      {"h", s.errors[i].h},
                      {"l2_error", s.errors[i].l2_error}});
    fam[s.family] = {{"slope", s.slope}, {"levels", rows}};
  }
  nlohmann::json j = {{"laplacian", copt.laplacian.canonical_name()}, {"mass", o.mass}, {"families", fam}};
  if (!o.plot.empty()) {
    std::vector<PlotSeries> ps;
    for (const auto& s : series) {
      PlotSeries p{s.family, {}, {}};
      for (const auto& e : s.errors) {
        p.x.push_back(e.h);
        p.y.push_back(e.l2_error);
      }
      ps.push_back(p);
    }
    PlotOptions popt;
    popt.title = "Poisson, Franke function: L2 error vs h";
    popt.x_label = "h (mean edge length)";
    popt.y_label = "L2 error";
    timer.time("write", [&] { write_plot(o.plot, ps, popt); });
    j["plot"] = o.plot;
  }
  if (!o.png.empty()) {
    const auto t_write = PhaseTimer::Clock::now();
    // The error f - f* on the coarsest hexagon grid.
    const Mesh mesh = hex_grid(o.resolutions.front(), o.resolutions.front());
    const PoissonError e = franke_poisson(build_operators(mesh, copt.laplacian, false), copt.lumped_mass);
    RenderOptions ropt;
    ropt.width = 640;
    ropt.height = 480;
    ropt.scalar_label = "f - f*";
    ropt.title = fmt::format("Franke Poisson error, hexagons n = {}", o.resolutions.front());
    ropt.colormap = Colormap::turbo;
    render_png(o.png, mesh, e.solution - e.exact, ropt);
    j["png"] = o.png;
    timer.add("write", t_write);
  }
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print(
      "Poisson problem Delta f = b, Franke function, Dirichlet boundary, unit square; Laplacian {}, {} "
      "mass\n",
      copt.laplacian.canonical_name(), o.mass);
  for (const auto& s : series) {
    fmt::print("{}: fitted slope of log(L2 error) vs log(h) = {:.3f}\n", s.family, s.slope);
    for (size_t i = 0; i < s.errors.size(); ++i)
      fmt::print("  n = {:4d}  |V| = {:6d}  h = {:.5f}  L2 error = {:.6e}\n", s.resolutions[i],
                 s.errors[i].n_vertices, s.errors[i].h, s.errors[i].l2_error);
  }
}

const RegisterCommand reg(
    "poisson", "Convergence of the Poisson problem for Franke's function (paper section 5.8)",
    [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      auto* res = app.add_option(
          "--resolutions", o->resolutions,
          "grid resolutions n (n x n cells), default 8 16 32 64 (--volume: n^3 cells, 4 8 16)");
      auto* mass = app.add_option("--mass", o->mass, "lumped (default; --volume: unlumped) or unlumped mass");
      app.add_flag("--volume", o->volume, "the 3D Franke study on polyhedral meshes of the unit cube");
      auto* family = app.add_option("--family", o->family, "surface: triangles, quads, hexagons (default: all three) or sawtooth; --volume: hex (default), pyramids, truncated, cuboctahedra (generated: the structure of the "
                     "cube_truncated files) or tetrahedra");
      app.add_option("--data", o->data,
                     "--volume: folder of the cube_<family>_<level>.ovm files (else generated grids)");
      app.add_option("--levels", o->levels, "--volume --data: file levels (default 1 2 3)");
      app.add_option("--laplacian", o->laplacian,
                     "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")) +
                         " (--volume: " + fmt::format("{}", fmt::join(volume_laplacian_names(), ", ")) + ")");
      app.add_option("--plot", o->plot, "log-log plot of the error against h (.svg or .png)");
      app.add_option("--png", o->png, "picture of the error on the coarsest hexagon grid (.png)");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      app.add_option("--order", o->order,
                     "1 (default): the paper's operators; 2: quadratic elements, L2 and H1 errors, a "
                     "fourth family of non-convex polygons (Galerkin mass)");
      app.callback([o, res, mass, family] {
        if (!o->volume && family->count() > 0) o->surface_families = {o->family};
        if (o->order == 2 && (mass->count() > 0 || o->laplacian != "ours"))
          throw UsageError("--order 2 uses the quadratic operators with the Galerkin mass (no --mass, --laplacian)");
        if (o->volume && res->count() == 0) o->resolutions = {4, 8, 16};
        if (o->volume && mass->count() == 0) o->mass = "unlumped";
        run(*o);
      });
    });

}  // namespace
}  // namespace polydec::cli::poisson_command
