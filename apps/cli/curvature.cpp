// apps/cli/curvature.cpp — `polydec curvature MESH [--unit-sphere] [--mass unlumped] [--out FILE.ply]`:
// mean curvature from eq. (29) (paper section 5.2, Table 2).
#include "polydec/apps/applications/curvature.h"

#include <fmt/format.h>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/cli/virtual_lift.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"

namespace polydec::cli::curvature_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, out, png, mass = "lumped", laplacian = "ours";
  VirtualLiftArgs lift;
  bool json = false, unit_sphere = false;
};

void run(const Options& o) {
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  PhaseTimer timer;
  Mesh mesh = timer.time("read", [&] { return load_mesh(o.mesh, o.repair); });
  if (o.unit_sphere) mesh = project_to_unit_sphere(mesh);
  OperatorOptions oopt;
  oopt.with_gradient = false;
  oopt.lift = virtual_lift(o.lift, mesh);
  const OperatorSet ops =
      timer.time("operators", [&] { return build_operators(mesh, parse_laplacian(o.laplacian), oopt); });
  CurvatureOptions copt;
  copt.lumped_mass = o.mass == "lumped";
  const Eigen::VectorXd H =
      timer.time("solve", [&] { return Eigen::VectorXd(mean_curvature(ops, copt).head(ops.n_input_vertices)); });
  nlohmann::json j = {{"mesh", o.mesh},          {"laplacian", ops.name},
                      {"mass", o.mass},          {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()}, {"min", H.minCoeff()},
                      {"max", H.maxCoeff()},     {"mean", H.mean()}};
  if (o.unit_sphere) j["rmse_vs_unit_sphere"] = curvature_rmse(H, 1.0);
  const auto t_write = PhaseTimer::Clock::now();
  if (!o.out.empty()) {
    write_mesh(o.out, mesh, {{"mean_curvature", H}});
    j["out"] = o.out;
  }
  if (!o.png.empty()) {
    RenderOptions ropt;
    ropt.width = 640;
    ropt.height = 480;
    ropt.scalar_label = "H";
    ropt.title = fmt::format("mean curvature ({}, {} mass)", ops.name, o.mass);
    ropt.smooth_shading = true;
    render_png(o.png, mesh, H, ropt);
    j["png"] = o.png;
  }
  timer.add("write", t_write);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; Laplacian {}, {} mass{}\n", o.mesh, mesh.n_vertices(),
             mesh.n_faces(), ops.name, o.mass, o.unit_sphere ? ", projected to the unit sphere" : "");
  fmt::print("mean curvature: min {:.6g}, max {:.6g}, mean {:.6g}\n", H.minCoeff(), H.maxCoeff(), H.mean());
  if (o.unit_sphere)
    fmt::print("RMSE against 1 (unit sphere): {:.6g}\n", j["rmse_vs_unit_sphere"].get<double>());
  if (!o.out.empty()) fmt::print("wrote {} (property 'mean_curvature')\n", o.out);
  if (!o.png.empty()) fmt::print("wrote {}\n", o.png);
}

const RegisterCommand reg(
    "curvature", "Mean curvature from the Laplacian of the coordinates (paper section 5.2)",
    [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("mesh", o->mesh, mesh_input_help(false))->required();
      app.add_flag("--unit-sphere", o->unit_sphere,
                   "project the vertices to the unit sphere first and report the RMSE against 1");
      app.add_option("--mass", o->mass, "lumped (default) or unlumped mass in L = M^-1 S");
      app.add_option("--laplacian", o->laplacian,
                     "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")));
      app.add_option("--out", o->out, "output mesh with a 'mean_curvature' vertex property (.ply)");
      app.add_option("--png", o->png, "picture of the mean curvature with a colour bar (.png)");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      add_virtual_lift_options(app, o->lift);
      add_repair_flag(app, o->repair);
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::curvature_command
