// apps/cli/poisson.cpp — `polydec poisson`: the convergence study of the paper's section 5.8
// (Figure 9), Franke's function on triangle, quad and hexagon grids of the unit square.
#include "polydec/apps/applications/poisson.h"

#include <fmt/format.h>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/pictures/plot.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/dec/generators.h"

namespace polydec::cli::poisson_command {
namespace {

struct Options {
  std::vector<int> resolutions{8, 16, 32, 64};
  std::string plot, png, mass = "lumped", laplacian = "ours";
  bool json = false;
};

void run(const Options& o) {
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  ConvergenceOptions copt;
  copt.resolutions = o.resolutions;
  copt.lumped_mass = o.mass == "lumped";
  copt.laplacian = parse_laplacian(o.laplacian);
  const auto series = franke_convergence(copt);
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
    write_plot(o.plot, ps, popt);
    j["plot"] = o.plot;
  }
  if (!o.png.empty()) {
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
  }
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
      app.add_option("--resolutions", o->resolutions, "grid resolutions n (n x n cells), default 8 16 32 64");
      app.add_option("--mass", o->mass, "lumped (default) or unlumped mass");
      app.add_option("--laplacian", o->laplacian,
                     "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")));
      app.add_option("--plot", o->plot, "log-log plot of the error against h (.svg or .png)");
      app.add_option("--png", o->png, "picture of the error on the coarsest hexagon grid (.png)");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::poisson_command
