// apps/cli/info.cpp — `polydec info MESH`: counts, valence histogram, boundary loops, Euler
// characteristic and genus, planarity and convexity statistics, fan quality.
#include "polydec/apps/cli/command.h"
#include "polydec/apps/applications/mesh_statistics.h"
#include "polydec/dec/io.h"

#include <fmt/format.h>

namespace polydec::cli::info_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh;
  bool json = false;
};

void run(const Options& o) {
  const Mesh mesh = load_mesh(o.mesh, o.repair);
  const MeshStatistics s = mesh_statistics(mesh);
  nlohmann::json hist = nlohmann::json::object();
  for (const auto& [n, c] : s.valence_histogram) hist[std::to_string(n)] = c;
  const nlohmann::json j = {{"mesh", o.mesh},
                            {"vertices", s.vertices},
                            {"faces", s.faces},
                            {"edges", s.edges},
                            {"halfedges", s.halfedges},
                            {"face_valence_histogram", hist},
                            {"boundary_edges", s.boundary_edges},
                            {"boundary_loops", s.boundary_loop_lengths},
                            {"components", s.components},
                            {"unreferenced_vertices", s.unreferenced_vertices},
                            {"euler_characteristic", s.euler_characteristic},
                            {"genus", s.genus},
                            {"mean_edge_length", s.mean_edge_length},
                            {"bounding_box_diagonal", s.bounding_box_diagonal},
                            {"planarity_tolerance", s.planarity_tolerance},
                            {"nonplanar_faces", s.nonplanar_faces},
                            {"max_nonplanarity", s.max_nonplanarity},
                            {"mean_nonplanarity", s.mean_nonplanarity},
                            {"convex_faces", s.convex_faces},
                            {"nonconvex_faces", s.nonconvex_faces},
                            {"fan_degenerate", s.fan.n_degenerate},
                            {"fan_inverted", s.fan.n_inverted},
                            {"fan_faces_affected", s.fan.n_faces_affected}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}\n", o.mesh);
  fmt::print("  vertices {}, faces {}, edges {}, halfedges {}\n", s.vertices, s.faces, s.edges, s.halfedges);
  std::string h;
  for (const auto& [n, c] : s.valence_histogram) h += fmt::format(" {}-gons: {};", n, c);
  fmt::print("  face valences:{}\n", h);
  fmt::print("  components {}, boundary loops {} (lengths {}), unreferenced vertices {}\n", s.components,
             s.boundary_loop_lengths.size(), fmt::join(s.boundary_loop_lengths, ", "), s.unreferenced_vertices);
  fmt::print("  Euler characteristic {}, genus {}\n", s.euler_characteristic, s.genus);
  fmt::print("  mean edge length {:.6g}, bounding-box diagonal {:.6g}\n", s.mean_edge_length, s.bounding_box_diagonal);
  fmt::print("  planarity: {} faces deviate more than {:g} of their diameter from their plane (max {:.3g}, mean {:.3g})\n",
             s.nonplanar_faces, s.planarity_tolerance, s.max_nonplanarity, s.mean_nonplanarity);
  fmt::print("  convexity: {} convex, {} non-convex faces\n", s.convex_faces, s.nonconvex_faces);
  fmt::print("  virtual refinement: {} degenerate and {} inverted fan triangles in {} faces\n", s.fan.n_degenerate,
             s.fan.n_inverted, s.fan.n_faces_affected);
}

const RegisterCommand reg("info", "Print counts, topology, planarity and convexity statistics of a mesh",
                          [](CLI::App& app) {
                            auto o = std::make_shared<Options>();
                            app.add_option("mesh", o->mesh, "input mesh (.obj, .off, .ply)")->required();
                            app.add_flag("--json", o->json, "print one JSON object instead of text");
                            add_repair_flag(app, o->repair);
                            app.callback([o] { run(*o); });
                          });

}  // namespace
}  // namespace polydec::cli::info_command
