// apps/cli/render.cpp — `polydec render MESH --png FILE [...]`: a picture of a mesh, plain or
// with a scalar field (a coordinate, or the heat-method distance from a vertex) colour-mapped,
// with isolines, polygon edges and a colour bar (apps/pictures/render.h). A volume mesh (.ovm, .vtk,
// .mesh or --volume) is drawn as its boundary cut by a plane, front half removed, the section coloured
// (apps/pictures/volume_cut.h).
#include "polydec/apps/pictures/render.h"

#include <fmt/format.h>

#include "polydec/apps/applications/geodesics.h"
#include "polydec/apps/cli/command.h"
#include "polydec/apps/pictures/volume_cut.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/operators/registry/volume_laplacians.h"

namespace polydec::cli::render_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, png, scalar = "none", colormap = "viridis", title;
  int source = -1, isolines = -1, width = 800, height = 600;
  double spacing = 0;
  std::vector<double> view, up;
  bool perspective = false, no_edges = false, smooth = false, json = false;
  // Volume meshes.
  bool volume = false;
  std::vector<double> cut_plane;
  std::string cut_axis = "z", laplacian = "ours";
};

Eigen::Vector3d vec3(const std::vector<double>& v, const char* name) {
  if (v.size() != 3) throw UsageError(fmt::format("{} needs three numbers", name));
  return {v[0], v[1], v[2]};
}

// The picture options shared by surfaces and volumes.
RenderOptions picture_options(const Options& o) {
  RenderOptions r;
  r.width = o.width;
  r.height = o.height;
  r.colormap = parse_colormap(o.colormap);
  r.perspective = o.perspective;
  r.edges = !o.no_edges;
  r.smooth_shading = o.smooth;
  r.title = o.title;
  if (!o.up.empty()) r.up = vec3(o.up, "--up");
  return r;
}

// --scalar x|y|z: that coordinate of every vertex (label set in r); none: empty.
Eigen::VectorXd coordinate_scalar(const Options& o, const Eigen::MatrixX3d& X, RenderOptions& r) {
  if (o.scalar == "none") return {};
  if (o.scalar != "x" && o.scalar != "y" && o.scalar != "z")
    throw UsageError("--scalar must be x, y, z or none");
  r.scalar_label = o.scalar;
  return X.col(o.scalar[0] - 'x');
}

// The options given after the scalar's defaults: --isolines, --isoline-spacing, --view.
void finish_options(const Options& o, RenderOptions& r) {
  if (o.isolines >= 0) r.isolines = o.isolines;
  r.isoline_spacing = o.spacing;
  if (!o.view.empty()) r.view_direction = vec3(o.view, "--view");
}

// A volume mesh: the solid behind the cut plane, the scalar on the section and the boundary.
void run_volume(const Options& o, const VolumeMesh& mesh, PhaseTimer& timer) {
  if (o.repair) throw UsageError("--repair applies to surface meshes only");
  RenderOptions r = picture_options(o);
  CutPlane plane;
  if (!o.cut_plane.empty()) {
    if (o.cut_plane.size() != 6) throw UsageError("--cut-plane needs six numbers: PX PY PZ NX NY NZ");
    plane.point = {o.cut_plane[0], o.cut_plane[1], o.cut_plane[2]};
    plane.normal = {o.cut_plane[3], o.cut_plane[4], o.cut_plane[5]};
  } else {
    if (o.cut_axis.size() != 1 || o.cut_axis[0] < 'x' || o.cut_axis[0] > 'z')
      throw UsageError("--cut-axis must be x, y or z");
    plane = centre_plane(mesh, Eigen::Vector3d::Unit(o.cut_axis[0] - 'x'));
  }
  Eigen::VectorXd s;
  VolumeRefinement refinement;  // the distance's operators' own, or the default one
  if (o.source >= 0) {
    if (o.scalar != "none") throw UsageError("--distance-from and --scalar exclude each other");
    if (o.source >= mesh.n_vertices())
      throw std::out_of_range(fmt::format("source vertex {} is out of range (the mesh has {} vertices)",
                                          o.source, mesh.n_vertices()));
    VolumeOperatorOptions vopt;
    vopt.keep_refinement = true;
    OperatorSet ops = timer.time("operators", [&] {
      return build_volume_operators(mesh, parse_volume_laplacian(o.laplacian), vopt);
    });
    const HeatGeodesics heat =
        timer.time("factorization", [&] { return HeatGeodesics(take_operators(ops), mesh.mean_edge_length()); });
    s = timer.time("solve", [&] { return heat.distance(o.source); });
    refinement = *heat.operators().volume_refinement;
    r.scalar_label = "distance";
    r.isolines = 15;
  } else {
    s = coordinate_scalar(o, mesh.positions(), r);
    refinement = timer.time("operators", [&] { return refine_volume(mesh); });
  }
  finish_options(o, r);
  timer.time("render", [&] { render_volume_cut_png(o.png, mesh, refinement, s, plane, r); });
  if (o.json)
    print_json({{"mesh", o.mesh},
                {"png", o.png},
                {"width", r.width},
                {"height", r.height},
                {"cut_point", {plane.point.x(), plane.point.y(), plane.point.z()}},
                {"cut_normal", {plane.normal.x(), plane.normal.y(), plane.normal.z()}},
                {"times_ms", timer.json()}});
  else
    fmt::print("wrote {}\n", o.png);
}

void run(const Options& o) {
  PhaseTimer timer;
  const InputMesh in = timer.time("read", [&] { return load_input_mesh(o.mesh, o.volume, o.repair); });
  if (in.volume) return run_volume(o, *in.volume, timer);
  const Mesh& mesh = *in.surface;
  RenderOptions r = picture_options(o);
  Eigen::VectorXd s;
  if (o.source >= 0) {
    if (o.scalar != "none") throw UsageError("--distance-from and --scalar exclude each other");
    OperatorSet ops = timer.time("operators", [&] {
      return build_operators(mesh, parse_laplacian("ours"), {.gradient_with_refinement = false});
    });
    const HeatGeodesics heat =
        timer.time("factorization", [&] { return HeatGeodesics(take_operators(ops), mesh.mean_edge_length()); });
    s = timer.time("solve", [&] { return heat.distance(o.source); });
    r.scalar_label = "distance";
    r.isolines = 15;
    r.view_direction = view_facing_vertex(mesh, o.source, r.up);
  } else {
    s = coordinate_scalar(o, mesh.positions(), r);
  }
  finish_options(o, r);
  timer.time("render", [&] { render_png(o.png, mesh, s, r); });
  if (o.json)
    print_json(
        {{"mesh", o.mesh}, {"png", o.png}, {"width", r.width}, {"height", r.height}, {"times_ms", timer.json()}});
  else
    fmt::print("wrote {}\n", o.png);
}

const RegisterCommand reg(
    "render", "Picture of a mesh (PNG), optionally with a colour-mapped scalar field", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("mesh", o->mesh, mesh_input_help())
          ->required();
      app.add_flag("--volume", o->volume, kVolumeFlagHelp);
      app.add_option(
             "--cut-plane", o->cut_plane,
             "volumes: cut plane through PX PY PZ with normal NX NY NZ; the half the normal points into "
             "is removed")
          ->expected(6);
      app.add_option(
          "--cut-axis", o->cut_axis,
          "volumes: cut by the plane through the bounding-box centre normal to x, y or z (default z)");
      app.add_option(
          "--laplacian", o->laplacian,
          "volumes, --distance-from: " + fmt::format("{}", fmt::join(volume_laplacian_names(), ", ")));
      app.add_option("--png", o->png, "output picture (.png)")->required();
      app.add_option("--scalar", o->scalar, "colour by a coordinate: x, y, z, or none (default)");
      app.add_option("--distance-from", o->source,
                     "colour by the heat-method geodesic distance from this vertex");
      app.add_option("--colormap", o->colormap, "viridis (default) or turbo");
      app.add_option("--isolines", o->isolines, "number of isolines (default 15 for distances, else 0)");
      app.add_option("--isoline-spacing", o->spacing, "isolines at multiples of this value instead");
      app.add_option(
             "--view", o->view,
             "view direction X Y Z (default: -z, or straight at a flat mesh; volumes: at the cut, tilted)")
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
