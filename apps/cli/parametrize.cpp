// apps/cli/parametrize.cpp — `polydec parametrize MESH --out FILE.obj`: spectral free-boundary
// conformal parametrization (paper section 5.3), written as an OBJ with vt lines.
#include <fmt/format.h>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/applications/parametrization.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/dec/io/mesh_io.h"

namespace polydec::cli::parametrize_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, out, png, laplacian = "ours";
  bool json = false;
};

void run(const Options& o) {
  PhaseTimer timer;
  const Mesh mesh = timer.time("read", [&] { return load_mesh(o.mesh, o.repair); });
  const OperatorSet ops =
      timer.time("operators", [&] { return build_operators(mesh, parse_laplacian(o.laplacian), false); });
  const ConformalParametrization p = timer.time("solve", [&] { return spectral_conformal_parametrization(ops); });
  const Eigen::MatrixX2d uv = p.uv.topRows(ops.n_input_vertices);
  const int flipped = count_flipped_fan_triangles(mesh, refine(mesh), uv);
  const double distortion = conformal_distortion(mesh, uv);
  nlohmann::json j = {{"mesh", o.mesh},
                      {"laplacian", ops.name},
                      {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()},
                      {"boundary_loops", mesh.boundary_loops().size()},
                      {"eigenvalue", p.eigenvalue},
                      {"conformal_distortion", distortion},
                      {"flipped_fan_triangles", flipped}};
  const auto t_write = PhaseTimer::Clock::now();
  if (!o.out.empty()) {
    write_obj_with_uv(o.out, mesh, uv);
    j["out"] = o.out;
  }
  if (!o.png.empty()) {
    // The mesh laid out in the plane, coloured by the per-vertex angle distortion.
    Eigen::MatrixX3d flat = Eigen::MatrixX3d::Zero(mesh.n_vertices(), 3);
    flat.leftCols(2) = uv;
    RenderOptions ropt;
    ropt.width = 640;
    ropt.height = 480;
    ropt.scalar_label = "rad";
    ropt.title = fmt::format("conformal parametrization, angle distortion ({})", ops.name);
    ropt.colormap = Colormap::turbo;
    render_png(o.png, mesh.with_positions(flat), vertex_conformal_distortion(mesh, uv), ropt);
    j["png"] = o.png;
  }
  timer.add("write", t_write);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces, {} boundary loop(s); Laplacian {}\n", o.mesh, mesh.n_vertices(),
             mesh.n_faces(), mesh.boundary_loops().size(), ops.name);
  fmt::print("conformal distortion (area-weighted RMS corner-angle difference): {:.6g} rad\n", distortion);
  fmt::print("flipped fan triangles in uv: {}\n", flipped);
  if (!o.out.empty()) fmt::print("wrote {} (v + vt)\n", o.out);
  if (!o.png.empty()) fmt::print("wrote {}\n", o.png);
}

const RegisterCommand reg(
    "parametrize", "Spectral free-boundary conformal parametrization (paper section 5.3)", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("mesh", o->mesh, "input mesh with boundary (" + std::string(kSurfaceFormats) + ")")->required();
      app.add_option("--out", o->out, "output OBJ with vt texture coordinates");
      app.add_option("--laplacian", o->laplacian,
                     "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")));
      app.add_option("--png", o->png, "picture of the uv layout coloured by angle distortion (.png)");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      add_repair_flag(app, o->repair);
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::parametrize_command
