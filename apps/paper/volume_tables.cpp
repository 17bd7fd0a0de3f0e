// apps/paper/volume_tables.cpp — the Volumes section of the paper report: 3D Poisson convergence on
// the shared cubes and the unit ball's eigenvalue errors.
#include "polydec/apps/paper/volume_tables.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <vector>

#include "polydec/apps/applications/volume/poisson.h"
#include "polydec/apps/applications/volume/spectrum.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec {

namespace {

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

struct CubeFamily {
  const char* name;  // the report's name: `polydec poisson --volume --family NAME`
  const char* file;  // cube_<file>_<level>.ovm
  int levels;        // full run; quick: at most 3
};
constexpr CubeFamily kFamilies[] = {
    {"hex", "hexahedron", 4}, {"pyramids", "pyramids", 4}, {"truncated", "truncated", 4}, {"tetrahedra", "tetrahedron", 2}};

nlohmann::json poisson_rows(const VolumeConvergenceSeries& s) {
  nlohmann::json rows = nlohmann::json::array();
  for (size_t i = 0; i < s.errors.size(); ++i) {
    const auto& e = s.errors[i];
    nlohmann::json r = {{"level", s.levels[i]}, {"vertices", e.n_vertices}, {"cells", e.n_cells},
                        {"h", e.h},             {"l2_error", e.l2_error},   {"rms_error", e.rms_error}};
    if (i > 0) {
      r["l2_slope"] = number(s.l2_slopes[i - 1]);
      r["rms_slope"] = number(s.rms_slopes[i - 1]);
    }
    rows.push_back(r);
  }
  return rows;
}

std::string slope(const nlohmann::json& row, const char* key) {
  return row.contains(key) && row[key].is_number() ? fmt::format("{:.2f}", row[key].get<double>()) : "";
}

}  // namespace

nlohmann::json volume_tables(const std::string& data_dir, bool quick) {
  nlohmann::json out;
  for (const CubeFamily& f : kFamilies) {
    std::vector<VolumeMesh> meshes;
    std::vector<std::string> labels;
    for (int l = 1; l <= (quick ? std::min(f.levels, 3) : f.levels); ++l) {
      labels.push_back(fmt::format("cube_{}_{}.ovm", f.file, l));
      meshes.push_back(read_volume_mesh(data_dir + "/volume/" + labels.back()));
    }
    for (const char* method : {"ours", "diamond"})
      for (const bool lumped : {false, true})
        out["poisson"][method][lumped ? "lumped" : "galerkin"][f.name] =
            poisson_rows(volume_franke_convergence(f.name, meshes, labels, lumped, parse_laplacian(method)));
  }
  const std::vector<int> balls = quick ? std::vector<int>{4, 8} : std::vector<int>{8, 16, 24};
  const int k = 10;
  for (const bool dirichlet : {true, false})
    for (const int n : balls) {
      const BallSpectrum b = ball_spectrum(n, k, dirichlet);
      double mx = 0;
      nlohmann::json analytic = nlohmann::json::array();
      for (size_t i = 0; i < b.analytic.size(); ++i) {
        analytic.push_back({{"lambda", b.analytic[i].lambda}, {"l", b.analytic[i].l}, {"n", b.analytic[i].n}});
        if (b.analytic[i].lambda > 0) mx = std::max(mx, b.relative_error[i]);
      }
      out["ball"][dirichlet ? "dirichlet" : "neumann"].push_back(
          {{"n", n}, {"vertices", b.n_vertices}, {"cells", b.n_cells}, {"h", b.h}, {"eigenvalues", b.eigenvalues},
           {"analytic", analytic}, {"relative_error", b.relative_error}, {"max_error", mx}, {"method", b.method}});
    }
  out["setup"] = {
      {"poisson", fmt::format("polydec poisson --volume --family F --data {}/volume --levels 1..{} "
                              "--laplacian ours|diamond [--mass lumped]; tetrahedra levels 1..2",
                              data_dir, quick ? 3 : 4)},
      {"ball", fmt::format("polydec volume-spectrum --ball N --k {} [--dirichlet], N in {}", k,
                           fmt::join(balls, ", "))}};
  return out;
}

std::string volume_tables_markdown(const nlohmann::json& results) {
  std::string s = "## Volumes: 3D Poisson convergence and the unit ball's spectrum\n\n";
  if (!results.contains("volumes")) return s + "(not run)\n\n";
  const nlohmann::json& v = results["volumes"];
  s += "The polyhedral Laplacian of docs/volumes.md (`ours`: virtual face and cell points, sub-tetrahedra, "
       "S = P^T S^tet P) and the Diamond Laplacian [BBA21] on the same points (`diamond`, with its own mass as "
       "'Galerkin', the authors' set-up, and that mass's row sums as 'lumped').\n\n";
  s += "### Franke Poisson problem on the shared cube families\n\n"
       "Delta f = b in the unit cube, f = f* at the boundary vertices, S f = M b at the interior ones "
       "(apps/applications/volume/poisson.h). Errors at the vertices: L2 = sqrt(e^T M e), RMS = polyLaplace's "
       "sqrt(sum_v e_v^2 / |V|) over all vertices; h = mean edge length; slopes log(e_{i+1}/e_i) / log(h_{i+1}/h_i) "
       "per refinement step (2 expected asymptotically). The `truncated` files hold, per cube of a grid, a "
       "cuboctahedron and its 8 corner tetrahedra (docs/volumes.md). Command: `" +
       v["setup"]["poisson"].get<std::string>() + "`.\n\n";
  for (const char* method : {"ours", "diamond"}) {
    if (!v["poisson"].contains(method)) continue;
    for (const auto& [mass, families] : v["poisson"][method].items()) {
      s += fmt::format("`{}`, {} mass:\n\n", method, mass == "galerkin" ? "Galerkin" : "lumped");
      s += "| family | mesh | V | h | L2 | RMS | slope L2 | slope RMS |\n|---|---|---:|---:|---:|---:|---:|---:|\n";
      for (const auto& [family, rows] : families.items())
        for (const auto& r : rows)
          s += fmt::format("| {} | {} | {} | {:.4f} | {:.3e} | {:.3e} | {} | {} |\n", family,
                           r["level"].get<std::string>(), r["vertices"].get<int>(), r["h"].get<double>(),
                           r["l2_error"].get<double>(), r["rms_error"].get<double>(), slope(r, "l2_slope"),
                           slope(r, "rms_slope"));
      s += "\n";
    }
  }
  s += "### Eigenvalues of the unit ball\n\n"
       "-S x = lambda M x (Galerkin M) on hex_ball_volume(n) (a [-1,1]^3 grid of n^3 hexahedra mapped to the "
       "ball), against Dirichlet j_{l,k}^2 and Neumann j'_{l,k}^2 (zeros of spherical Bessel functions and "
       "their derivatives, multiplicity 2l + 1); relative errors of the 10 smallest (Neumann: without the zero "
       "eigenvalue). Command: `" +
       v["setup"]["ball"].get<std::string>() + "`.\n\n";
  s += "| boundary | n | V | h | max error | relative error per eigenvalue (%) |\n|---|---:|---:|---:|---:|---|\n";
  for (const auto& [bc, runs] : v["ball"].items())
    for (const auto& b : runs) {
      std::vector<std::string> per;
      const auto& an = b["analytic"];
      for (size_t i = 0; i < an.size(); ++i)
        if (an[i]["lambda"].get<double>() > 0) per.push_back(fmt::format("{:.2f}", 100 * b["relative_error"][i].get<double>()));
      s += fmt::format("| {} | {} | {} | {:.4f} | {:.2f}% | {} |\n", bc, b["n"].get<int>(), b["vertices"].get<int>(),
                       b["h"].get<double>(), 100 * b["max_error"].get<double>(), fmt::format("{}", fmt::join(per, ", ")));
    }
  return s + "\n";
}

}  // namespace polydec
