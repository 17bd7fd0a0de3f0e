// apps/cli/convert.cpp — `polydec convert IN OUT [--dual] [--subdivide N] [--unit-sphere]`:
// format conversion and the generators' transformations, applied in this order: dual, then
// N Catmull-Clark steps; with --unit-sphere every vertex is projected to the unit sphere after
// each of these steps (so `--dual --subdivide 1 --unit-sphere` on unit-sphere.off builds the
// paper's FINE SPHERE, `--dual --unit-sphere` its HEX SPHERE).
#include "polydec/apps/cli/command.h"
#include "polydec/dec/generators.h"
#include "polydec/dec/io.h"

#include <fmt/format.h>

namespace polydec::cli::convert_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string in, out;
  bool dual = false, unit_sphere = false, json = false;
  int subdivide = 0;
};

void run(const Options& o) {
  if (o.subdivide < 0) throw UsageError("--subdivide takes a non-negative count");
  Mesh mesh = load_mesh(o.in, o.repair);
  auto project = [&](Mesh m) { return o.unit_sphere ? project_to_unit_sphere(m) : m; };
  if (o.dual) mesh = project(dual(mesh));
  for (int k = 0; k < o.subdivide; ++k) mesh = project(catmull_clark(mesh));
  if (!o.dual && o.subdivide == 0) mesh = project(mesh);
  write_mesh(o.out, mesh);
  const nlohmann::json j = {{"in", o.in}, {"out", o.out}, {"vertices", mesh.n_vertices()}, {"faces", mesh.n_faces()}};
  if (o.json)
    print_json(j);
  else
    fmt::print("wrote {}: {} vertices, {} faces\n", o.out, mesh.n_vertices(), mesh.n_faces());
}

const RegisterCommand reg("convert", "Convert between formats; optionally dual, Catmull-Clark, projection to the unit sphere",
                          [](CLI::App& app) {
                            auto o = std::make_shared<Options>();
                            app.add_option("in", o->in, "input mesh (.obj, .off, .ply)")->required();
                            app.add_option("out", o->out, "output mesh (.obj, .off, .ply)")->required();
                            app.add_flag("--dual", o->dual, "replace the mesh by its dual (dual vertex at the face centroid)");
                            app.add_option("--subdivide", o->subdivide, "number of Catmull-Clark steps");
                            app.add_flag("--unit-sphere", o->unit_sphere, "project to the unit sphere (after each step)");
                            app.add_flag("--json", o->json, "print one JSON object instead of text");
                            add_repair_flag(app, o->repair);
                            app.callback([o] { run(*o); });
                          });

}  // namespace
}  // namespace polydec::cli::convert_command
