// apps/cli/dec.cpp — `polydec dec MESH --out DIR`: the FEEC building blocks (paper section 4.6)
// in Matrix Market: d0, d1, star0, star1, star2, P0, P1, P2, plus the coarse cell lists
// edges.txt (vertex pairs) and triangles.txt (vertex triples), 0-based, one per line, in
// matrix order. With --complex mesh, on the mesh's own cells (dec/surface/mesh_complex.h): the
// same matrices, edges.txt (the mesh edges i j, oriented i -> j) and faces.txt (each face's
// vertices in its orientation). Volume meshes (.ovm, .vtk, .mesh, or --volume): d0, d1, d2, star0..star3,
// P0..P3 of the polyhedral refinement (dec/volume/hodge_star.h) and the coarse cell lists
// edges.txt, triangles.txt, tetrahedra.txt (vertex pairs, triples, quadruples sharing a cell), up
// to the degree the cells' sizes allow (--max-degree; dec/volume/complex.h); with --complex mesh on
// the mesh's edges, faces and cells, every degree (dec/volume/mesh_complex.h).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "polydec/apps/cli/command.h"
#include "polydec/dec/surface/form_span.h"
#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/dec/surface/prolongation.h"

namespace polydec::cli::dec_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, out, rule = "squared-area", cell_rule = "squared-volume";
  bool json = false, lumped = false, volume = false;
  int max_degree = -1;  // volumes: -1 = the largest the cells allow (volume_dec_max_degree)
  std::string complex = "complete", spoke_rule = "area";
};

template <class Cells>
void write_cells(const std::string& path, const Cells& cells) {
  std::ofstream out(path);
  if (!out) throw FileError(path, 0, -1, "cannot open file for writing");
  for (long r = 0; r < cells.rows(); ++r) {
    for (long c = 0; c < cells.cols(); ++c) out << (c ? " " : "") << cells(r, c);
    out << '\n';
  }
  if (!out) throw FileError(path, 0, -1, "write failed");
}

void write_simplices(const std::string& path, const SimplexComplex3& K, int k) {
  write_cells(path, K.simplices(k));
}

// Variable-length lists, one a line: list(i) for i < n (faces' vertices, cells' half-faces).
template <class List>
void write_lists(const std::string& path, int n, List list) {
  std::ofstream out(path);
  if (!out) throw FileError(path, 0, -1, "cannot open file for writing");
  for (int i = 0; i < n; ++i) {
    const auto items = list(i);
    for (size_t k = 0; k < items.size(); ++k) out << (k ? " " : "") << items[k];
    out << '\n';
  }
  if (!out) throw FileError(path, 0, -1, "write failed");
}

// The surface mesh complex: d, P and the stars on the mesh's edges and faces.
void run_surface_mesh_complex(const Options& o, const Mesh& mesh, const Refinement& r, PhaseTimer& timer) {
  const SpokeRule rule = parse_option(parse_spoke_rule, o.spoke_rule);
  const SurfaceDec D = timer.time("operators", [&] {
    return surface_dec(mesh, r, {.max_degree = 2, .complex = DecComplex::Mesh, .spoke_rule = rule});
  });
  const auto t_write = PhaseTimer::Clock::now();
  std::filesystem::create_directories(o.out);
  SparseMatrix star0 = D.star[0];
  if (o.lumped) {
    const Eigen::VectorXd rows = D.star[0] * Eigen::VectorXd::Ones(mesh.n_vertices());
    star0 = SparseMatrix(rows.asDiagonal());
  }
  const std::string d = o.out + "/";
  write_matrix_market(d + "d0.mtx", D.d[0]);
  write_matrix_market(d + "d1.mtx", D.d[1]);
  write_matrix_market(d + "star0.mtx", star0);
  write_matrix_market(d + "star1.mtx", D.star[1]);
  write_matrix_market(d + "star2.mtx", D.star[2]);
  for (int k = 0; k < 3; ++k) write_matrix_market(d + fmt::format("P{}.mtx", k), D.P[k]);
  write_cells(d + "edges.txt", mesh.edges());
  write_lists(d + "faces.txt", mesh.n_faces(), [&](int f) { return mesh.face(f); });
  timer.add("write", t_write);
  nlohmann::json j = {{"mesh", o.mesh},
                      {"out", o.out},
                      {"complex", "mesh"},
                      {"spoke_rule", to_string(rule)},
                      {"vertices", mesh.n_vertices()},
                      {"edges", mesh.n_edges()},
                      {"faces", mesh.n_faces()},
                      {"max_face_size", mesh.max_face_size()},
                      {"star0", o.lumped ? "lumped" : "galerkin"},
                      {"star1_nonzeros", D.star[1].nonZeros()},
                      {"star2_nonzeros", D.star[2].nonZeros()},
                      {"fan_degenerate", r.quality.n_degenerate},
                      {"fan_inverted", r.quality.n_inverted},
                      {"times_ms", timer.json()},
                      {"files",
                       {"d0.mtx", "d1.mtx", "star0.mtx", "star1.mtx", "star2.mtx", "P0.mtx", "P1.mtx", "P2.mtx",
                        "edges.txt", "faces.txt"}}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} edges, {} faces (up to {} corners)\n", o.mesh, mesh.n_vertices(), mesh.n_edges(),
             mesh.n_faces(), mesh.max_face_size());
  fmt::print("mesh complex ({} spoke rule): star1 {} non-zeros, star2 diagonal\n", to_string(rule),
             D.star[1].nonZeros());
  fmt::print("fan triangles: {} degenerate, {} inverted\n", r.quality.n_degenerate, r.quality.n_inverted);
  fmt::print("wrote d0 d1 star0 star1 star2 P0 P1 P2 (.mtx), edges.txt, faces.txt to {}\n", o.out);
}

// The volume mesh complex: d0..d2, P0..P3, star0..star3 on the mesh's edges, faces and cells (every
// degree for every cell size), edges.txt, faces.txt and cells.txt (one cell a line: its half-faces
// h, face h / 2 as listed in faces.txt when h is even (then d2 = +1), reversed when odd (d2 = -1)).
void run_volume_mesh_complex(const Options& o, const VolumeMesh& mesh, const VolumeRefinement& r, PhaseTimer& timer) {
  const SpokeRule rule = parse_option(parse_spoke_rule, o.spoke_rule);
  const int degree = o.max_degree < 0 ? 3 : o.max_degree;
  const auto t_build = PhaseTimer::Clock::now();
  VolumeDec D;
  try {
    D = volume_dec(mesh, r, VolumeDecOptions{.max_degree = degree, .complex = DecComplex::Mesh, .spoke_rule = rule});
  } catch (const std::invalid_argument& e) {  // a cell that is not a ball: the file's content
    throw FileError(o.mesh, 0, -1, e.what());
  }
  timer.add("operators", t_build);
  const auto t_write = PhaseTimer::Clock::now();
  std::filesystem::create_directories(o.out);
  const std::string d = o.out + "/";
  std::vector<std::string> files;
  auto write = [&](const std::string& name, const SparseMatrix& A) {
    write_matrix_market(d + name, A);
    files.push_back(name);
  };
  for (int k = 0; k < degree; ++k) write(fmt::format("d{}.mtx", k), D.d[k]);
  if (o.lumped) {
    const Eigen::VectorXd rows = D.star[0] * Eigen::VectorXd::Ones(mesh.n_vertices());
    write("star0.mtx", SparseMatrix(rows.asDiagonal()));
  } else {
    write("star0.mtx", D.star[0]);
  }
  for (int k = 1; k <= degree; ++k) write(fmt::format("star{}.mtx", k), D.star[k]);
  for (int k = 0; k <= degree; ++k) write(fmt::format("P{}.mtx", k), D.P[k]);
  write_cells(d + "edges.txt", mesh.edges());
  files.push_back("edges.txt");
  write_lists(d + "faces.txt", mesh.n_faces(), [&](int f) { return mesh.face(f); });
  write_lists(d + "cells.txt", mesh.n_cells(), [&](int c) { return mesh.cell(c); });
  files.push_back("faces.txt");
  files.push_back("cells.txt");
  timer.add("write", t_write);
  nlohmann::json nonzeros = nlohmann::json::object();
  for (int k = 0; k <= degree; ++k) nonzeros[fmt::format("star{}", k)] = D.star[k].nonZeros();
  nlohmann::json j = {{"mesh", o.mesh},
                      {"out", o.out},
                      {"complex", "mesh"},
                      {"spoke_rule", to_string(rule)},
                      {"vertices", mesh.n_vertices()},
                      {"edges", mesh.n_edges()},
                      {"faces", mesh.n_faces()},
                      {"cells", mesh.n_cells()},
                      {"max_degree", degree},
                      {"star0", o.lumped ? "lumped" : "galerkin"},
                      {"nonzeros", nonzeros},
                      {"subtet_degenerate", r.quality.n_degenerate},
                      {"subtet_inverted", r.quality.n_inverted},
                      {"times_ms", timer.json()},
                      {"files", files}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} edges, {} faces, {} cells\n", o.mesh, mesh.n_vertices(), mesh.n_edges(),
             mesh.n_faces(), mesh.n_cells());
  fmt::print("mesh complex up to degree {}: positive definite stars (star3 diagonal)\n", degree);
  fmt::print("sub-tetrahedra: {} degenerate, {} inverted\n", r.quality.n_degenerate, r.quality.n_inverted);
  fmt::print("wrote {} to {}\n", fmt::join(files, " "), o.out);
}

void run_volume(const Options& o, DecComplex complex, const VolumeMesh& mesh, PhaseTimer& timer) {
  VolumeRefinementOptions ropt;
  try {
    ropt.cell_rule = parse_cell_point_rule(o.cell_rule);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (o.max_degree < -1 || o.max_degree > 3) throw UsageError("--max-degree must be 0, 1, 2 or 3");
  const VolumeRefinement r = timer.time("operators", [&] { return refine_volume(mesh, ropt); });
  if (complex == DecComplex::Mesh) return run_volume_mesh_complex(o, mesh, r, timer);
  const int allowed = volume_dec_max_degree(mesh);
  const int degree = o.max_degree < 0 ? allowed : o.max_degree;
  if (degree < 3 && o.max_degree < 0)
    std::cerr << fmt::format(
        "polydec: warning: cells with more than {} vertices: forms up to degree {} only (star_k gets C(m, k+1)^2 "
        "entries from a cell of m vertices; cells of at most {}, {}, {} vertices for k = 1, 2, 3)\n",
        max_dec_cell_vertices(degree + 1), degree, max_dec_cell_vertices(1), max_dec_cell_vertices(2),
        max_dec_cell_vertices(3));
  const auto t_build = PhaseTimer::Clock::now();
  VolumeDec D;
  try {
    D = volume_dec(mesh, r, degree);
  } catch (const std::invalid_argument& e) {  // a cell with too many vertices: the file's content
    throw FileError(o.mesh, 0, -1, e.what());
  }
  timer.add("operators", t_build);
  const auto t_write = PhaseTimer::Clock::now();
  std::filesystem::create_directories(o.out);
  SparseMatrix star0 = D.star[0];
  if (o.lumped) {
    const Eigen::VectorXd rows = D.star[0] * Eigen::VectorXd::Ones(mesh.n_vertices());
    star0 = SparseMatrix(mesh.n_vertices(), mesh.n_vertices());
    star0.setIdentity();
    star0.diagonal() = rows;
  }
  const std::string d = o.out + "/";
  std::vector<std::string> files;
  auto write = [&](const std::string& name, const SparseMatrix& A) {
    write_matrix_market(d + name, A);
    files.push_back(name);
  };
  for (int k = 0; k < degree; ++k) write(fmt::format("d{}.mtx", k), D.d[k]);
  write("star0.mtx", star0);
  for (int k = 1; k <= degree; ++k) write(fmt::format("star{}.mtx", k), D.star[k]);
  for (int k = 0; k <= degree; ++k) write(fmt::format("P{}.mtx", k), D.P[k]);
  const char* lists[] = {"", "edges.txt", "triangles.txt", "tetrahedra.txt"};
  for (int k = 1; k <= degree; ++k) {
    write_simplices(d + lists[k], D.coarse, k);
    files.push_back(lists[k]);
  }
  timer.add("write", t_write);
  // Ranks of star1..star3 by the dense reduced-basis decision, when the mesh is small enough.
  nlohmann::json ranks = nlohmann::json::object();
  for (int k = 1; k < 4; ++k) {
    if (k > degree) {
      ranks[fmt::format("rank_star{}", k)] = nullptr;
      continue;
    }
    try {
      ranks[fmt::format("rank_star{}", k)] = volume_form_span(D, mesh, r, k).rank();
    } catch (const std::invalid_argument&) {
      ranks[fmt::format("rank_star{}", k)] = nullptr;
    }
  }
  nlohmann::json j = {{"mesh", o.mesh},
                      {"out", o.out},
                      {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()},
                      {"cells", mesh.n_cells()},
                      {"pairs", D.coarse.n_pairs()},
                      {"triples", D.coarse.n_triples()},
                      {"quadruples", D.coarse.n_quads()},
                      {"max_degree", degree},
                      {"star0", o.lumped ? "lumped" : "galerkin"},
                      {"subtet_degenerate", r.quality.n_degenerate},
                      {"subtet_inverted", r.quality.n_inverted},
                      {"files", files}};
  j.update(ranks);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces, {} cells\n", o.mesh, mesh.n_vertices(), mesh.n_faces(), mesh.n_cells());
  fmt::print("coarse complex: {} 1-cells, {} 2-cells, {} 3-cells; ranks of star1..3: {}, {}, {}\n",
             D.coarse.n_pairs(), D.coarse.n_triples(), D.coarse.n_quads(), ranks["rank_star1"].dump(),
             ranks["rank_star2"].dump(), ranks["rank_star3"].dump());
  fmt::print("sub-tetrahedra: {} degenerate, {} inverted\n", r.quality.n_degenerate, r.quality.n_inverted);
  fmt::print("wrote {} to {}\n", fmt::join(files, " "), o.out);
}

void run(const Options& o) {
  const DecComplex complex = parse_option(parse_dec_complex, o.complex);
  PhaseTimer timer;
  InputMesh in = timer.time("read", [&] { return load_input_mesh(o.mesh, o.volume, o.repair); });
  if (in.volume) return run_volume(o, complex, *in.volume, timer);
  const Mesh& mesh = *in.surface;
  if (complex == DecComplex::Mesh) {
    RefinementOptions ropt;
    ropt.rule = parse_virtual_vertex_rule(o.rule);
    run_surface_mesh_complex(o, mesh, timer.time("operators", [&] { return refine(mesh, ropt); }), timer);
    return;
  }
  if (mesh.max_face_size() > kHighValence)
    std::cerr << fmt::format(
        "polydec: warning: faces with up to {} corners: a face of valence n carries n(n-1)/2 1-cells and "
        "n(n-1)(n-2)/6 2-cells, and star2 has (n(n-1)(n-2)/6)^2 entries per face ({} for the largest)\n",
        mesh.max_face_size(),
        long(mesh.max_face_size()) * (mesh.max_face_size() - 1) * (mesh.max_face_size() - 2) / 6 *
            (long(mesh.max_face_size()) * (mesh.max_face_size() - 1) * (mesh.max_face_size() - 2) / 6));
  RefinementOptions ropt;
  ropt.rule = parse_virtual_vertex_rule(o.rule);
  const auto t_build = PhaseTimer::Clock::now();
  const Refinement r = refine(mesh, ropt);
  const CoarseComplex K(mesh);
  const HodgeStars H = hodge_stars(mesh, r, K);
  const SparseMatrix P0 = prolongation(mesh, r), P1 = prolongation1(mesh, r, K), P2 = prolongation2(mesh, r, K);
  timer.add("operators", t_build);
  const auto t_write = PhaseTimer::Clock::now();
  std::filesystem::create_directories(o.out);
  SparseMatrix star0 = H.star0;
  if (o.lumped) {
    star0 = SparseMatrix(mesh.n_vertices(), mesh.n_vertices());
    star0.setIdentity();
    star0.diagonal() = H.star0_lumped;
  }
  const std::string d = o.out + "/";
  write_matrix_market(d + "d0.mtx", K.d0());
  write_matrix_market(d + "d1.mtx", K.d1());
  write_matrix_market(d + "star0.mtx", star0);
  write_matrix_market(d + "star1.mtx", H.star1);
  write_matrix_market(d + "star2.mtx", H.star2);
  write_matrix_market(d + "P0.mtx", P0);
  write_matrix_market(d + "P1.mtx", P1);
  write_matrix_market(d + "P2.mtx", P2);
  write_cells(d + "edges.txt", K.pairs());
  write_cells(d + "triangles.txt", K.triples());
  timer.add("write", t_write);
  const FormSpan s1 = form_span(mesh, r, K, 1), s2 = form_span(mesh, r, K, 2);
  nlohmann::json j = {{"mesh", o.mesh},
                      {"out", o.out},
                      {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()},
                      {"max_face_size", mesh.max_face_size()},
                      {"pairs", K.n_pairs()},
                      {"triples", K.triples().rows()},
                      {"rank_star1", s1.rank()},
                      {"rank_star2", s2.rank()},
                      {"star0", o.lumped ? "lumped" : "galerkin"},
                      {"star1_nonzeros", H.star1.nonZeros()},
                      {"star2_nonzeros", H.star2.nonZeros()},
                      {"fan_degenerate", r.quality.n_degenerate},
                      {"fan_inverted", r.quality.n_inverted},
                      {"files",
                       {"d0.mtx", "d1.mtx", "star0.mtx", "star1.mtx", "star2.mtx", "P0.mtx", "P1.mtx",
                        "P2.mtx", "edges.txt", "triangles.txt"}},
                      {"times_ms", timer.json()}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces (up to {} corners)\n", o.mesh, mesh.n_vertices(), mesh.n_faces(),
             mesh.max_face_size());
  fmt::print("coarse complex: {} 1-cells (rank of star1 {}), {} 2-cells (rank of star2 {})\n", K.n_pairs(),
             s1.rank(), K.n_triples(), s2.rank());
  fmt::print("fan triangles: {} degenerate, {} inverted\n", r.quality.n_degenerate, r.quality.n_inverted);
  fmt::print("wrote d0 d1 star0 star1 star2 P0 P1 P2 (.mtx), edges.txt, triangles.txt to {}\n", o.out);
}

const RegisterCommand reg("dec", "Write d0, d1, star0-2, P0-2 and the coarse cell lists (paper section 4.6)",
                          [](CLI::App& app) {
                            auto o = std::make_shared<Options>();
                            app.add_option("mesh", o->mesh,
                                           mesh_input_help())
                                ->required();
                            app.add_flag("--volume", o->volume, "read MESH as a volume mesh whatever its extension");
                            app.add_option("--cell-point", o->cell_rule,
                                           "volumes: cell-point weights, squared-volume (default) or polylaplace");
                            app.add_option("--out", o->out, "output directory")->required();
                            app.add_option("--virtual-vertex", o->rule,
                                           "virtual-vertex rule: squared-area (default), centroid");
                            app.add_flag("--lumped", o->lumped, "write the lumped (diagonal) star0");
                            app.add_option("--complex", o->complex,
                                           "the cells: complete (default; the paper's vertex pairs and triples "
                                           "of a face) or mesh (the mesh's edges and faces: positive definite stars)");
                            app.add_option("--spoke-rule", o->spoke_rule,
                                           "mesh complex: area (default; star2 = 1/area) or minimum-norm");
                            app.add_option("--max-degree", o->max_degree,
                                           "volumes: forms up to this degree (0..3; default: the largest the "
                                           "cells allow, 3 for cells of up to 12 vertices)");
                            app.add_flag("--json", o->json, "print one JSON object instead of text");
                            add_repair_flag(app, o->repair);
                            app.callback([o] { run(*o); });
                          });

}  // namespace
}  // namespace polydec::cli::dec_command
