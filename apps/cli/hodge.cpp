// apps/cli/hodge.cpp — `polydec hodge MESH --out FILE`: Hodge decomposition of a 1-form
// (one value per coarse 1-cell, in the order of `polydec dec`'s edges.txt) into exact,
// co-exact and harmonic parts, with their star1 norms; --complex mesh: one value per mesh edge.
// Surfaces and volume meshes (.ovm, .vtk, .mesh or --volume) alike.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <chrono>
#include <fstream>
#include <iostream>
#include <random>
#include <type_traits>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/applications/hodge_decomposition.h"
#include "polydec/apps/applications/volume/hodge_decomposition.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/io/mesh_io.h"

namespace polydec::cli::hodge_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, out, form;
  double noise = 0.05;
  unsigned seed = 1;
  bool json = false;
  bool volume = false;  // --volume
  std::string complex = "complete";
};

// Reads one finite value per line (blank lines and '#' comments skipped).
Eigen::VectorXd read_form(const std::string& path, long expected, const char* cells) {
  std::ifstream in(path);
  if (!in) throw FileError(path, 0, -1, "cannot open file");
  std::vector<double> v;
  std::string line;
  long lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const size_t b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos || line[b] == '#') continue;
    size_t used = 0;
    double x = 0;
    try {
      x = std::stod(line.substr(b), &used);
    } catch (const std::exception&) {
      throw FileError(path, lineno, -1, "expected a number, got '" + line + "'");
    }
    if (line.find_first_not_of(" \t\r", b + used) != std::string::npos)
      throw FileError(path, lineno, -1, "expected one number per line, got '" + line + "'");
    if (!std::isfinite(x)) throw FileError(path, lineno, -1, "value is not finite");
    v.push_back(x);
  }
  if (long(v.size()) != expected)
    throw FileError(
        path, 0, -1,
        fmt::format("{} values, but the mesh has {} {} (see `polydec dec`'s edges.txt)", v.size(), expected, cells));
  return Eigen::Map<Eigen::VectorXd>(v.data(), long(v.size()));
}

// d0 of the x coordinate + the rotation about the z axis through the centroid, integrated along
// each 1-cell (midpoint rule) + uniform noise of amplitude noise * mean edge length.
template <class AnyMesh>
Eigen::VectorXd builtin_form(const AnyMesh& mesh, const Eigen::MatrixX2i& cells, double noise, unsigned seed) {
  const Eigen::MatrixX3d& X = mesh.positions();
  const Eigen::RowVector3d c = X.colwise().mean();
  const double h = mesh.mean_edge_length();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd omega(cells.rows());
  for (int p = 0; p < cells.rows(); ++p) {
    const Eigen::Vector3d a = X.row(cells(p, 0)).transpose(), b = X.row(cells(p, 1)).transpose();
    const Eigen::Vector3d m = 0.5 * (a + b) - c.transpose();
    omega[p] = (b - a).x() + Eigen::Vector3d::UnitZ().cross(m).dot(b - a) + noise * h * U(rng);
  }
  return omega;
}

// What the decomposition of either kind of mesh reports.
struct Decomposed {
  Eigen::MatrixX2i cells;
  Eigen::VectorXd omega;
  HodgeParts parts;
  int harmonic_dimension = 0;
  std::string counts;  // "V vertices, F faces" (and cells)
};

// Builds the decomposer (its operators and factorizations: the phase "operators"), decomposes the given
// or built-in form (the phase "solve").
template <class AnyMesh, class Decomposer>
Decomposed decompose(const Options& o, const AnyMesh& mesh, DecComplex complex, PhaseTimer& timer) {
  const bool on_mesh = complex == DecComplex::Mesh;
  const Decomposer hd = timer.time("operators", [&] { return Decomposer(mesh, {}, complex); });
  Decomposed r;
  if constexpr (std::is_same_v<Decomposer, HodgeDecomposer>)
    r.cells = on_mesh ? mesh.edges() : hd.complex().pairs();
  else
    r.cells = hd.cells();
  const char* cell_name = on_mesh ? "edges" : "coarse 1-cells";
  r.omega = o.form.empty() ? builtin_form(mesh, r.cells, o.noise, o.seed) : read_form(o.form, r.cells.rows(), cell_name);
  r.parts = timer.time("solve", [&] { return hd.decompose(r.omega); });
  r.harmonic_dimension = hd.harmonic_dimension();
  return r;
}

void run(const Options& o) {
  if (!(o.noise >= 0) || !std::isfinite(o.noise)) throw UsageError("--noise must be a finite number >= 0");
  const DecComplex complex = parse_option(parse_dec_complex, o.complex);
  const bool on_mesh = complex == DecComplex::Mesh;
  PhaseTimer timer;
  InputMesh in = timer.time("read", [&] { return load_input_mesh(o.mesh, o.volume, o.repair); });
  const bool volume = in.volume.has_value();
  Decomposed r;
  if (volume) {
    if (o.repair) throw UsageError("--repair applies to surface meshes only");
    const VolumeMesh& mesh = *in.volume;
    r = decompose<VolumeMesh, VolumeHodgeDecomposer>(o, mesh, complex, timer);
    r.counts = fmt::format("{} vertices, {} faces, {} cells", mesh.n_vertices(), mesh.n_faces(), mesh.n_cells());
  } else {
    const Mesh& mesh = *in.surface;
    if (!on_mesh && mesh.max_face_size() > kHighValence)
      std::cerr << fmt::format("polydec: warning: faces with up to {} corners: star1 grows as n^4 per face\n",
                               mesh.max_face_size());
    r = decompose<Mesh, HodgeDecomposer>(o, mesh, complex, timer);
    r.counts = fmt::format("{} vertices, {} faces", mesh.n_vertices(), mesh.n_faces());
  }
  const long n1 = r.cells.rows();
  const char* cell_name = on_mesh ? "edges" : "coarse 1-cells";
  const HodgeParts& parts = r.parts;
  const auto t_write = PhaseTimer::Clock::now();
  if (!o.out.empty()) {
    std::ofstream out(o.out);
    if (!out) throw FileError(o.out, 0, -1, "cannot open file for writing");
    out << fmt::format("# i j omega exact coexact harmonic (one line per {}, i < j, 0-based)\n",
                       on_mesh ? "mesh edge" : "coarse 1-cell");
    for (int p = 0; p < n1; ++p)
      out << fmt::format("{} {} {:.17g} {:.17g} {:.17g} {:.17g}\n", r.cells(p, 0), r.cells(p, 1), r.omega[p],
                         parts.exact[p], parts.coexact[p], parts.harmonic[p]);
    if (!out) throw FileError(o.out, 0, -1, "write failed");
  }
  if (!o.out.empty()) timer.add("write", t_write);
  const nlohmann::json j = {{"mesh", o.mesh},
                            {"kind", volume ? "volume" : "surface"},
                            {"form", o.form.empty() ? "builtin" : o.form},
                            {"complex", to_string(complex)},
                            {on_mesh ? "edges" : "pairs", n1},
                            {"harmonic_dimension", r.harmonic_dimension},
                            {"norm", parts.norm},
                            {"norm_exact", parts.norm_exact},
                            {"norm_coexact", parts.norm_coexact},
                            {"norm_harmonic", parts.norm_harmonic},
                            {"out", o.out},
                            {"times_ms", timer.json()}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {}, {} {}, harmonic dimension {}\n", o.mesh, r.counts, n1, cell_name, r.harmonic_dimension);
  fmt::print("star1 norms: form {:.6g} = sqrt(exact^2 + co-exact^2 + harmonic^2)\n", parts.norm);
  fmt::print("  exact    {:.6g}\n  co-exact {:.6g}\n  harmonic {:.6g}\n", parts.norm_exact,
             parts.norm_coexact, parts.norm_harmonic);
  if (!o.out.empty()) fmt::print("wrote {}\n", o.out);
}

const RegisterCommand reg(
    "hodge", "Hodge decomposition of a 1-form into exact, co-exact and harmonic parts", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("mesh", o->mesh, mesh_input_help())->required();
      app.add_option("--out", o->out, "output text file: i j omega exact coexact harmonic");
      app.add_option("--form", o->form,
                     "1-form file, one value per coarse 1-cell in edges.txt order (default: "
                     "built-in d(x) + rotation about z + noise)");
      app.add_option("--noise", o->noise,
                     "noise amplitude of the built-in form, relative to "
                     "the mean edge length (default 0.05)");
      app.add_option("--seed", o->seed, "random seed of the built-in form's noise");
      app.add_option("--complex", o->complex,
                     "the cells: complete (default; vertex pairs sharing a face) or mesh (the mesh's edges: "
                     "positive definite star1, unique parts)");
      app.add_flag("--volume", o->volume, "read MESH as a volume mesh whatever its extension");
      app.add_flag("--json", o->json, "print one JSON object instead of text (with the phases' times, times_ms)");
      add_repair_flag(app, o->repair);
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::hodge_command
