// apps/cli/operators.cpp — `polydec operators MESH --out DIR`: writes S, M, M_lumped, G, D, P
// in Matrix Market, rows and columns in the file's vertex order. With `--repeat N` it instead
// times N assemblies of S, M and lumped M from the loaded mesh (virtual vertices, sparsity
// pattern and values; load time excluded) and writes no files. Volume meshes (.ovm, .vtk, .mesh,
// or --volume) get S, M, M_lumped and P of the polyhedral refinement (operators/volume/laplacian.h).
// `--order 2`: the quadratic operators (operators/surface/quadratic.h) on the vertex and edge dofs.
// `--virtual-vertex split`: several virtual vertices per non-convex face (apps/cli/split_operators.h).
#include "polydec/apps/cli/command.h"
#include "polydec/apps/cli/split_operators.h"
#include "polydec/apps/cli/virtual_lift.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/detail/threads.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/operators/surface/gradient.h"
#include "polydec/operators/surface/quadratic.h"
#include "polydec/operators/volume/laplacian.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>

namespace polydec::cli::operators_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, out, rule = "squared-area", cell_rule = "squared-volume";
  int repeat = 0, threads = 1, order = 1;
  bool json = false, volume = false;
  VirtualLiftArgs lift;  // --virtual-lift, --virtual-positions (surfaces)
};

// CPU time of the calling thread in ms (robust to other processes on a busy machine).
double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// --repeat N: times N full assemblies (refine + pattern + S, M, lumped M) and N re-assemblies
// with the pattern kept.
void run_timing(const Options& o, const Mesh& mesh, const RefinementOptions& ropt, const AssemblyOptions& aopt,
                PhaseTimer& timer) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> full, full_cpu, values;
  Laplacian L;
  for (int i = 0; i < o.repeat; ++i) {
    const auto t0 = Clock::now();
    const double c0 = thread_cpu_ms();
    const Refinement r = refine(mesh, ropt);
    Laplacian fresh = assemble_laplacian(mesh, r, {}, nullptr, aopt);
    L.S.swap(fresh.S);  // Eigen 3.4's SparseMatrix has no move assignment: swap, not copy
    L.M.swap(fresh.M);
    L.M_lumped.swap(fresh.M_lumped);
    full.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    full_cpu.push_back(thread_cpu_ms() - c0);
  }
  const FacePattern fp = face_pattern(mesh, aopt.threads);
  for (int i = 0; i < o.repeat; ++i) {
    const auto t0 = Clock::now();
    const Refinement r = refine(mesh, ropt);
    reassemble_laplacian(mesh, r, fp, {}, L, aopt);
    values.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  nlohmann::json j = {{"mesh", o.mesh},
                      {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()},
                      {"S_nonzeros", L.S.nonZeros()},
                      {"threads", aopt.threads},
                      {"repeat", o.repeat},
                      {"median_ms", median(full)},
                      {"min_ms", *std::min_element(full.begin(), full.end())},
                      {"median_thread_cpu_ms", median(full_cpu)},
                      {"pattern_kept_median_ms", median(values)},
                      {"parts", {"S", "M", "M_lumped"}},
                      {"times_ms", timer.json()}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; {} threads\n", o.mesh, mesh.n_vertices(), mesh.n_faces(), aopt.threads);
  fmt::print("assembly of S, M, lumped M: median {:.3f} ms over {} runs (pattern kept: {:.3f} ms)\n", median(full),
             o.repeat, median(values));
}

// Volume meshes: S, M, M_lumped, P of the polyhedral refinement, or --repeat N timings.
void run_volume(const Options& o, const VolumeMesh& mesh, PhaseTimer& timer) {
  using Clock = std::chrono::steady_clock;
  VolumeRefinementOptions ropt;
  ropt.threads = resolve_threads(o.threads);
  try {
    ropt.cell_rule = parse_cell_point_rule(o.cell_rule);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (o.repeat > 0) {
    std::vector<double> full, values;
    const SparseMatrix pattern = cell_pattern(mesh);
    long nnz = 0;
    for (int i = 0; i < o.repeat; ++i) {
      const auto t0 = Clock::now();
      const VolumeLaplacian L = assemble_volume_laplacian(mesh, refine_volume(mesh, ropt), nullptr, ropt.threads);
      full.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
      nnz = L.S.nonZeros();
    }
    for (int i = 0; i < o.repeat; ++i) {
      const auto t0 = Clock::now();
      const VolumeLaplacian L = assemble_volume_laplacian(mesh, refine_volume(mesh, ropt), &pattern, ropt.threads);
      values.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    nlohmann::json j = {{"mesh", o.mesh},         {"vertices", mesh.n_vertices()}, {"faces", mesh.n_faces()},
                        {"cells", mesh.n_cells()}, {"S_nonzeros", nnz},             {"repeat", o.repeat},
                        {"median_ms", median(full)}, {"min_ms", *std::min_element(full.begin(), full.end())},
                        {"pattern_kept_median_ms", median(values)}, {"threads", ropt.threads},
                        {"parts", {"S", "M", "M_lumped"}}, {"times_ms", timer.json()}};
    if (o.json) {
      print_json(j);
      return;
    }
    fmt::print("{}: {} vertices, {} faces, {} cells\n", o.mesh, mesh.n_vertices(), mesh.n_faces(), mesh.n_cells());
    fmt::print("assembly of S, M, lumped M: median {:.3f} ms over {} runs (pattern kept: {:.3f} ms)\n", median(full),
               o.repeat, median(values));
    return;
  }
  const auto t_build = Clock::now();
  const VolumeRefinement r = refine_volume(mesh, ropt);
  const VolumeLaplacian L = assemble_volume_laplacian(mesh, r, nullptr, ropt.threads);
  const SparseMatrix P = volume_prolongation(mesh, r);
  timer.add("operators", t_build);
  const auto t_write = Clock::now();
  std::filesystem::create_directories(o.out);
  SparseMatrix Ml(mesh.n_vertices(), mesh.n_vertices());
  Ml.setIdentity();
  Ml.diagonal() = L.M_lumped;
  write_matrix_market(o.out + "/S.mtx", L.S);
  write_matrix_market(o.out + "/M.mtx", L.M);
  write_matrix_market(o.out + "/M_lumped.mtx", Ml);
  write_matrix_market(o.out + "/P.mtx", P);
  timer.add("write", t_write);
  nlohmann::json j = {{"mesh", o.mesh},
                      {"out", o.out},
                      {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()},
                      {"cells", mesh.n_cells()},
                      {"cell_point", to_string(ropt.cell_rule)},
                      {"S_nonzeros", L.S.nonZeros()},
                      {"volume", L.M_lumped.sum()},
                      {"subtet_degenerate", r.quality.n_degenerate},
                      {"subtet_inverted", r.quality.n_inverted},
                      {"files", {"S.mtx", "M.mtx", "M_lumped.mtx", "P.mtx"}},
                      {"times_ms", timer.json()}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces, {} cells; S has {} non-zeros\n", o.mesh, mesh.n_vertices(), mesh.n_faces(),
             mesh.n_cells(), L.S.nonZeros());
  fmt::print("sub-tetrahedra: {} degenerate, {} inverted\n", r.quality.n_degenerate, r.quality.n_inverted);
  fmt::print("wrote S.mtx M.mtx M_lumped.mtx P.mtx to {}\n", o.out);
}

// --order 2: S, M, M_lumped (HRZ) and P of the quadratic elements, dofs.txt (x y z per dof).
void run_quadratic(const Options& o, const Mesh& mesh, const Refinement& r, PhaseTimer& timer) {
  const auto t_build = PhaseTimer::Clock::now();
  const QuadraticLaplacian Q = assemble_quadratic_laplacian(mesh, r);
  const SparseMatrix P = quadratic_prolongation(mesh, r);
  timer.add("operators", t_build);
  const auto t_write = PhaseTimer::Clock::now();
  const int nd = int(Q.dofs.rows());
  std::filesystem::create_directories(o.out);
  SparseMatrix Ml(nd, nd);
  Ml.setIdentity();
  Ml.diagonal() = Q.M_lumped;
  write_matrix_market(o.out + "/S.mtx", Q.S);
  write_matrix_market(o.out + "/M.mtx", Q.M);
  write_matrix_market(o.out + "/M_lumped.mtx", Ml);
  write_matrix_market(o.out + "/P.mtx", P);
  {
    std::ofstream f(o.out + "/dofs.txt");
    if (!f) throw FileError(o.out + "/dofs.txt", 0, -1, "cannot open file for writing");
    for (int i = 0; i < nd; ++i) f << fmt::format("{:.17g} {:.17g} {:.17g}\n", Q.dofs(i, 0), Q.dofs(i, 1), Q.dofs(i, 2));
  }
  timer.add("write", t_write);
  nlohmann::json j = {{"mesh", o.mesh},
                      {"out", o.out},
                      {"order", 2},
                      {"vertices", mesh.n_vertices()},
                      {"edges", mesh.n_edges()},
                      {"faces", mesh.n_faces()},
                      {"dofs", nd},
                      {"S_nonzeros", Q.S.nonZeros()},
                      {"fan_degenerate", r.quality.n_degenerate},
                      {"fan_inverted", r.quality.n_inverted},
                      {"files", {"S.mtx", "M.mtx", "M_lumped.mtx", "P.mtx", "dofs.txt"}},
                      {"times_ms", timer.json()}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} edges, {} faces; order 2: {} dofs, S has {} non-zeros\n", o.mesh,
             mesh.n_vertices(), mesh.n_edges(), mesh.n_faces(), nd, Q.S.nonZeros());
  fmt::print("fan triangles: {} degenerate, {} inverted\n", r.quality.n_degenerate, r.quality.n_inverted);
  fmt::print("wrote S.mtx M.mtx M_lumped.mtx P.mtx dofs.txt to {}\n", o.out);
}

void run(const Options& o) {
  if (o.order != 1 && o.order != 2) throw UsageError("--order must be 1 or 2");
  if (o.order == 2 && o.repeat > 0) throw UsageError("--repeat times the order 1 assembly only");
  if (o.repeat < 0) throw UsageError("--repeat must be positive");
  if (o.threads < 0) throw UsageError("--threads must be at least 0 (0: all hardware threads)");
  if (o.repeat == 0 && o.out.empty()) throw UsageError("--out DIR is required (or --repeat N to time the assembly)");
  PhaseTimer timer;
  InputMesh in = timer.time("read", [&] { return load_input_mesh(o.mesh, o.volume, o.repair); });
  if (in.volume) {
    if (o.order == 2) throw UsageError("--order 2: surface meshes only (volumes: docs/extensions.md)");
    if (o.lift.lift != "none" || !o.lift.positions.empty())
      throw UsageError("--virtual-lift and --virtual-positions apply to surface meshes only");
    return run_volume(o, *in.volume, timer);
  }
  const Mesh mesh = std::move(*in.surface);
  if (o.rule == "split") {
    if (o.order != 1 || o.repeat > 0 || o.lift.lift != "none" || !o.lift.positions.empty())
      throw UsageError("--virtual-vertex split: order 1 files only (no --order 2, --repeat, --virtual-lift)");
    return write_split_operators(mesh, o.mesh, o.out, o.json, timer);
  }
  RefinementOptions ropt;
  ropt.rule = parse_virtual_vertex_rule(o.rule);
  ropt.lift = virtual_lift(o.lift, mesh);
  AssemblyOptions aopt;
  aopt.threads = resolve_threads(o.threads);
  ropt.threads = aopt.threads;
  if (o.repeat > 0) {
    run_timing(o, mesh, ropt, aopt, timer);
    return;
  }
  const Refinement r = timer.time("operators", [&] { return refine(mesh, ropt); });
  if (o.order == 2) return run_quadratic(o, mesh, r, timer);
  const auto t_build = PhaseTimer::Clock::now();
  const Laplacian L = assemble_laplacian(mesh, r, {}, nullptr, aopt);
  const SparseMatrix G = gradient(mesh, r), D = divergence(mesh, r), P = prolongation(mesh, r);
  timer.add("operators", t_build);
  const auto t_write = PhaseTimer::Clock::now();
  std::filesystem::create_directories(o.out);
  SparseMatrix Ml(mesh.n_vertices(), mesh.n_vertices());
  Ml.setIdentity();
  Ml.diagonal() = L.M_lumped;
  write_matrix_market(o.out + "/S.mtx", L.S);
  write_matrix_market(o.out + "/M.mtx", L.M);
  write_matrix_market(o.out + "/M_lumped.mtx", Ml);
  write_matrix_market(o.out + "/G.mtx", G);
  write_matrix_market(o.out + "/D.mtx", D);
  write_matrix_market(o.out + "/P.mtx", P);
  timer.add("write", t_write);
  nlohmann::json j = {{"mesh", o.mesh},
                      {"out", o.out},
                      {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()},
                      {"S_nonzeros", L.S.nonZeros()},
                      {"fan_degenerate", r.quality.n_degenerate},
                      {"fan_inverted", r.quality.n_inverted},
                      {"virtual_lift", to_string(ropt.lift)},
                      {"files", {"S.mtx", "M.mtx", "M_lumped.mtx", "G.mtx", "D.mtx", "P.mtx"}},
                      {"times_ms", timer.json()}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; S has {} non-zeros\n", o.mesh, mesh.n_vertices(), mesh.n_faces(),
             L.S.nonZeros());
  fmt::print("fan triangles: {} degenerate, {} inverted\n", r.quality.n_degenerate, r.quality.n_inverted);
  fmt::print("wrote S.mtx M.mtx M_lumped.mtx G.mtx D.mtx P.mtx to {}\n", o.out);
}

const RegisterCommand reg("operators", "Assemble S, M, lumped M, G, D, P and write them in Matrix Market", [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("mesh", o->mesh, mesh_input_help())->required();
  app.add_option("--out", o->out, "output directory (required unless --repeat)");
  app.add_flag("--volume", o->volume, "read MESH as a volume mesh whatever its extension");
  app.add_option("--cell-point", o->cell_rule, "volumes: cell-point weights, squared-volume (default) or polylaplace");
  app.add_option("--virtual-vertex", o->rule, "virtual-vertex rule: squared-area (default), centroid, split (several per non-convex face)");
  app.add_option("--order", o->order, "1 (default): the paper's operators; 2: quadratic elements on vertex and edge dofs");
  app.add_option("--repeat", o->repeat, "time N assemblies of S, M, lumped M instead of writing files");
  app.add_option("--threads", o->threads, "threads for the virtual vertices and the assembly (default 1; 0: all hardware threads)");
  app.add_flag("--json", o->json, "print one JSON object instead of text");
  add_virtual_lift_options(app, o->lift);
  add_repair_flag(app, o->repair);
  app.callback([o] { run(*o); });
});

}  // namespace
}  // namespace polydec::cli::operators_command
