// apps/cli/spectrum.cpp — `polydec spectrum MESH --k K --out DIR`: the k smallest eigenpairs of
// -S x = lambda M x (manifold harmonics) with Spectra's shift-invert solver.
#include "polydec/apps/applications/spectrum.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/cli/engine.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/dec/io.h"

namespace polydec::cli::spectrum_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, out, png, mass = "lumped", laplacian = "ours";
  int k = 10, png_index = 1;
  bool json = false;
  EngineOptions engine;  // --engine, --solver, --petsc-options
};

// Dense Matrix Market ("array real general", column by column), 17 significant digits.
void write_dense_matrix_market(const std::string& path, const Eigen::MatrixXd& A) {
  std::ofstream out(path);
  if (!out) throw FileError(path, 0, -1, "cannot open file for writing");
  out << "%%MatrixMarket matrix array real general\n" << A.rows() << ' ' << A.cols() << '\n';
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = 0; i < A.rows(); ++i) out << fmt::format("{:.17g}\n", A(i, j));
  if (!out) throw FileError(path, 0, -1, "write failed");
}

void report(const Options& o, const Mesh& mesh, const std::string& laplacian, int n_in, const Spectrum& sp,
            const nlohmann::json* engine);

void run(const Options& o) {
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  if (o.engine.engine == "petsc") {
    // The distributed run (apps/cli/engine.h); rank 0 reports as the serial run does.
    if (o.laplacian != "ours") throw UsageError("--engine petsc computes the paper's Laplacian only (--laplacian ours)");
    if (!o.png.empty() && (o.png_index < 0 || o.png_index >= o.k)) throw UsageError("--png-index must lie in [0, k)");
#ifdef POLYDEC_HAVE_PETSC
    petsc_spectrum(o.mesh, o.repair, o.k, o.mass == "lumped", o.engine, [&](const EngineSpectrum& r) {
      report(o, r.mesh, "ours", r.mesh.n_vertices(), r.spectrum, &r.summary);
    });
    return;
#else
    throw UsageError("--engine petsc: this polydec was built without PETSc (configure with -DPOLYDEC_WITH_PETSC=ON)");
#endif
  }
  if (o.engine.engine != "serial") throw UsageError("--engine must be serial or petsc");
  const Mesh mesh = load_mesh(o.mesh, o.repair);
  const OperatorSet ops = build_operators(mesh, parse_laplacian(o.laplacian), false);
  SpectrumOptions sopt;
  sopt.k = o.k;
  sopt.lumped_mass = o.mass == "lumped";
  const Spectrum sp = laplacian_spectrum(ops, sopt);
  report(o, mesh, ops.name, ops.n_input_vertices, sp, nullptr);
}

// The outputs of both engines: text or JSON (with the engine's summary), the files, the picture.
void report(const Options& o, const Mesh& mesh, const std::string& laplacian, int n_in, const Spectrum& sp,
            const nlohmann::json* engine) {
  std::vector<double> ev(sp.eigenvalues.data(), sp.eigenvalues.data() + sp.eigenvalues.size());
  nlohmann::json j = {{"mesh", o.mesh},          {"laplacian", laplacian},
                      {"mass", o.mass},          {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()}, {"k", o.k},
                      {"shift", sp.shift},       {"eigenvalues", ev}};
  if (engine) j["engine"] = *engine;
  if (!o.out.empty()) {
    std::filesystem::create_directories(o.out);
    {
      const std::string p = o.out + "/eigenvalues.txt";
      std::ofstream f(p);
      if (!f) throw FileError(p, 0, -1, "cannot open file for writing");
      for (double e : ev) f << fmt::format("{:.17g}\n", e);
    }
    write_dense_matrix_market(o.out + "/eigenvectors.mtx", sp.eigenvectors.topRows(n_in));
    VertexScalars props;
    for (int i = 0; i < o.k; ++i) props[fmt::format("u{:03d}", i)] = sp.eigenvectors.col(i).head(n_in);
    write_mesh(o.out + "/eigenvectors.ply", mesh, props);
    j["out"] = o.out;
    j["files"] = {"eigenvalues.txt", "eigenvectors.mtx", "eigenvectors.ply"};
  }
  if (!o.png.empty()) {
    if (o.png_index < 0 || o.png_index >= o.k) throw UsageError("--png-index must lie in [0, k)");
    RenderOptions ropt;
    ropt.width = 640;
    ropt.height = 480;
    ropt.isolines = 10;
    ropt.colormap = Colormap::turbo;
    ropt.scalar_label = fmt::format("u{}", o.png_index);
    ropt.title = fmt::format("eigenfunction {}, lambda = {:.4g} ({}, {} mass)", o.png_index, ev[o.png_index], laplacian,
                             o.mass);
    ropt.smooth_shading = true;
    render_png(o.png, mesh, sp.eigenvectors.col(o.png_index).head(n_in), ropt);
    j["png"] = o.png;
  }
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; Laplacian {}, {} mass, shift {:.6g}\n", o.mesh, mesh.n_vertices(),
             mesh.n_faces(), laplacian, o.mass, sp.shift);
  if (engine) fmt::print("engine petsc: {} ranks, {}\n", (*engine)["ranks"].get<int>(), sp.method);
  fmt::print("{} smallest eigenvalues of -S x = lambda M x:\n", o.k);
  for (int i = 0; i < o.k; ++i) fmt::print("  {:4d}  {:.10g}\n", i, ev[i]);
  if (!o.png.empty()) fmt::print("wrote {}\n", o.png);
  if (!o.out.empty())
    fmt::print("wrote eigenvalues.txt, eigenvectors.mtx (|V| x k) and eigenvectors.ply (u000..) to {}\n",
               o.out);
}

const RegisterCommand reg(
    "spectrum", "Smallest eigenpairs of the Laplacian, -S x = lambda M x (Spectra shift-invert)",
    [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("mesh", o->mesh, "input mesh (.obj, .off, .ply)")->required();
      app.add_option("--k", o->k, "number of eigenpairs (default 10)");
      app.add_option("--out", o->out,
                     "output directory: eigenvalues.txt, eigenvectors.mtx, eigenvectors.ply");
      app.add_option("--mass", o->mass, "lumped (default) or unlumped mass");
      app.add_option("--laplacian", o->laplacian,
                     "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")));
      app.add_option("--png", o->png, "picture of one eigenfunction with isolines (.png)");
      app.add_option("--png-index", o->png_index, "which eigenfunction to draw (default 1)");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      add_repair_flag(app, o->repair);
      add_engine_options(app, o->engine);
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::spectrum_command
