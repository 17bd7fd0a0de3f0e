// apps/cli/parametrize.cpp — `polydec parametrize MESH --out FILE.obj`: spectral free-boundary
// conformal parametrization (paper section 5.3), written as an OBJ with vt lines.
#include "apps/cli/command.h"
#include "apps/parametrization.h"
#include "dec/io.h"

#include <fmt/format.h>

namespace polydec::cli {
namespace {

struct Options {
  std::string mesh, out, laplacian = "ours";
  bool json = false;
};

void run(const Options& o) {
  const Mesh mesh = read_mesh(o.mesh);
  const OperatorSet ops = build_operators(mesh, parse_laplacian(o.laplacian), false);
  const ConformalParametrization p = spectral_conformal_parametrization(ops);
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
  if (!o.out.empty()) {
    write_obj_with_uv(o.out, mesh, uv);
    j["out"] = o.out;
  }
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces, {} boundary loop(s); Laplacian {}\n", o.mesh, mesh.n_vertices(),
             mesh.n_faces(), mesh.boundary_loops().size(), ops.name);
  fmt::print("conformal distortion (area-weighted RMS corner-angle difference): {:.6g} rad\n", distortion);
  fmt::print("flipped fan triangles in uv: {}\n", flipped);
  if (!o.out.empty()) fmt::print("wrote {} (v + vt)\n", o.out);
}

const RegisterCommand reg("parametrize", "Spectral free-boundary conformal parametrization (paper section 5.3)",
                          [](CLI::App& app) {
                            auto o = std::make_shared<Options>();
                            app.add_option("mesh", o->mesh, "input mesh with boundary (.obj, .off, .ply)")->required();
                            app.add_option("--out", o->out, "output OBJ with vt texture coordinates");
                            app.add_option("--laplacian", o->laplacian,
                                           "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")));
                            app.add_flag("--json", o->json, "print one JSON object instead of text");
                            app.callback([o] { run(*o); });
                          });

}  // namespace
}  // namespace polydec::cli
