// apps/cli/harmonics.cpp — `polydec harmonics MESH`: how far the spherical harmonics are from
// being eigenvectors of the Laplacian (paper section 5.4, eq. 30, Table 3).
#include "polydec/apps/applications/harmonics.h"

#include <fmt/format.h>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/cli/virtual_lift.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"

namespace polydec::cli::harmonics_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, png, mass = "lumped", laplacian = "ours";
  VirtualLiftArgs lift;
  bool json = false, keep_positions = false;
};

void run(const Options& o) {
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  PhaseTimer timer;
  Mesh mesh = timer.time("read", [&] { return load_mesh(o.mesh, o.repair); });
  if (!o.keep_positions) mesh = project_to_unit_sphere(mesh);
  OperatorOptions oopt;
  oopt.with_gradient = false;
  oopt.lift = virtual_lift(o.lift, mesh);
  const OperatorSet ops =
      timer.time("operators", [&] { return build_operators(mesh, parse_laplacian(o.laplacian), oopt); });
  HarmonicsOptions hopt;
  hopt.max_band = 9;
  hopt.lumped_mass = o.mass == "lumped";
  const HarmonicsError e = timer.time("solve", [&] { return spherical_harmonics_error(ops, hopt); });
  nlohmann::json j = {{"mesh", o.mesh},
                      {"laplacian", ops.name},
                      {"mass", o.mass},
                      {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()},
                      {"projected_to_unit_sphere", !o.keep_positions},
                      {"band_error", e.band_error},
                      {"error_l1_8", e.sum(8)},
                      {"error_l1_9", e.sum(9)}};
  const auto t_write = PhaseTimer::Clock::now();
  if (!o.png.empty()) {
    // Error density: each vertex's share of eq. (30) summed over l = 1..9, per unit area.
    Eigen::VectorXd density = Eigen::VectorXd::Zero(e.vertex_error.size());
    for (int v = 0; v < density.size(); ++v)
      if (ops.M_lumped[v] > 0) density[v] = e.vertex_error[v] / ops.M_lumped[v];
    RenderOptions ropt;
    ropt.width = 640;
    ropt.height = 480;
    ropt.scalar_label = "err/area";
    ropt.title = fmt::format("eq. (30) error per area, l = 1..9 ({}, {} mass)", ops.name, o.mass);
    ropt.colormap = Colormap::turbo;
    render_png(o.png, mesh, density.head(ops.n_input_vertices), ropt);
    j["png"] = o.png;
    timer.add("write", t_write);
  }
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; Laplacian {}, {} mass{}\n", o.mesh, mesh.n_vertices(),
             mesh.n_faces(), ops.name, o.mass, o.keep_positions ? "" : ", projected to the unit sphere");
  for (int l = 1; l <= 9; ++l) fmt::print("  band l = {}: {:.6g}\n", l, e.band_error[l - 1]);
  fmt::print("error, l = 1..8 (authors' program): {:.6g}\n", e.sum(8));
  fmt::print("error, l = 1..9 (paper's caption):  {:.6g}\n", e.sum(9));
  if (!o.png.empty()) fmt::print("wrote {}\n", o.png);
}

const RegisterCommand reg(
    "harmonics", "Spherical-harmonics reproduction error of the Laplacian (paper section 5.4, eq. 30)",
    [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("mesh", o->mesh, "input mesh of a sphere (" + std::string(kSurfaceFormats) + ")")->required();
      app.add_option("--mass", o->mass, "lumped (default) or unlumped mass, in L = M^-1 S and in the norm");
      app.add_option("--laplacian", o->laplacian,
                     "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")));
      app.add_flag("--keep-positions", o->keep_positions,
                   "do not project the vertices to the unit sphere first (they should lie on it)");
      app.add_option("--png", o->png,
                     "picture of where the error sits (per-vertex share per unit area) (.png)");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      add_virtual_lift_options(app, o->lift);
      add_repair_flag(app, o->repair);
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::harmonics_command
