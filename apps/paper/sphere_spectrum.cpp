// apps/paper/sphere_spectrum.cpp — the unit sphere's first 100 eigenvalues against l(l+1), every Laplacian.
#include "polydec/apps/paper/sphere_spectrum.h"

#include <fmt/format.h>

#include <cmath>

#include "polydec/apps/applications/spectrum.h"
#include "polydec/operators/solvers/cholesky.h"

namespace polydec {

nlohmann::json sphere_spectrum_errors(const Mesh& mesh, const std::string& method, const VirtualLift& lift) {
  nlohmann::json out;
  try {
    OperatorOptions options;
    options.with_gradient = false;
    options.lift = lift;
    const OperatorSet ops = build_operators(mesh, parse_laplacian(method), options);
    SpectrumOptions o;
    o.k = 100;
    const Spectrum sp = laplacian_spectrum(ops, o);
    double sum = 0, mx = 0;
    std::vector<double> band(9, 0.0);
    int i = 1;
    for (int l = 1; l <= 9; ++l)
      for (int c = 0; c < 2 * l + 1; ++c, ++i) {
        const double e = std::abs(sp.eigenvalues[i] / (l * (l + 1.0)) - 1);
        sum += e;
        mx = std::max(mx, e);
        band[size_t(l - 1)] = std::max(band[size_t(l - 1)], e);
      }
    out = {{"mean", sum / 99}, {"max", mx}, {"per_band", band}, {"lambda_0", sp.eigenvalues[0]}};
  } catch (const std::exception& e) {
    out = {{"mean", nullptr}, {"max", nullptr}, {"error", e.what()}};
  }
  return out;
}

std::string sphere_spectrum_markdown(const nlohmann::json& r, const std::vector<std::string>& methods) {
  std::string s =
      "## Spectrum: the unit sphere's first 100 eigenvalues\n\n"
      "-S x = lambda M x (lumped M, `polydec spectrum`) against l(l+1), l = 0..9 with multiplicity 2l + 1 "
      "(exactly 100 eigenvalues); mean and largest relative error |lambda_i / l(l+1) - 1| over i = 1..99, as "
      "the "
      "2023 polygon-Laplacian survey compares them (docs/spectral.md).\n\n";
  if (!r.contains("spectrum100")) return s + "(not run)\n\n";
  s += "| mesh | error |";
  std::vector<std::string> cols;
  for (const std::string& m : methods)
    for (const auto& [mesh, row] : r["spectrum100"].items())
      if (row.contains(m)) {
        cols.push_back(m);
        break;
      }
  for (const std::string& c : cols) s += " " + c + " |";
  s += "\n|---|---|";
  for (size_t i = 0; i < cols.size(); ++i) s += "---|";
  s += "\n";
  auto value = [](const nlohmann::json& v) {
    return v.is_number() ? fmt::format("{:.3e}", v.get<double>()) : std::string("–");
  };
  for (const auto& [mesh, row] : r["spectrum100"].items())
    for (const char* what : {"mean", "max"}) {
      s += fmt::format("| {} | {} |", mesh, what);
      for (const std::string& c : cols)
        s += fmt::format(" {} |", row.contains(c) ? value(row[c][what]) : "–");
      s += "\n";
    }
  return s + "\n";
}

}  // namespace polydec
