// apps/cli/repair.cpp — `polydec repair IN OUT [--merge-tolerance R]`: the opt-in repair steps of
// dec/mesh/repair.h (merge coincident vertices, drop invalid faces, remove duplicate faces and
// unreferenced vertices), printing what each changed, then the diagnostics of the result.
#include "polydec/dec/mesh/repair.h"

#include <fmt/format.h>

#include <cmath>

#include "polydec/apps/cli/command.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/mesh/mesh_checks.h"

namespace polydec::cli::repair_command {
namespace {

struct Options {
  std::string in, out;
  double merge_tolerance = 0.0;
  bool no_merge = false, json = false;
};

void run(const Options& o) {
  if (!(o.merge_tolerance >= 0) || !std::isfinite(o.merge_tolerance))
    throw UsageError("--merge-tolerance must be a finite number >= 0");
  PhaseTimer timer;
  PolygonSoup soup = timer.time("read", [&] { return read_polygon_soup(o.in); });
  const int nv0 = soup.n_vertices(), nf0 = soup.n_faces();
  RepairOptions ropt;
  ropt.merge_vertices = !o.no_merge;
  ropt.merge_tolerance = o.merge_tolerance;
  const RepairReport r = repair(soup, ropt);
  Mesh mesh;
  try {
    mesh = Mesh(std::move(soup));
  } catch (const InvalidMeshError& e) {
    throw InvalidMeshError(e.element, e.index,
                           fmt::format("{}: still invalid after repair: {}", o.in, e.what()));
  }
  timer.time("write", [&] { write_mesh(o.out, mesh); });
  const MeshReport checks = check_mesh(mesh);
  if (o.json) {
    print_json({{"in", o.in},
                {"out", o.out},
                {"vertices_in", nv0},
                {"faces_in", nf0},
                {"vertices_out", mesh.n_vertices()},
                {"faces_out", mesh.n_faces()},
                {"merged_vertices", r.merge.n_merged},
                {"merge_distance", r.merge.distance},
                {"collapsed_corners", r.drop.n_collapsed_corners},
                {"dropped_out_of_range", r.drop.n_out_of_range},
                {"dropped_too_few", r.drop.n_too_few},
                {"dropped_repeated_vertex", r.drop.n_repeated_vertex},
                {"dropped_zero_area", r.drop.n_zero_area},
                {"duplicate_faces_removed", r.dedup.n_removed()},
                {"unreferenced_removed", r.unreferenced.n_removed},
                {"remaining_findings", checks.summary()},
                {"times_ms", timer.json()}});
    return;
  }
  fmt::print("{}: {} vertices, {} faces\n", o.in, nv0, nf0);
  for (const auto& line : r.summary()) fmt::print("  {}\n", line);
  fmt::print("wrote {}: {} vertices, {} faces\n", o.out, mesh.n_vertices(), mesh.n_faces());
  const auto findings = checks.summary();
  if (!findings.empty()) {
    fmt::print("remaining findings (not repaired):\n");
    for (const auto& line : findings) fmt::print("  {}\n", line);
  }
}

const RegisterCommand reg(
    "repair", "Merge duplicate vertices, drop invalid and duplicate faces and unreferenced vertices",
    [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("in", o->in, mesh_input_help(false))->required();
      app.add_option("out", o->out, "output mesh (" + std::string(kSurfaceFormats) + ")")->required();
      app.add_option("--merge-tolerance", o->merge_tolerance,
                     "merge vertices closer than R x bounding-box diagonal (default 0: "
                     "coincident vertices only)");
      app.add_flag("--no-merge", o->no_merge, "do not merge vertices");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::repair_command
