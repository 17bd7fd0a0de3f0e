// apps/cli/smooth.cpp — `polydec smooth MESH --steps N --dt T --out DIR`: conformalized mean
// curvature flow (paper section 5.1, eq. 28), writing the mesh after every step.
#include <fmt/format.h>

#include <filesystem>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/applications/curvature.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/apps/applications/smoothing.h"
#include "polydec/dec/io/mesh_io.h"

namespace polydec::cli::smooth_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, out, png, mass = "lumped", laplacian = "ours", format = "obj";
  int steps = 10;
  double dt = 0;
  bool json = false;
};

// Relative spread of the distances to the area centroid (the origin after each step):
// standard deviation / mean.
double sphericity_spread(const Mesh& m) {
  const Eigen::VectorXd r = m.positions().rowwise().norm();
  const double mean = r.mean();
  return std::sqrt((r.array() - mean).square().mean()) / mean;
}

void run(const Options& o) {
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  if (o.steps < 0) throw UsageError("--steps must be >= 0");
  if (o.format != "obj" && o.format != "off" && o.format != "ply")
    throw UsageError("--format must be obj, off or ply");
  PhaseTimer timer;
  const Mesh mesh = timer.time("read", [&] { return load_mesh(o.mesh, o.repair); });
  SmoothingOptions sopt;
  sopt.time_step = o.dt;
  sopt.lumped_mass = o.mass == "lumped";
  CurvatureFlow flow = timer.time("operators", [&] { return CurvatureFlow(mesh, sopt, parse_laplacian(o.laplacian)); });
  if (!o.out.empty()) std::filesystem::create_directories(o.out);
  nlohmann::json steps = nlohmann::json::array();
  for (int i = 1; i <= o.steps; ++i) {
    const Mesh& m = timer.time("solve", [&]() -> const Mesh& { return flow.step(); });
    nlohmann::json s = {{"step", i}, {"radius_spread", sphericity_spread(m)}};
    if (!o.out.empty()) {
      const std::string p = fmt::format("{}/step_{:03d}.{}", o.out, i, o.format);
      timer.time("write", [&] { write_mesh(p, m); });
      s["file"] = p;
    }
    steps.push_back(s);
  }
  const bool png = !o.png.empty();
  nlohmann::json j = {{"mesh", o.mesh},      {"laplacian", flow.laplacian_name()},
                      {"mass", o.mass},      {"time_step", flow.time_step()},
                      {"area", flow.area()}, {"steps", steps}};
  if (png) {
    // The last mesh coloured by its mean curvature (Figure 5), with the input's Laplacian.
    const auto t_write = PhaseTimer::Clock::now();
    const Mesh& m = flow.mesh();
    const Eigen::VectorXd H = mean_curvature(build_operators(m, parse_laplacian(o.laplacian), false));
    RenderOptions ropt;
    ropt.width = 640;
    ropt.height = 480;
    ropt.scalar_label = "H";
    ropt.title = fmt::format("curvature flow, {} steps, eps {:.3g}", o.steps, flow.time_step());
    render_png(o.png, m, H, ropt);
    j["png"] = o.png;
    timer.add("write", t_write);
  }
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; Laplacian {}, {} mass, eps {:.6g}, area {:.6g}\n", o.mesh,
             mesh.n_vertices(), mesh.n_faces(), flow.laplacian_name(), o.mass, flow.time_step(), flow.area());
  if (png) fmt::print("wrote {}\n", o.png);
  for (const auto& s : steps)
    fmt::print("  step {:3d}: radius spread (std/mean of |x - centroid|) {:.6g}{}\n", s["step"].get<int>(),
               s["radius_spread"].get<double>(),
               s.contains("file") ? "  -> " + s["file"].get<std::string>() : "");
}

const RegisterCommand reg(
    "smooth", "Conformalized mean curvature flow (paper section 5.1, eq. 28)", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("mesh", o->mesh, mesh_input_help(false))->required();
      app.add_option("--steps", o->steps, "number of implicit steps (default 10)");
      app.add_option("--dt", o->dt, "time step eps (units of area); default 1e-3 * surface area");
      app.add_option("--out", o->out, "output directory: step_001.obj, step_002.obj, ...");
      app.add_option("--format", o->format, "output format: obj (default), off, ply");
      app.add_option("--mass", o->mass, "lumped (default) or unlumped mass M^t");
      app.add_option("--laplacian", o->laplacian,
                     "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")));
      app.add_option("--png", o->png, "picture of the last mesh coloured by its mean curvature (.png)");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      add_repair_flag(app, o->repair);
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::smooth_command
