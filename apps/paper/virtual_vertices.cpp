// apps/paper/virtual_vertices.cpp — Tables 2 and 3 and the sphere spectrum with lifted virtual vertices.
#include "polydec/apps/paper/virtual_vertices.h"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "polydec/apps/applications/curvature.h"
#include "polydec/apps/applications/harmonics.h"
#include "polydec/apps/paper/sphere_spectrum.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec {

namespace {

// The placements compared: key, lift, label in the report.
struct Placement {
  const char* key;
  const char* lift;
  const char* label;
};
const Placement kPlacements[] = {{"affine", "none", "affine point (the paper's)"},
                                 {"sphere", "sphere:0,0,0,1", "closest point on the unit sphere"},
                                 {"quadric", "quadric", "local quadric lift"}};

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

}  // namespace

nlohmann::json virtual_vertex_rows(const Mesh& sphere, bool spectrum) {
  nlohmann::json out = nlohmann::json::object();
  for (const Placement& p : kPlacements) {
    nlohmann::json& row = out[p.key];
    OperatorOptions o;
    o.with_gradient = false;
    o.lift = parse_virtual_lift(p.lift);
    const OperatorSet ops = build_operators(sphere, parse_laplacian("ours"), o);
    row["laplacian"] = ops.name;
    const Eigen::VectorXd H = mean_curvature(ops);
    row["table2"] = number(curvature_rmse(H.head(ops.n_input_vertices), 1.0));
    HarmonicsOptions h;
    h.max_band = 8;
    row["table3"] = number(spherical_harmonics_error(ops, h).sum(8));
    row["fan_inverted"] = ops.quality.n_inverted;
    row["fan_degenerate"] = ops.quality.n_degenerate;
    RefinementOptions ro;
    ro.lift = o.lift;
    const Refinement r = refine(sphere, ro);
    double sum = 0, mx = 0;
    for (int f = 0; f < sphere.n_faces(); ++f) {
      const double d = std::abs(r.virtual_points.row(f).norm() - 1);
      sum += d;
      mx = std::max(mx, d);
    }
    row["virtual_off_sphere"] = {{"mean", sum / std::max(1, sphere.n_faces())}, {"max", mx}};
    if (spectrum) row["spectrum100"] = sphere_spectrum_errors(sphere, "ours", o.lift);
  }
  return out;
}

std::string virtual_vertices_markdown(const nlohmann::json& results) {
  std::string s =
      "## Beyond the paper: virtual vertices off the plane\n\n"
      "**Not in the paper** (its section 6 proposes it). The weights of the squared-area rule keep defining the "
      "prolongation P; only the position of each face's virtual vertex, where the fan triangles meet, moves: the "
      "affine point (the paper's operator, `ours`), the closest point on the unit sphere "
      "(`--virtual-lift sphere:0,0,0,1`), or the local quadric lift (`--virtual-lift quadric`; docs/extensions.md). "
      "Lumped mass. Table 2: `polydec curvature MESH --unit-sphere --virtual-lift LIFT --json`; Table 3: "
      "`polydec harmonics MESH --virtual-lift LIFT --json`; spectrum: `polydec spectrum MESH --k 100 --virtual-lift "
      "LIFT` on the projected mesh. \"off sphere\": mean | |x_f| - 1 | of the virtual vertices.\n\n";
  if (!results.contains("virtual_vertices")) return s + "(not run)\n\n";
  auto v = [](const nlohmann::json& x, const char* fmt_spec) {
    return x.is_number() ? fmt::format(fmt::runtime(fmt_spec), x.get<double>()) : std::string("–");
  };
  s += "| mesh | virtual vertex | Table 2 RMSE | Table 3 error | spectrum mean | spectrum max | off sphere | "
       "inverted fans |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& [mesh, rows] : results["virtual_vertices"].items())
    for (const Placement& p : kPlacements) {
      if (!rows.contains(p.key)) continue;
      const nlohmann::json& r = rows[p.key];
      const nlohmann::json none;
      const nlohmann::json& sp = r.contains("spectrum100") ? r["spectrum100"] : none;
      s += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} |\n", mesh, p.label, v(r["table2"], "{:.4e}"),
                       v(r["table3"], "{:.4e}"), sp.is_object() ? v(sp["mean"], "{:.3e}") : "–",
                       sp.is_object() ? v(sp["max"], "{:.3e}") : "–", v(r["virtual_off_sphere"]["mean"], "{:.2e}"),
                       r.value("fan_inverted", 0));
    }
  return s + "\n";
}

}  // namespace polydec
