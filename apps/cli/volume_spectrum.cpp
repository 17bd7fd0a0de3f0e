// apps/cli/volume_spectrum.cpp — `polydec volume-spectrum`: the smallest eigenvalues of the volume Laplacian
// on a generated hexahedral unit ball against the analytic ones (zeros of spherical Bessel functions).
#include "polydec/apps/applications/volume/spectrum.h"

#include <fmt/format.h>

#include "polydec/apps/cli/command.h"

namespace polydec::cli::volume_spectrum_command {
namespace {

struct Options {
  int ball = 8, k = 10;
  bool dirichlet = false, json = false;
  std::string mass = "unlumped";
};

void run(const Options& o) {
  if (o.ball < 2) throw UsageError("--ball must be >= 2");
  if (o.k < 1) throw UsageError("--k must be >= 1");
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  PhaseTimer timer;  // the generated ball, its operators and the eigensolver: "solve"
  const BallSpectrum b = timer.time("solve", [&] { return ball_spectrum(o.ball, o.k, o.dirichlet, o.mass == "lumped"); });
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < o.k; ++i) {
    const BallEigenvalue& a = b.analytic[size_t(i)];
    rows.push_back({{"eigenvalue", b.eigenvalues[size_t(i)]},
                    {"analytic", a.lambda},
                    {"l", a.l},
                    {"n", a.n},
                    {"relative_error", b.relative_error[size_t(i)]}});
  }
  const nlohmann::json j = {{"mesh", fmt::format("hex_ball_volume({})", o.ball)},
                            {"vertices", b.n_vertices},
                            {"cells", b.n_cells},
                            {"h", b.h},
                            {"boundary", o.dirichlet ? "dirichlet" : "neumann"},
                            {"mass", o.mass},
                            {"method", b.method},
                            {"eigenvalues", rows},
                            {"times_ms", timer.json()}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print(
      "-S x = lambda M x on hex_ball_volume({}) (|V| = {}, |C| = {}, h = {:.5f}), {} boundary, {} mass\n",
      o.ball, b.n_vertices, b.n_cells, b.h, o.dirichlet ? "Dirichlet" : "Neumann", o.mass);
  fmt::print("  {:>3s}  {:>14s}  {:>14s}  {:>3s} {:>3s}  {:>10s}\n", "i", "lambda_h", "lambda (ball)", "l",
             "n", "rel. error");
  for (int i = 0; i < o.k; ++i) {
    const BallEigenvalue& a = b.analytic[size_t(i)];
    fmt::print("  {:3d}  {:14.8f}  {:14.8f}  {:3d} {:3d}  {:10.3e}{}\n", i, b.eigenvalues[size_t(i)],
               a.lambda, a.l, a.n, b.relative_error[size_t(i)], a.lambda > 0 ? "" : " (absolute)");
  }
}

const RegisterCommand reg(
    "volume-spectrum",
    "Smallest eigenvalues of the volume Laplacian on a hexahedral unit ball vs the analytic ones",
    [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("--ball", o->ball, "resolution n of hex_ball_volume(n) (default 8)");
      app.add_option("--k", o->k, "number of eigenvalues (default 10)");
      app.add_flag("--dirichlet", o->dirichlet,
                   "boundary vertices removed (default: Neumann, all vertices free)");
      app.add_option("--mass", o->mass, "unlumped (Galerkin, default) or lumped mass");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::volume_spectrum_command
