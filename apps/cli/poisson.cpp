// apps/cli/poisson.cpp — `polydec poisson`: the convergence study of the paper's section 5.8
// (Figure 9), Franke's function on triangle, quad and hexagon grids of the unit square.
#include "apps/cli/command.h"
#include "apps/poisson.h"

#include <fmt/format.h>

namespace polydec::cli {
namespace {

struct Options {
  std::vector<int> resolutions{8, 16, 32, 64};
  std::string mass = "lumped", laplacian = "ours";
  bool json = false;
};

void run(const Options& o) {
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  ConvergenceOptions copt;
  copt.resolutions = o.resolutions;
  copt.lumped_mass = o.mass == "lumped";
  copt.laplacian = parse_laplacian(o.laplacian);
  const auto series = franke_convergence(copt);
  nlohmann::json fam = nlohmann::json::object();
  for (const auto& s : series) {
    nlohmann::json rows = nlohmann::json::array();
    for (size_t i = 0; i < s.errors.size(); ++i)
      rows.push_back({{"n", s.resolutions[i]},
                      {"vertices", s.errors[i].n_vertices},
                      {"h", s.errors[i].h},
                      {"l2_error", s.errors[i].l2_error}});
    fam[s.family] = {{"slope", s.slope}, {"levels", rows}};
  }
  const nlohmann::json j = {{"laplacian", copt.laplacian.canonical_name()}, {"mass", o.mass}, {"families", fam}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("Poisson problem Delta f = b, Franke function, Dirichlet boundary, unit square; Laplacian {}, {} mass\n",
             copt.laplacian.canonical_name(), o.mass);
  for (const auto& s : series) {
    fmt::print("{}: fitted slope of log(L2 error) vs log(h) = {:.3f}\n", s.family, s.slope);
    for (size_t i = 0; i < s.errors.size(); ++i)
      fmt::print("  n = {:4d}  |V| = {:6d}  h = {:.5f}  L2 error = {:.6e}\n", s.resolutions[i], s.errors[i].n_vertices,
                 s.errors[i].h, s.errors[i].l2_error);
  }
}

const RegisterCommand reg("poisson", "Convergence of the Poisson problem for Franke's function (paper section 5.8)",
                          [](CLI::App& app) {
                            auto o = std::make_shared<Options>();
                            app.add_option("--resolutions", o->resolutions, "grid resolutions n (n x n cells), default 8 16 32 64");
                            app.add_option("--mass", o->mass, "lumped (default) or unlumped mass");
                            app.add_option("--laplacian", o->laplacian,
                                           "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")));
                            app.add_flag("--json", o->json, "print one JSON object instead of text");
                            app.callback([o] { run(*o); });
                          });

}  // namespace
}  // namespace polydec::cli
