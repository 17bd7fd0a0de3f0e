// apps/cli/info.cpp — `polydec info MESH`: counts, valence histogram, boundary loops, Euler
// characteristic and genus, planarity and convexity statistics, fan quality; on a volume mesh
// (.ovm, .vtk, .vtu, .mesh, .meshb, a gmsh .msh with 3-D elements, or --volume) counts, cells
// skipped by the reader, cell shapes, volumes, boundary and face planarity; for every kind the
// file's named groups and the lower-dimensional elements the reader skipped (gmsh .msh, MEDIT .meshb).
#include "polydec/apps/cli/command.h"
#include "polydec/apps/applications/mesh_statistics.h"
#include "polydec/dec/io/mesh_groups.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_cells.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

namespace polydec::cli::info_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh;
  bool json = false;
  bool volume = false;  // --volume
};

// Largest distance of a face's vertex to its least-squares plane over the face's diameter (the
// surface statistic of mesh_statistics, applied to the faces of a volume mesh); `diameter_out`
// receives the diameter.
double face_nonplanarity(const VolumeMesh& m, int f, double& diameter_out) {
  const auto vs = m.face(f);
  const int n = int(vs.size());
  Eigen::MatrixX3d X(n, 3);
  for (int k = 0; k < n; ++k) X.row(k) = m.positions().row(vs[k]);
  const Eigen::RowVector3d c = X.colwise().mean();
  const Eigen::MatrixX3d Y = X.rowwise() - c;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(Y), Eigen::ComputeThinV);
  const Eigen::Vector3d normal = svd.matrixV().col(2);
  double diameter = 0;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) diameter = std::max(diameter, (X.row(a) - X.row(b)).norm());
  diameter_out = diameter;
  return diameter > 0 ? (Y * normal).cwiseAbs().maxCoeff() / diameter : 0.0;
}

// The file's groups ("groups": name -> vertex and element counts) and skipped elements
// ("skipped_elements": kind -> count) added to j when it has any; their text lines are printed by
// print_groups. `elements` is "faces" or "cells".
void add_groups(const MeshGroups& g, const char* elements, nlohmann::json& j) {
  if (!g.skipped.empty()) j["skipped_elements"] = g.skipped;
  if (g.vertices.empty()) return;
  nlohmann::json groups = nlohmann::json::object();
  for (const auto& [name, vs] : g.vertices) {
    const auto it = g.elements.find(name);
    groups[name] = {{"vertices", vs.size()}, {elements, it == g.elements.end() ? 0 : it->second.size()}};
  }
  j["groups"] = groups;
}
void print_groups(const nlohmann::json& j, const char* elements) {
  if (j.contains("skipped_elements")) {
    std::vector<std::string> parts;
    for (const auto& [kind, n] : j["skipped_elements"].items()) parts.push_back(fmt::format("{} {}", n.get<long>(), kind));
    fmt::print("  skipped lower-dimensional elements: {}\n", fmt::join(parts, ", "));
  }
  if (j.contains("groups")) {
    std::vector<std::string> parts;
    for (const auto& [name, c] : j["groups"].items())
      parts.push_back(fmt::format("'{}' ({} vertices, {} {})", name, c["vertices"].get<long>(), c[elements].get<long>(),
                                  elements));
    fmt::print("  groups: {}\n", fmt::join(parts, ", "));
  }
}

void run_volume(const Options& o, const InputMesh& in, PhaseTimer& timer) {
  if (o.repair) throw UsageError("--repair applies to surface meshes only");
  const auto t_statistics = PhaseTimer::Clock::now();
  const VolumeReadNotes& notes = in.notes;
  const VolumeMesh& m = *in.volume;
  std::map<std::string, int> shapes{
      {"tetrahedron", 0}, {"pyramid", 0}, {"wedge", 0}, {"hexahedron", 0}, {"other", 0}};
  double min_volume = m.n_cells() ? 1e308 : 0.0, max_volume = m.n_cells() ? -1e308 : 0.0;
  int nonpositive = 0;
  for (int c = 0; c < m.n_cells(); ++c) {
    ++shapes[cell_shape_name(cell_shape(m, c))];
    const double v = m.cell_volume(c);
    min_volume = std::min(min_volume, v);
    max_volume = std::max(max_volume, v);
    nonpositive += v <= 0;
  }
  // Boundary: faces, vertices, edges (of the boundary faces) and its Euler characteristic.
  int boundary_faces = 0, boundary_vertices = 0;
  std::vector<std::pair<int, int>> boundary_edges;
  for (int f = 0; f < m.n_faces(); ++f) {
    if (!m.is_boundary_face(f)) continue;
    ++boundary_faces;
    const auto vs = m.face(f);
    for (size_t i = 0; i < vs.size(); ++i)
      boundary_edges.push_back({std::min(vs[i], vs[(i + 1) % vs.size()]), std::max(vs[i], vs[(i + 1) % vs.size()])});
  }
  std::sort(boundary_edges.begin(), boundary_edges.end());
  boundary_edges.erase(std::unique(boundary_edges.begin(), boundary_edges.end()), boundary_edges.end());
  for (int v = 0; v < m.n_vertices(); ++v) boundary_vertices += m.is_boundary_vertex(v);
  std::map<int, int> face_sizes;
  double max_np = 0, sum_np = 0;
  int nonplanar = 0;
  const double tolerance = 1e-5;
  // A face counts as non-planar when it deviates more than the tolerance of its diameter and more
  // than sqrt(3) times the coordinates' absolute noise (how far moving each coordinate by what the
  // file's digits resolve can take a vertex off a plane; 0 for exact doubles).
  const double noise = m.coordinate_noise();
  for (int f = 0; f < m.n_faces(); ++f) {
    ++face_sizes[m.face_size(f)];
    double diameter = 0;
    const double d = face_nonplanarity(m, f, diameter);
    max_np = std::max(max_np, d);
    sum_np += d;
    nonplanar += d > tolerance && d * diameter > std::sqrt(3.0) * noise;
  }
  nlohmann::json fs = nlohmann::json::object();
  for (const auto& [n, c] : face_sizes) fs[std::to_string(n)] = c;
  const int chi_boundary = boundary_vertices - int(boundary_edges.size()) + boundary_faces;
  nlohmann::json j = {{"mesh", o.mesh},
                            {"kind", "volume"},
                            {"vertices", m.n_vertices()},
                            {"edges", m.n_edges()},
                            {"faces", m.n_faces()},
                            {"cells", m.n_cells()},
                            {"cell_shapes", shapes},
                            {"face_size_histogram", fs},
                            {"euler_characteristic", m.n_vertices() - m.n_edges() + m.n_faces() - m.n_cells()},
                            {"unreferenced_vertices", m.n_unreferenced_vertices()},
                            {"volume", m.volume()},
                            {"min_cell_volume", min_volume},
                            {"max_cell_volume", max_volume},
                            {"nonpositive_cells", nonpositive},
                            {"boundary_faces", boundary_faces},
                            {"boundary_edges", boundary_edges.size()},
                            {"boundary_vertices", boundary_vertices},
                            {"boundary_euler_characteristic", chi_boundary},
                            {"mean_edge_length", m.mean_edge_length()},
                            {"bounding_box_diagonal", m.bounding_box_diagonal()},
                            {"planarity_tolerance", tolerance},
                            {"coordinate_precision", m.precision().noise},
                            {"coordinate_noise", noise},
                            {"nonplanar_faces", nonplanar},
                            {"max_nonplanarity", max_np},
                            {"mean_nonplanarity", m.n_faces() ? sum_np / m.n_faces() : 0.0},
                            {"skipped_cells", notes.skipped_cells}};
  add_groups(in.groups, "cells", j);
  timer.add("statistics", t_statistics);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{} (volume mesh)\n", o.mesh);
  fmt::print("  vertices {}, edges {}, faces {}, cells {}\n", m.n_vertices(), m.n_edges(), m.n_faces(), m.n_cells());
  std::string skipped;
  for (const auto& [kind, n] : notes.skipped_cells)
    skipped += fmt::format("{}{} {}", skipped.empty() ? "" : ", ", n, kind);
  if (!skipped.empty())
    fmt::print("  skipped lower-dimensional cells beside the volume cells: {}\n", skipped);
  fmt::print("  cells: {} tetrahedra, {} pyramids, {} wedges, {} hexahedra, {} other\n", shapes["tetrahedron"],
             shapes["pyramid"], shapes["wedge"], shapes["hexahedron"], shapes["other"]);
  std::string h;
  for (const auto& [n, c] : face_sizes) h += fmt::format(" {}-gons: {};", n, c);
  fmt::print("  face valences:{}\n", h);
  fmt::print("  V - E + F - C = {}, unreferenced vertices {}\n", j["euler_characteristic"].get<int>(),
             m.n_unreferenced_vertices());
  fmt::print("  volume {:.10g}; cell volumes from {:.6g} to {:.6g} ({} not positive)\n", m.volume(), min_volume,
             max_volume, nonpositive);
  fmt::print("  boundary: {} faces, {} edges, {} vertices, Euler characteristic {}\n", boundary_faces,
             boundary_edges.size(), boundary_vertices, chi_boundary);
  fmt::print("  mean edge length {:.6g}, bounding-box diagonal {:.6g}\n", m.mean_edge_length(), m.bounding_box_diagonal());
  fmt::print("  planarity: {} faces deviate more than {:g} of their diameter from their plane (max {:.3g}, mean {:.3g})\n",
             nonplanar, tolerance, max_np, m.n_faces() ? sum_np / m.n_faces() : 0.0);
  if (noise > 0)
    fmt::print("  coordinate precision: the file's digits resolve {:.3g} ({:.3g} of the rms radius); faces within it count as planar\n",
               noise, m.precision().noise);
  print_groups(j, "cells");
}

void run(const Options& o) {
  PhaseTimer timer;
  const InputMesh in = timer.time("read", [&] { return load_input_mesh(o.mesh, o.volume, o.repair, true); });
  if (in.volume) return run_volume(o, in, timer);
  const Mesh& mesh = *in.surface;
  const MeshStatistics s = timer.time("statistics", [&] { return mesh_statistics(mesh); });
  nlohmann::json hist = nlohmann::json::object();
  for (const auto& [n, c] : s.valence_histogram) hist[std::to_string(n)] = c;
  nlohmann::json j = {{"mesh", o.mesh},
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
  add_groups(in.groups, "faces", j);
  j["times_ms"] = timer.json();
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
  print_groups(j, "faces");
}

const RegisterCommand reg("info", "Print counts, topology, planarity and convexity statistics of a surface or volume mesh",
                          [](CLI::App& app) {
                            auto o = std::make_shared<Options>();
                            app.add_option("mesh", o->mesh, mesh_input_help())->required();
                            app.add_flag("--volume", o->volume, kVolumeFlagHelp);
                            app.add_flag("--json", o->json, "print one JSON object instead of text");
                            add_repair_flag(app, o->repair);
                            app.callback([o] { run(*o); });
                          });

}  // namespace
}  // namespace polydec::cli::info_command
