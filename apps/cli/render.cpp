// apps/cli/render.cpp — `polydec render MESH --png FILE [...]`: a picture of a mesh, plain or
// with a scalar field (a coordinate, or the heat-method distance from a vertex) colour-mapped,
// with isolines, polygon edges and a colour bar (apps/pictures/render.h).
#include "polydec/apps/pictures/render.h"

#include <fmt/format.h>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/applications/geodesics.h"
#include "polydec/dec/io.h"

namespace polydec::cli::render_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, png, scalar = "none", colormap = "viridis", title;
  int source = -1, isolines = -1, width = 800, height = 600;
  double spacing = 0;
  std::vector<double> view, up;
  bool perspective = false, no_edges = false, smooth = false, json = false;
};

Eigen::Vector3d vec3(const std::vector<double>& v, const char* name) {
  if (v.size() != 3) throw UsageError(fmt::format("{} needs three numbers", name));
  return {v[0], v[1], v[2]};
}

void run(const Options& o) {
  const Mesh mesh = load_mesh(o.mesh, o.repair);
  RenderOptions r;
  r.width = o.width;
  r.height = o.height;
  r.colormap = parse_colormap(o.colormap);
  r.perspective = o.perspective;
  r.edges = !o.no_edges;
  r.smooth_shading = o.smooth;
  r.title = o.title;
  if (!o.up.empty()) r.up = vec3(o.up, "--up");
  Eigen::VectorXd s;
  if (o.source >= 0) {
    if (o.scalar != "none") throw UsageError("--distance-from and --scalar exclude each other");
    s = HeatGeodesics(mesh).distance(o.source);
    r.scalar_label = "distance";
    r.isolines = 15;
    r.view_direction = view_facing_vertex(mesh, o.source, r.up);
  } else if (o.scalar == "x" || o.scalar == "y" || o.scalar == "z") {
    s = mesh.positions().col(o.scalar[0] - 'x');
    r.scalar_label = o.scalar;
  } else if (o.scalar != "none") {
    throw UsageError("--scalar must be x, y, z or none");
  }
  if (o.isolines >= 0) r.isolines = o.isolines;
  r.isoline_spacing = o.spacing;
  if (!o.view.empty()) r.view_direction = vec3(o.view, "--view");
  render_png(o.png, mesh, s, r);
  if (o.json)
    print_json({{"mesh", o.mesh}, {"png", o.png}, {"width", r.width}, {"height", r.height}});
  else
    fmt::print("wrote {}\n", o.png);
}

const RegisterCommand reg(
    "render", "Picture of a mesh (PNG), optionally with a colour-mapped scalar field", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("mesh", o->mesh, "input mesh (.obj, .off, .ply)")->required();
      app.add_option("--png", o->png, "output picture (.png)")->required();
      app.add_option("--scalar", o->scalar, "colour by a coordinate: x, y, z, or none (default)");
      app.add_option("--distance-from", o->source,
                     "colour by the heat-method geodesic distance from this vertex");
      app.add_option("--colormap", o->colormap, "viridis (default) or turbo");
      app.add_option("--isolines", o->isolines, "number of isolines (default 15 for distances, else 0)");
      app.add_option("--isoline-spacing", o->spacing, "isolines at multiples of this value instead");
      app.add_option("--view", o->view, "view direction X Y Z (default: -z, or straight at a flat mesh)")
          ->expected(3);
      app.add_option("--up", o->up, "screen-up direction X Y Z (default 0 1 0)")->expected(3);
      app.add_flag("--perspective", o->perspective, "perspective instead of orthographic projection");
      app.add_flag("--smooth", o->smooth, "smooth shading (vertex normals) instead of flat polygons");
      app.add_flag("--no-edges", o->no_edges, "do not draw the polygon edges");
      app.add_option("--title", o->title, "title printed on top");
      app.add_option("--width", o->width, "image width in pixels (default 800)");
      app.add_option("--height", o->height, "image height in pixels (default 600)");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      add_repair_flag(app, o->repair);
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::render_command
