// apps/paper/paper.cpp — the paper's evaluation (section 5) with every Laplacian: the experiments, the
// printed reference values, and the Markdown report.
#include "polydec/apps/paper/paper.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fmt/format.h>
#include <map>

#include "polydec/apps/applications/curvature.h"
#include "polydec/apps/applications/geodesics.h"
#include "polydec/apps/applications/harmonics.h"
#include "polydec/apps/pictures/image.h"
#include "polydec/apps/paper/metrics.h"
#include "polydec/apps/paper/sphere_spectrum.h"
#include "polydec/apps/paper/split_faces.h"
#include "polydec/apps/paper/virtual_vertices.h"
#include "polydec/apps/paper/volume_tables.h"
#include "polydec/apps/applications/parametrization.h"
#include "polydec/apps/pictures/plot.h"
#include "polydec/apps/applications/poisson.h"
#include "polydec/apps/applications/quadratic.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/apps/applications/smoothing.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec {
namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

// Every operator of operators/registry/laplacians.h, with the parameters the paper uses.
const std::vector<std::string> kAllMethods = {"ours",
                                              "centroid",
                                              "abs-area",
                                              "convex",
                                              "trace-min",
                                              "triangulated-minarea",
                                              "triangulated-maxminangle",
                                              "refined",
                                              "intrinsic-delaunay",
                                              "aw11:0.1",
                                              "aw11:0.5",
                                              "aw11:1",
                                              "degoes20:1",
                                              "diamond"};
// Table 6: the virtual-vertex choices (trace-min is Bunge et al. 2024, not in the paper).
const std::vector<std::string> kVariants = {"ours", "convex", "centroid", "abs-area", "trace-min"};
// Table 5: the paper's six columns first.
const std::vector<std::string> kTimed = {"ours",     "convex",     "centroid",           "abs-area",
                                         "aw11:0.5", "triangulated-minarea", "trace-min", "intrinsic-delaunay",
                                         "degoes20:1", "refined",    "diamond"};
// Methods whose operators act on the input's vertices (the curvature flow and parametrization
// need that).
bool on_input_vertices(const std::string& m) { return m != "refined"; }

json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// CPU time of the whole process (all threads, BLAS's included), in ms.
double process_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * double(ts.tv_sec) + 1e-6 * double(ts.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[v.size() / 2];
}

struct NamedMesh {
  std::string name, setup;
  Mesh mesh;
};

// One unit of work, for the progress bar.
struct Step {
  std::string label;
  double weight;
  std::function<void()> run;
};

class Evaluation {
 public:
  explicit Evaluation(const PaperOptions& o) : o_(o) {}

  json run() {
    plan();
    double total = 0, done = 0;
    for (const Step& s : steps_) total += s.weight;
    json step_ms = json::object();
    for (const Step& s : steps_) {
      if (o_.progress) o_.progress(done / total, s.label);
      const auto start = std::chrono::steady_clock::now();
      s.run();
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      step_ms[s.label] = step_ms.value(s.label, 0.0) + ms;
      done += s.weight;
    }
    r_["step_times_ms"] = step_ms;
    if (o_.progress) o_.progress(1.0, "done");
    r_["paper"] = paper_printed_values();
    r_["authors_program"] = authors_program_values();
    r_["setup"] = setup_;
    const BlasThreads blas = blas_threads();
    r_["options"] = {{"quick", o_.quick},
                     {"timings", o_.timings && !o_.quick},
                     {"timing_rounds", std::max(1, o_.timing_repeats)},
                     {"data_dir", o_.data_dir},
                     {"blas_threads", {{"threads", blas.threads}, {"requested", blas.requested}, {"source", blas.source}}}};
    return r_;
  }

 private:
  const PaperOptions& o_;
  json r_ = json::object(), setup_ = json::object();
  std::vector<Step> steps_;
  std::map<std::string, NamedMesh> meshes_;

  Mesh load(const std::string& file) const { return read_mesh(o_.data_dir + "/" + file); }
  bool write_files() const { return !o_.out_dir.empty(); }
  bool pictures() const { return o_.pictures && write_files(); }

  const Mesh& mesh(const std::string& name) {
    auto it = meshes_.find(name);
    if (it != meshes_.end()) return it->second.mesh;
    NamedMesh m{name, "", {}};
    if (name == "REGULAR SPHERE") {
      m.mesh = project_to_unit_sphere(load("quad-sphere.off"));
      m.setup = "quad-sphere.off projected to the unit sphere";
    } else if (name == "NOISY SPHERE") {
      m.mesh = project_to_unit_sphere(load("noisy-sphere.off"));
      m.setup = "noisy-sphere.off projected to the unit sphere";
    } else if (name == "HEX SPHERE") {
      m.mesh = project_to_unit_sphere(dual(load("unit-sphere.off")));
      m.setup = "dual of unit-sphere.off (dual vertex at the triangle centroid), projected to the unit sphere";
    } else if (name == "FINE SPHERE") {
      m.mesh = project_to_unit_sphere(catmull_clark(mesh("HEX SPHERE")));
      m.setup = "one Catmull-Clark step of HEX SPHERE, projected to the unit sphere";
    } else if (name == "QUADS 1") {
      m.mesh = catmull_clark(load("quad-plane.obj"));
      m.setup = "one Catmull-Clark step of quad-plane.obj";
    } else if (name == "QUADS 2") {
      m.mesh = load("quad-plane.obj");
      m.setup = "quad-plane.obj";
    } else if (name == "L-SHAPED") {
      m.mesh = load("L-plane.obj");
      m.setup = "L-plane.obj";
    } else if (name == "TETRIS 1") {
      m.mesh = load("tetris.obj");
      m.setup = "tetris.obj";
    } else if (name == "TETRIS 2") {
      m.mesh = load("tetris_2.obj");
      m.setup = "tetris_2.obj";
    } else {
      throw std::logic_error("paper: unknown mesh " + name);
    }
    setup_["meshes"][name] = {{"from", m.setup}, {"vertices", m.mesh.n_vertices()}, {"faces", m.mesh.n_faces()}};
    return meshes_.emplace(name, std::move(m)).first->second.mesh;
  }

  std::vector<std::string> spheres() const {
    if (o_.quick) return {"REGULAR SPHERE", "NOISY SPHERE"};
    return {"REGULAR SPHERE", "NOISY SPHERE", "HEX SPHERE", "FINE SPHERE"};
  }

  void plan() {
    for (const std::string& s : spheres()) {
      const double w = s == "FINE SPHERE" ? 40 : s == "HEX SPHERE" ? 8 : 1;
      for (const std::string& m : kAllMethods)
        steps_.push_back({fmt::format("Tables 2-3: {} / {}", s, m), w, [this, s, m] { sphere_cell(s, m); }});
    }
    for (const std::string p : {"QUADS 1", "QUADS 2", "L-SHAPED", "TETRIS 1", "TETRIS 2"})
      for (const std::string& m : kAllMethods)
        steps_.push_back({fmt::format("Tables 4, 6: {} / {}", p, m), 0.3, [this, p, m] { planar_cell(p, m); }});
    steps_.push_back({"Table 1: parametrization (Figure 6)", 2, [this] { table1_parametrization(); }});
    steps_.push_back({"Table 1: curvature flows (Figures 4, 5)", 4, [this] { table1_flows(); }});
    if (o_.timings && !o_.quick) {
      // Interleaved: each round times every method once, so that a burst of load on the machine
      // spreads over all methods instead of skewing one.
      const int rounds = std::max(1, o_.timing_repeats);
      for (const std::string s : {"HEX SPHERE", "FINE SPHERE"}) {
        for (int k = 0; k < rounds; ++k)
          steps_.push_back({fmt::format("Table 5: {} round {}/{}", s, k + 1, rounds),
                            (s == "FINE SPHERE" ? 30.0 : 6.0) * double(kTimed.size()) / rounds,
                            [this, s] { timing_round(s); }});
        steps_.push_back({fmt::format("Table 5: {} summary", s), 0.1, [this, s] { timing_summary(s); }});
      }
    }
    for (const std::string& m : kAllMethods)
      steps_.push_back({"Figure 9: " + m, o_.quick ? 0.5 : 3, [this, m] { figure9_cell(m); }});
    steps_.push_back({"Figure 9: plots, Poisson condition numbers", 3, [this] { figure9_finish(); }});
    steps_.push_back({"Beyond the paper: Figure 9 with quadratic elements", 1, [this] { figure9_quadratic(); }});
    steps_.push_back({"Figures 7, 8: geodesics pictures, negative off-diagonals", 4, [this] { figures78(); }});
    // The unit sphere's first 100 eigenvalues (apps/paper/sphere_spectrum.h); FINE SPHERE left
    // out, quick: REGULAR SPHERE only.
    for (const std::string& s : spheres())
      if (s != "FINE SPHERE" && (!o_.quick || s == "REGULAR SPHERE"))
        for (const std::string& m : kAllMethods)
          steps_.push_back({fmt::format("Spectrum: {} / {}", s, m), s == "HEX SPHERE" ? 3.0 : 0.5,
                            [this, s, m] { r_["spectrum100"][s][m] = sphere_spectrum_errors(mesh(s), m); }});
    // Beyond the paper (apps/paper/virtual_vertices.h): lifted virtual vertices; spectra as above.
    for (const std::string& s : spheres())
      steps_.push_back({"Beyond the paper: virtual vertices, " + s, s == "FINE SPHERE" ? 20.0 : s == "HEX SPHERE" ? 8.0 : 1.0,
                        [this, s] { r_["virtual_vertices"][s] = virtual_vertex_rows(mesh(s), s != "FINE SPHERE"); }});
    // Beyond the paper (apps/paper/split_faces.h): several virtual vertices in non-convex faces.
    for (const std::string p : {"L-SHAPED", "TETRIS 1", "TETRIS 2"})
      steps_.push_back({"Beyond the paper: split faces, " + p, 0.3, [this, p] { r_["split_faces"][p] = split_face_rows(mesh(p)); }});
    steps_.push_back({"Beyond the paper: split faces, Poisson", o_.quick ? 0.5 : 3.0, [this] {
                        r_["split_poisson"] = split_poisson(o_.quick ? std::vector<int>{8, 16, 32} : std::vector<int>{8, 16, 32, 64});
                      }});
    // The volume tables (apps/paper/volume_tables.h): 3D Poisson on the shared cubes, ball eigenvalues.
    steps_.push_back({"Volumes: 3D Poisson, ball eigenvalues", o_.quick ? 1.0 : 20.0,
                      [this] { r_["volumes"] = volume_tables(o_.data_dir, o_.quick); }});
  }

  // ---- Tables 2 and 3 -----------------------------------------------------------------------

  void sphere_cell(const std::string& s, const std::string& m) {
    const OperatorSet ops = build_operators(mesh(s), parse_laplacian(m), false);
    const int n = ops.n_input_vertices;
    for (bool lumped : {true, false}) {
      if (!lumped && ops.M.size() == 0) continue;
      const std::string key = lumped ? m : m + "-unlumped";
      CurvatureOptions c;
      c.lumped_mass = lumped;
      const Eigen::VectorXd H = mean_curvature(ops, c);
      r_["table2"][s][key] = number(curvature_rmse(H.head(n), 1.0));
      HarmonicsOptions h;
      h.max_band = 9;
      h.lumped_mass = lumped;
      const HarmonicsError e = spherical_harmonics_error(ops, h);
      r_["table3"][s][key] = number(e.sum(8));
      r_["table3_l1_9"][s][key] = number(e.sum(9));
    }
  }

  // ---- Tables 4 and 6 -----------------------------------------------------------------------

  void planar_cell(const std::string& p, const std::string& m) {
    const Mesh& mesh0 = mesh(p);
    const OperatorSet ops = build_operators(mesh0, parse_laplacian(m), true);
    Eigen::VectorXd e(mesh0.n_vertices());
    for (int v = 0; v < mesh0.n_vertices(); ++v) e[v] = (mesh0.position(v) - mesh0.position(0)).norm();
    e.array() -= e.minCoeff();
    // [BS07] as libigl runs it (the paper's numbers): h from the triangulation's edges.
    const double h = m == "intrinsic-delaunay" ? ops.mean_edge_length : mesh0.mean_edge_length();
    HeatGeodesicsOptions lumped;
    const double err = rmse(HeatGeodesics(ops, h, lumped).distance(0), e);
    r_["table4"][p][m] = number(err);
    r_["fan_quality"][p][m] = {{"degenerate", ops.quality.n_degenerate}, {"inverted", ops.quality.n_inverted}};
    if (std::find(kVariants.begin(), kVariants.end(), m) == kVariants.end()) return;
    r_["table6"][p][m] = number(err);
    // Un-lumped as the authors' program solves it: (M - t S) u = delta (see apps/applications/geodesics.h).
    HeatGeodesicsOptions unlumped;
    unlumped.lumped_mass = false;
    unlumped.mass_weighted_source = false;
    r_["table6"][p][m + "-unlumped"] = number(rmse(HeatGeodesics(ops, h, unlumped).distance(0), e));
  }

  // ---- Table 1 ------------------------------------------------------------------------------

  void table1_parametrization() {
    const Mesh m0 = load("suzanne-half.obj");
    setup_["table1"]["Figure 6"] = "suzanne-half.obj, spectral free-boundary parametrization [MTAD08]";
    for (const std::string& m : kAllMethods) {
      if (!on_input_vertices(m)) continue;
      const ConformalParametrization p = spectral_conformal_parametrization(build_operators(m0, parse_laplacian(m), false));
      r_["table1"]["Figure 6"][m] = number(conformal_distortion(m0, p.uv));
    }
  }

  void table1_flows() {
    struct Flow {
      std::string figure, file, setup;
      int steps;
    };
    // The paper's Figure 5 quad mesh is not in ../shared/data: amo_quad.off (a closed quad mesh)
    // stands in. The time step is the library default (1e-3 of the surface area); the flow runs
    // until the mesh is round (Figure 4: ten iterations).
    const std::vector<Flow> flows = {
        {"Figure 4", "noisy-sphere.off", "noisy-sphere.off (not projected), 10 steps of conformalized MCF", 10},
        {"Figure 5", "amo_quad.off",
         "amo_quad.off standing in for the paper's quad mesh (not available), 10 steps of conformalized MCF", 10}};
    for (const Flow& f : flows) {
      const Mesh m0 = load(f.file);
      setup_["table1"][f.figure] = f.setup;
      for (const std::string& m : kAllMethods) {
        if (!on_input_vertices(m)) continue;
        const std::vector<Mesh> steps = curvature_flow(m0, f.steps, {}, parse_laplacian(m));
        r_["table1"][f.figure][m] = number(conformal_distortion(m0, Eigen::MatrixX3d(steps.back().positions())));
      }
    }
  }

  // ---- Table 5 ------------------------------------------------------------------------------

  // Wall and process CPU time of one phase (the BLAS threads' work counts in the CPU time).
  struct Sample {
    double wall_ms = 0, cpu_ms = 0;
  };
  struct PhaseTimer {
    Clock::time_point wall = Clock::now();
    double cpu = process_cpu_ms();
    Sample stop() const { return {ms_since(wall), process_cpu_ms() - cpu}; }
  };
  // Per mesh and method: the samples of build, factor, solve over the rounds, and the checks.
  struct TimingCell {
    std::vector<Sample> build, factor, solve;
    json info;
  };
  std::map<std::string, std::map<std::string, TimingCell>> timings_;

  // One round of Table 5 on mesh s: every method once, in order.
  void timing_round(const std::string& s) {
    const Mesh& mesh0 = mesh(s);
    // The heat step's system (eq. 31) with lumped mass, t = (mean edge length)^2.
    const double t = std::pow(mesh0.mean_edge_length(), 2);
    for (const std::string& m : kTimed) {
      TimingCell& cell = timings_[s][m];
      const LaplacianChoice choice = parse_laplacian(m);
      PhaseTimer tb;
      const OperatorSet ops = build_operators(mesh0, choice, false);
      cell.build.push_back(tb.stop());
      const SparseMatrix A = SparseMatrix(ops.M_lumped.asDiagonal()) - t * ops.S;
      PhaseTimer tf;
      const SparseCholesky chol(A, "M - t S (" + m + ")");
      cell.factor.push_back(tf.stop());
      const Eigen::VectorXd b = Eigen::VectorXd::Unit(A.rows(), 0);
      // Five back-substitutions per round; the round's sample is their median (the first one
      // also allocates CHOLMOD's workspace).
      double checksum = 0;
      std::vector<double> wall, cpu;
      for (int k = 0; k < 5; ++k) {
        PhaseTimer ts;
        checksum += chol.solve(b)[0];
        const Sample x = ts.stop();
        wall.push_back(x.wall_ms);
        cpu.push_back(x.cpu_ms);
      }
      cell.solve.push_back({median(wall), median(cpu)});
      cell.info = {{"matrix_rows", A.rows()},
                   {"matrix_nonzeros", A.nonZeros()},
                   {"factor_nonzeros", chol.factor_nonzeros()},
                   {"solve_check", number(checksum / 5)}};
    }
  }

  // Medians over the rounds; a cell whose wall-time samples of a phase disagree by more than 2x
  // (max / min) is flagged as unstable (the machine's load changed while it ran).
  void timing_summary(const std::string& s) {
    for (const std::string& m : kTimed) {
      const TimingCell& c = timings_[s][m];
      json cell = c.info;
      json unstable = json::array();
      const std::array<std::pair<std::string, const std::vector<Sample>*>, 3> phases = {
          {{"build", &c.build}, {"factor", &c.factor}, {"solve", &c.solve}}};
      for (const auto& [name, samples] : phases) {
        std::vector<double> wall, cpu;
        for (const Sample& x : *samples) {
          wall.push_back(x.wall_ms);
          cpu.push_back(x.cpu_ms);
        }
        const auto [lo, hi] = std::minmax_element(wall.begin(), wall.end());
        const double spread = *lo > 0 ? *hi / *lo : 1.0;
        cell[name + "_ms"] = median(wall);
        cell[name + "_cpu_ms"] = median(cpu);
        cell[name + "_spread"] = spread;
        if (spread > 2) unstable.push_back(name);
      }
      cell["samples"] = {{"build", c.build.size()}, {"factor", c.factor.size()}, {"solve", c.solve.size()}};
      cell["unstable"] = unstable;
      r_["table5"][s][m] = cell;
    }
    const json& ours = r_["table5"][s]["ours"];
    for (const std::string& m : kTimed) {
      if (m == "ours") continue;
      json& cell = r_["table5"][s][m];
      for (const char* k : {"build", "factor", "solve"}) {
        const std::string key = std::string(k) + "_ms", cpu = std::string(k) + "_cpu_ms";
        cell[std::string(k) + "_ratio"] = cell[key].get<double>() / ours[key].get<double>();
        cell[std::string(k) + "_cpu_ratio"] = cell[cpu].get<double>() / std::max(ours[cpu].get<double>(), 1e-3);
      }
    }
  }

  // ---- Figure 9 -----------------------------------------------------------------------------

  void figure9_cell(const std::string& m) {
    ConvergenceOptions c;
    c.laplacian = parse_laplacian(m);
    if (o_.quick) c.resolutions = {8, 16, 32};
    for (const ConvergenceSeries& s : franke_convergence(c)) {
      r_["figure9"][s.family][m] = number(s.slope);
      json h = json::array(), err = json::array();
      for (const PoissonError& e : s.errors) {
        h.push_back(e.h);
        err.push_back(number(e.l2_error));
      }
      r_["figure9_series"][s.family][m] = {{"h", h}, {"l2_error", err}, {"resolutions", c.resolutions}};
    }
  }

  // Beyond the paper (docs/extensions.md): the Franke study with quadratic elements, the same
  // resolutions, plus the non-convex chevron grid.
  void figure9_quadratic() {
    const std::vector<int> res = o_.quick ? std::vector<int>{8, 16, 32} : std::vector<int>{8, 16, 32, 64};
    for (const QuadraticConvergenceSeries& s : franke_convergence_quadratic(res)) {
      json l2 = json::array(), h1 = json::array();
      for (const QuadraticPoissonError& e : s.errors) {
        l2.push_back(number(e.l2_error));
        h1.push_back(number(e.h1_error));
      }
      r_["beyond_quadratic"][s.family] = {
          {"l2_slope", number(s.l2_slope)}, {"h1_slope", number(s.h1_slope)}, {"l2_error", l2}, {"h1_error", h1},
          {"resolutions", res}};
    }
  }

  void figure9_finish() {
    // Condition number of the Poisson system -S restricted to the interior vertices.
    const int n = o_.quick ? 8 : 32;
    setup_["poisson_condition"] = fmt::format("-S on the interior vertices of the {0}x{0} grids of Figure 9", n);
    const std::vector<std::pair<std::string, Mesh>> grids = {
        {"triangles", triangle_grid(n, n)}, {"quads", quad_grid(n, n)}, {"hexagons", hex_grid(n, n)}};
    for (const auto& [family, grid] : grids)
      for (const std::string& m : kAllMethods) {
        const OperatorSet ops = build_operators(grid, parse_laplacian(m), false);
        std::vector<int> boundary;
        for (int v = 0; v < ops.domain.n_vertices(); ++v)
          if (ops.domain.is_boundary_vertex(v)) boundary.push_back(v);
        const ConditionEstimate e = condition_number_estimate(poisson_free_block(ops, boundary).A);
        r_["poisson_condition"][family][m] = number(e.condition);
      }
    if (!pictures()) return;
    std::vector<PlotSeries> ours;
    for (const auto& [family, cells] : r_["figure9_series"].items()) {
      PlotSeries s{family, cells["ours"]["h"].get<std::vector<double>>(), {}};
      for (const json& e : cells["ours"]["l2_error"]) s.y.push_back(e.is_number() ? e.get<double>() : NAN);
      ours.push_back(s);
      std::vector<PlotSeries> all;
      for (const auto& [m, c] : cells.items()) {
        PlotSeries a{m, c["h"].get<std::vector<double>>(), {}};
        for (const json& e : c["l2_error"]) a.y.push_back(e.is_number() ? e.get<double>() : NAN);
        all.push_back(a);
      }
      PlotOptions po;
      po.title = "Poisson (Franke), " + family + ": every Laplacian";
      po.x_label = "mean edge length h";
      po.y_label = "L2 error";
      po.width = 800;
      po.height = 600;
      write_plot(o_.out_dir + "/figure9-" + family + ".svg", all, po);
    }
    PlotOptions po;
    po.title = "Figure 9: Poisson (Franke), ours";
    po.x_label = "mean edge length h";
    po.y_label = "L2 error";
    write_plot(o_.out_dir + "/figure9.svg", ours, po);
    write_plot(o_.out_dir + "/figure9.png", ours, po);
  }

  // ---- Figures 7 and 8 ----------------------------------------------------------------------

  // Geodesic distance from vertex 0 with every operator, tiled into one picture; and the share
  // of negative off-diagonal entries of each S.
  void figures78() {
    // The paper's Figure 7 and 8 quad meshes are not in ../shared/data: amo_quad.off (a quad
    // mesh) and tetris.obj (anisotropic, non-star-shaped polygons) stand in.
    const std::vector<std::pair<std::string, std::string>> figs = {{"figure7", "amo_quad.off"},
                                                                   {"figure8", "tetris.obj"}};
    for (const auto& [fig, file] : figs) {
      const Mesh m0 = load(file);
      setup_[fig] = file + " (the paper's mesh is not available), heat geodesics from vertex 0";
      std::vector<std::pair<std::string, Eigen::VectorXd>> fields;
      for (const std::string& m : kAllMethods) {
        const OperatorSet ops = build_operators(m0, parse_laplacian(m), true);
        r_[fig][file][m] = number(negative_offdiagonal_ratio(ops.S));
        const double h = m == "intrinsic-delaunay" ? ops.mean_edge_length : m0.mean_edge_length();
        if (pictures()) fields.emplace_back(m, HeatGeodesics(ops, h).distance(0));
      }
      if (pictures()) write_tiles(o_.out_dir + "/" + fig + "-geodesics.png", m0, fields);
    }
  }

  void write_tiles(const std::string& path, const Mesh& m0,
                   const std::vector<std::pair<std::string, Eigen::VectorXd>>& fields) const {
    const int cols = 4, rows = int(fields.size() + cols - 1) / cols, w = 420, h = 340;
    double hi = 0;
    for (int v = 0; v < fields[0].second.size(); ++v)
      if (std::isfinite(fields[0].second[v])) hi = std::max(hi, fields[0].second[v]);
    Image sheet(cols * w, rows * h, Color{1, 1, 1});
    for (size_t k = 0; k < fields.size(); ++k) {
      RenderOptions ro;
      ro.width = w;
      ro.height = h;
      ro.scalar_min = 0;
      ro.scalar_max = hi > 0 ? hi : 1;  // one range for every tile: that of "ours"
      ro.isoline_spacing = ro.scalar_max / 15;
      ro.title = fields[k].first;
      ro.view_direction = view_facing_vertex(m0, 0);
      const Image tile = render(m0, fields[k].second, ro);
      const int x0 = int(k % cols) * w, y0 = int(k / cols) * h;
      for (int y = 0; y < tile.height; ++y)
        for (int x = 0; x < tile.width; ++x) sheet.set(x0 + x, y0 + y, tile.pixel(x, y));
    }
    write_png(path, sheet);
  }
};

// ---- report --------------------------------------------------------------------------------

std::string fmt_value(const json& v) {
  if (!v.is_number()) return "–";
  const double x = v.get<double>();
  if (x != 0 && (std::abs(x) < 1e-3 || std::abs(x) >= 1e4)) return fmt::format("{:.3e}", x);
  return fmt::format("{:.4f}", x);
}

// "value" or "value (paper, +d%)" with a mark when outside the tolerance.
std::string cell(const json& ours, const json* paper, double tolerance) {
  std::string s = fmt_value(ours);
  if (!paper || !paper->is_number() || !ours.is_number()) return s;
  const double p = paper->get<double>(), d = (ours.get<double>() - p) / p;
  return s + fmt::format(" ({}, {:+.1f}%{})", fmt_value(*paper), 100 * d, std::abs(d) <= tolerance ? "" : " ✗");
}

const json* find(const json& j, const std::string& a, const std::string& b, const std::string& c) {
  if (!j.contains(a) || !j[a].contains(b) || !j[a][b].contains(c)) return nullptr;
  return &j[a][b][c];
}

// A table: rows = meshes of results[table], columns = `methods` present.
std::string table(const json& r, const std::string& t, const std::vector<std::string>& methods, double tolerance) {
  if (!r.contains(t)) return "(not run)\n\n";
  std::vector<std::string> cols;
  for (const std::string& m : methods)
    for (const auto& [mesh, row] : r[t].items())
      if (row.contains(m)) {
        cols.push_back(m);
        break;
      }
  std::string s = "| mesh |";
  for (const std::string& c : cols) s += " " + c + " |";
  s += "\n|---|";
  for (size_t i = 0; i < cols.size(); ++i) s += "---|";
  s += "\n";
  for (const auto& [mesh, row] : r[t].items()) {
    s += "| " + mesh + " |";
    for (const std::string& c : cols) {
      s += ' ';
      s += row.contains(c) ? cell(row[c], find(r["paper"], t, mesh, c), tolerance) : "–";
      s += " |";
    }
    s += "\n";
  }
  return s + "\n";
}

// Ours against the authors' program (1% acceptance).
std::string authors_table(const json& r, const std::string& t, const std::string& key) {
  const json& a = r["authors_program"];
  if (!a.contains(t) || !r.contains(t)) return "";
  std::string s = "| mesh | polydec | authors' program | paper | polydec vs program |\n|---|---|---|---|---|\n";
  for (const auto& [mesh, row] : a[t].items()) {
    if (!row.contains(key) || !find(r, t, mesh, key)) continue;
    const json& ours = r[t][mesh][key];
    const json* p = find(r["paper"], t, mesh, key);
    const double d = ours.is_number() ? (ours.get<double>() - row[key].get<double>()) / row[key].get<double>() : NAN;
    s += fmt::format("| {} | {} | {} | {} | {:+.2f}%{} |\n", mesh, fmt_value(ours), fmt_value(row[key]),
                     p ? fmt_value(*p) : "–", 100 * d, std::abs(d) <= 0.01 ? "" : " ✗");
  }
  return s + "\n";
}

std::vector<std::string> with_unlumped(const std::vector<std::string>& m) {
  std::vector<std::string> out = m;
  for (const std::string& x : m) out.push_back(x + "-unlumped");
  return out;
}

}  // namespace

json reproduce_paper(const PaperOptions& options) {
  if (!options.out_dir.empty()) std::filesystem::create_directories(options.out_dir);
  return Evaluation(options).run();
}

json paper_printed_values() {
  const std::vector<std::string> t23 = {"ours", "triangulated-minarea", "aw11:0.1", "aw11:0.5", "aw11:1"};
  const std::vector<std::string> t4 = {"ours", "intrinsic-delaunay", "aw11:0.1", "aw11:0.5", "aw11:1"};
  auto rows = [](const std::vector<std::string>& cols, const std::vector<std::pair<std::string, std::vector<double>>>& r) {
    json j;
    for (const auto& [mesh, v] : r)
      for (size_t i = 0; i < v.size(); ++i) j[mesh][cols[i]] = v[i];
    return j;
  };
  json p;
  p["table1"] = rows({"ours", "aw11"}, {{"Figure 4", {5.075e-3, 5.417e-3}},
                                        {"Figure 5", {2.271e-3, 2.69e-3}},
                                        {"Figure 6", {1.157e-3, 1.204e-3}}});
  p["table2"] = rows(t23, {{"REGULAR SPHERE", {0.0168, 0.0469, 0.0290, 0.0290, 0.0290}},
                           {"NOISY SPHERE", {0.0469, 0.1053, 0.0562, 0.0814, 0.1551}},
                           {"HEX SPHERE", {0.0016, 0.3711, 0.0023, 0.0038, 0.0075}},
                           {"FINE SPHERE", {0.1334, 0.0623, 0.0279, 0.0107, 0.0141}}});
  p["table3"] = rows(t23, {{"REGULAR SPHERE", {0.0393, 0.0200, 0.0599, 0.0220, 0.0175}},
                           {"NOISY SPHERE", {0.0643, 0.0722, 0.0969, 0.0589, 0.1366}},
                           {"HEX SPHERE", {7.41e-7, 0.0037, 9.93e-6, 1.46e-6, 1.13e-6}},
                           {"FINE SPHERE", {0.0003, 6.73e-5, 0.0005, 6.48e-5, 8.98e-5}}});
  p["table4"] = rows(t4, {{"QUADS 1", {0.0265, 0.0394, 0.0179, 0.0415, 0.1206}},
                          {"QUADS 2", {0.0356, 0.0856, 0.0403, 0.0469, 0.1233}},
                          {"L-SHAPED", {0.0574, 0.0736, 0.4216, 0.1115, 1.6531}},
                          {"TETRIS 1", {0.2183, 0.1408, 0.4521, 0.2304, 0.2483}},
                          {"TETRIS 2", {0.0821, 0.0665, 0.4381, 0.1177, 0.1852}}});
  // Table 5 in ms (the paper's machine): build, factorization + back-substitution. The paper's
  // "QUADS" row is FINE SPHERE (section 5.6).
  const std::vector<std::string> t5 = {"ours", "convex", "centroid", "abs-area", "aw11", "triangulated-minarea"};
  const std::vector<std::pair<std::string, std::vector<std::array<double, 3>>>> t5v = {
      {"HEX SPHERE", {{55, 472, 25}, {142, 483, 25}, {13, 476, 26}, {357, 469, 25}, {52, 477, 26}, {21, 77, 8}}},
      {"FINE SPHERE", {{171, 596, 35}, {573, 596, 35}, {50, 599, 35}, {1460, 600, 36}, {240, 599, 35}, {82, 498, 29}}}};
  for (const auto& [mesh, v] : t5v)
    for (size_t i = 0; i < v.size(); ++i)
      p["table5"][mesh][t5[i]] = {{"build_ms", v[i][0]}, {"factor_ms", v[i][1]}, {"solve_ms", v[i][2]}};
  const std::vector<std::string> t6 = {"ours-unlumped", "convex-unlumped", "centroid-unlumped", "abs-area-unlumped",
                                       "ours",          "convex",          "centroid",          "abs-area"};
  p["table6"] = rows(t6, {{"QUADS 1", {0.025, 0.025, 0.025, 0.025, 0.026, 0.027, 0.027, 0.027}},
                          {"QUADS 2", {0.031, 0.031, 0.031, 0.031, 0.036, 0.036, 0.036, 0.036}},
                          {"L-SHAPED", {0.141, 0.165, 0.134, 0.134, 0.057, 0.063, 0.068, 0.068}},
                          {"TETRIS 1", {0.465, 0.490, 0.490, 0.491, 0.218, 0.181, 0.186, 0.185}},
                          {"TETRIS 2", {0.406, 0.346, 0.151, 0.153, 0.082, 0.089, 0.089, 0.088}}});
  // Section 5.5: negative off-diagonal ratio on Figure 7's quad mesh.
  p["figure7"]["paper's quad mesh"] = {{"ours", 0.11},
                                       {"aw11:0.5", 0.21},
                                       {"refined", 0.17},
                                       {"triangulated-maxminangle", 0.05},
                                       {"triangulated-minarea", 0.15},
                                       {"intrinsic-delaunay", 0.0}};
  return p;
}

json authors_program_values() {
  json a;
  a["table2"] = {{"HEX SPHERE", {{"ours", 0.001598}, {"ours-unlumped", 0.003915}}},
                 {"FINE SPHERE", {{"ours", 0.13336}, {"ours-unlumped", 0.36685}}},
                 {"REGULAR SPHERE", {{"ours", 0.016770}, {"ours-unlumped", 0.051469}}},
                 {"NOISY SPHERE", {{"ours", 0.046895}, {"ours-unlumped", 0.15186}}}};
  a["table3"] = {{"HEX SPHERE", {{"ours", 7.411e-7}}},
                 {"FINE SPHERE", {{"ours", 3.168e-4}}},
                 {"REGULAR SPHERE", {{"ours", 0.039341}}},
                 {"NOISY SPHERE", {{"ours", 0.064276}}}};
  // TETRIS 1: 0.17758 with float positions, 0.18983 with double; not a target.
  a["table4"] = {{"QUADS 1", {{"ours", 0.026455}}},
                 {"QUADS 2", {{"ours", 0.035637}}},
                 {"L-SHAPED", {{"ours", 0.057402}}},
                 {"TETRIS 2", {{"ours", 0.082092}}}};
  return a;
}

std::string paper_report_markdown(const json& r) {
  const std::vector<std::string> baselines = {"ours",     "triangulated-minarea", "aw11:0.1", "aw11:0.5",
                                              "aw11:1",   "intrinsic-delaunay",   "centroid", "abs-area",
                                              "convex",   "trace-min",            "triangulated-maxminangle",
                                              "refined",  "degoes20:1",           "diamond"};
  std::string s;
  s += "# Polygon Laplacian Made Simple — the evaluation, reproduced by polydec\n\n";
  s += "Made by `polydec paper`. Each cell: our value, then in parentheses the paper's printed value and our "
       "deviation from it; ✗ marks a deviation above 10% (baselines), the tolerance within which we take a "
       "value as reproduced. "
       "Method names are polydec's (`--laplacian NAME`): `ours` is the paper's operator, "
       "`triangulated-minarea` is [Lie03], `intrinsic-delaunay` is [BS07], `aw11:L` is [AW11] with lambda L; "
       "`-unlumped` means the Galerkin mass instead of the lumped one. A dash: not defined for that method "
       "(AW11 and de Goes et al. have no Galerkin mass). Every ✗ is explained, with evidence, in polydec's "
       "docs/paper.md.\n\n";
  if (r["options"].value("quick", false))
    s += "**Quick run** (`--quick`): HEX SPHERE, FINE SPHERE and Table 5 left out, coarse Poisson grids.\n\n";
  s += "## Meshes\n\n| name | made from | vertices | faces |\n|---|---|---|---|\n";
  for (const auto& [name, m] : r["setup"]["meshes"].items())
    s += fmt::format("| {} | {} | {} | {} |\n", name, m["from"].get<std::string>(), m["vertices"].get<int>(),
                     m["faces"].get<int>());
  s += "\n";

  s += "## Table 1: conformal distortion\n\n";
  for (const auto& [fig, text] : r["setup"]["table1"].items()) s += "- " + fig + ": " + text.get<std::string>() + "\n";
  s += "\nThe paper compares ours with [AW11] at an unstated lambda (its column `aw11` below); our metric is the "
       "area-weighted RMS of corner-angle differences in radians (apps/applications/parametrization.h). Our values are 99.97 "
       "times the paper's on Figure 6 (0.11567 vs 1.157e-3) but 0.67 times on Figure 4: no normalization tried "
       "explains both (docs/paper.md lists them; most likely a misprinted exponent on Figure 6), so compare "
       "the methods' ranking, not the magnitudes.\n\n";
  {
    std::vector<std::string> cols = baselines;
    s += table(r, "table1", cols, INFINITY);  // magnitudes differ by an unknown normalization
    if (r.contains("table1")) {
      s += "| figure | ours | best AW11 | ours < best AW11 (paper: yes) |\n|---|---|---|---|\n";
      for (const auto& [fig, row] : r["table1"].items()) {
        double best = INFINITY;
        for (const char* m : {"aw11:0.1", "aw11:0.5", "aw11:1"})
          if (row.contains(m) && row[m].is_number()) best = std::min(best, row[m].get<double>());
        const double o = row.value("ours", NAN);
        s += fmt::format("| {} | {} | {} | {} |\n", fig, fmt_value(o), fmt_value(best), o < best ? "yes" : "no");
      }
      s += "\n";
    }
  }

  s += "## Table 2: mean curvature RMSE on unit spheres (eq. 29)\n\nLumped mass; "
       "`polydec curvature MESH --unit-sphere --laplacian NAME --json`.\n\n";
  s += table(r, "table2", baselines, 0.10);
  s += "Ours against the authors' program (acceptance: 1%), lumped and un-lumped:\n\n";
  s += authors_table(r, "table2", "ours") + authors_table(r, "table2", "ours-unlumped");
  s += "Un-lumped (Galerkin) mass for every method that has one:\n\n" +
       table(r, "table2", {"ours-unlumped", "triangulated-minarea-unlumped", "intrinsic-delaunay-unlumped",
                           "centroid-unlumped", "abs-area-unlumped", "convex-unlumped", "trace-min-unlumped",
                           "triangulated-maxminangle-unlumped", "refined-unlumped", "diamond-unlumped"},
             0.10);

  s += "## Table 3: spherical-harmonics error (eq. 30), l = 1..8\n\nThe authors' program sums l = 1..8 (the "
       "caption says 1..9; `table3_l1_9` in results.json); each sample vector normalized to unit length; lumped "
       "mass. `polydec harmonics MESH --laplacian NAME --json`.\n\n";
  s += table(r, "table3", baselines, 0.10);
  s += authors_table(r, "table3", "ours");
  s += "Un-lumped mass: ours with its Galerkin mass, diamond with its own P^T M P (lumping it is not what its "
       "authors do, docs/laplacians.md):\n\n" +
       table(r, "table3", {"ours-unlumped", "diamond-unlumped"}, 0.10);

  s += "## Table 4: geodesic RMSE on planar meshes (heat method)\n\nSource vertex 0, t = h^2 with h the mean "
       "edge length of the input (of the triangulation for [BS07], as libigl does), RMSE against the Euclidean "
       "distance; lumped mass. `polydec geodesics MESH --source 0 --euclidean --laplacian NAME --json`.\n\n";
  s += table(r, "table4", baselines, 0.10);
  s += authors_table(r, "table4", "ours");
  s += "TETRIS 1 (ours): the authors' program prints 0.17758 (float positions) or 0.18983 (double) and the paper "
       "0.2183; our value is well defined by dropping exactly-degenerate fan triangles (docs/operators.md). AW11 "
       "lambda = 1 on L-SHAPED: the paper's 1.6531 exceeds the mesh's largest distance; see docs/laplacians.md.\n\n";

  {
    const json* blas = r.contains("options") && r["options"].contains("blas_threads") ? &r["options"]["blas_threads"] : nullptr;
    const std::string threads =
        blas ? fmt::format("{} BLAS thread(s), chosen by {}", (*blas)["threads"].get<int>(), (*blas)["source"].get<std::string>())
             : "BLAS threads not recorded";
    const int rounds = r.contains("options") && r["options"].contains("timing_rounds") ? r["options"]["timing_rounds"].get<int>() : 0;
    s += fmt::format(
        "## Table 5: timings (this machine, {})\n\nProtocol: {} interleaved rounds in one process, each timing every "
        "method once in turn (build, factor, then the median of five back-substitutions), so that a change of the "
        "machine's load "
        "spreads over all methods; the medians of wall time (ms) and of the process's CPU time (cpu, all threads) "
        "are shown. A cell marked ⚠ had wall-time samples of one phase more than 2x apart (max/min): its wall time "
        "is unreliable, the CPU time is the better measure. The ratio to `ours` measured in the same run is what "
        "compares across machines. Build = S, Galerkin and lumped M from the mesh; factor = sparse Cholesky of "
        "M - t S (lumped M); solve = one back-substitution.\n\n",
        threads, rounds > 0 ? std::to_string(rounds) : "repeated");
  }
  if (r.contains("table5")) {
    s += "| mesh | method | build ms | cpu | × ours | paper × ours | factor ms | cpu | solve ms | cpu | factor × ours | "
         "paper × ours |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    auto get = [](const json& c, const char* k) { return c.contains(k) && c[k].is_number() ? c[k].get<double>() : NAN; };
    for (const auto& [mesh, row] : r["table5"].items()) {
      for (const auto& [m, c] : row.items()) {
        const std::string pm = m.rfind("aw11", 0) == 0 ? "aw11" : m;
        const json* p = find(r["paper"], "table5", mesh, pm);
        const json* po = find(r["paper"], "table5", mesh, "ours");
        std::string pb = "–", pf = "–";
        if (p && po) {
          pb = fmt::format("{:.2f}", (*p)["build_ms"].get<double>() / (*po)["build_ms"].get<double>());
          pf = fmt::format("{:.2f}", (*p)["factor_ms"].get<double>() / (*po)["factor_ms"].get<double>());
        }
        const bool unstable = c.contains("unstable") && !c["unstable"].empty();
        s += fmt::format("| {} | {}{} | {:.1f} | {:.1f} | {} | {} | {:.1f} | {:.1f} | {:.2f} | {:.2f} | {} | {} |\n", mesh, m,
                         unstable ? " ⚠ " + c["unstable"].dump() : "", get(c, "build_ms"), get(c, "build_cpu_ms"),
                         c.contains("build_ratio") ? fmt::format("{:.2f}", c["build_ratio"].get<double>()) : "1", pb,
                         get(c, "factor_ms"), get(c, "factor_cpu_ms"), get(c, "solve_ms"), get(c, "solve_cpu_ms"),
                         c.contains("factor_ratio") ? fmt::format("{:.2f}", c["factor_ratio"].get<double>()) : "1", pf);
      }
    }
    s += "\n";
  } else {
    s += "(not run)\n\n";
  }

  s += "## Table 6: virtual-vertex choices, geodesic RMSE\n\nUn-lumped as the authors' program solves it: "
       "(M - t S) u = delta (`--mass unlumped --delta-source`); `trace-min` (Bunge et al. 2024) is not in the "
       "paper.\n\n";
  s += table(r, "table6", with_unlumped({"ours", "convex", "centroid", "abs-area", "trace-min"}), 0.10);
  if (r.contains("fan_quality")) {
    s += "Fan quality (degenerate / inverted fan triangles) of the refining methods:\n\n| mesh |";
    for (const std::string& m : kVariants) s += " " + m + " |";
    s += "\n|---|";
    for (size_t i = 0; i < kVariants.size(); ++i) s += "---|";
    s += "\n";
    for (const auto& [mesh, row] : r["fan_quality"].items()) {
      s += "| " + mesh + " |";
      for (const std::string& m : kVariants)
        s += row.contains(m) ? fmt::format(" {} / {} |", row[m]["degenerate"].get<int>(), row[m]["inverted"].get<int>())
                             : " – |";
      s += "\n";
    }
    s += "\n";
  }

  s += "## Figure 9: Poisson convergence (Franke function)\n\nFitted slope of log(L2 error) against log(h); the "
       "paper shows slope 2 for ours on all three families. Plots: `figure9.svg`, `figure9.png` (ours), "
       "`figure9-FAMILY.svg` (every method).\n\n";
  s += table(r, "figure9", baselines, 0.10);
  if (r.contains("poisson_condition")) {
    s += "Condition number estimate of the Poisson system (" +
         r["setup"]["poisson_condition"].get<std::string>() + "):\n\n";
    s += table(r, "poisson_condition", baselines, 0.10);
  }

  if (r.contains("beyond_quadratic")) {
    s += "## Beyond the paper: Figure 9 with quadratic elements\n\nNot in the paper (its section 6 asks for "
         "higher-order bases; docs/extensions.md): quadratic elements on the vertices and edge midpoints, "
         "Galerkin mass, L2 and H1 errors of the whole piecewise quadratic function; fitted slopes against h. "
         "non-convex: chevron_grid (hexagons with a reflex corner).\n\n| family | L2 slope | H1 slope |\n|---|---|---|\n";
    auto slope = [](const json& x) { return x.is_number() ? fmt::format("{:.3f}", x.get<double>()) : std::string("–"); };
    for (const auto& [family, c] : r["beyond_quadratic"].items())
      s += fmt::format("| {} | {} | {} |\n", family, slope(c["l2_slope"]), slope(c["h1_slope"]));
    s += "\n";
  }

  s += "## Figures 7 and 8: geodesics and negative off-diagonal entries (section 5.5)\n\n";
  for (const char* f : {"figure7", "figure8"})
    if (r["setup"].contains(f)) s += fmt::format("- {}: {}\n", f, r["setup"][f].get<std::string>());
  s += "\nShare of negative off-diagonal entries of S (the paper, on its Figure 7 mesh: ours 11%, [AW11] 21%, "
       "refined 17%, max-min-angle 5%, min-area 15%, intrinsic Delaunay 0%):\n\n";
  s += table(r, "figure7", baselines, INFINITY) + table(r, "figure8", baselines, INFINITY);
  s += "Pictures: `figure7-geodesics.png`, `figure8-geodesics.png` (one colour range for every tile: that of "
       "`ours`; isolines at 1/15 of it).\n\n";
  s += sphere_spectrum_markdown(r, kAllMethods);
  s += virtual_vertices_markdown(r);
  s += split_faces_markdown(r);
  s += volume_tables_markdown(r);
  return s;
}

}  // namespace polydec
