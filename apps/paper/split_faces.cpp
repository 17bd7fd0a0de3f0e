// apps/paper/split_faces.cpp — Tables 4 and 6 and the Poisson study with several virtual vertices per face.
#include "polydec/apps/paper/split_faces.h"

#include <fmt/format.h>

#include <cmath>

#include "polydec/apps/applications/geodesics.h"
#include "polydec/apps/applications/poisson.h"
#include "polydec/dec/mesh/sawtooth_grid.h"
#include "polydec/dec/surface/split_refinement.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec {

namespace {

const char* const kRules[] = {"ours", "centroid", "abs-area", "convex", "trace-min", "split"};
const char* const kPoissonRules[] = {"ours", "trace-min", "split"};

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json quality(const FanQuality& q) {
  return {{"faces_affected", q.n_faces_affected}, {"inverted", q.n_inverted}, {"degenerate", q.n_degenerate}};
}

std::string cell(const nlohmann::json& x, const char* spec) {
  return x.is_number() ? fmt::format(fmt::runtime(spec), x.get<double>()) : std::string("–");
}

}  // namespace

nlohmann::json split_face_rows(const Mesh& mesh) {
  nlohmann::json out;
  const SplitRefinement s = split_refine(mesh);
  out["fans"] = {{"before", quality(s.before)},       {"after", quality(s.after)},
                 {"worst_before", number(s.worst_before)}, {"worst_after", number(s.worst_after)},
                 {"faces", mesh.n_faces()},           {"faces_split", s.n_faces_split},
                 {"unsplittable", s.n_faces_unsplittable}, {"pieces_histogram", s.pieces_histogram},
                 {"pieces", s.n_pieces()}};
  Eigen::VectorXd e(mesh.n_vertices());
  for (int v = 0; v < mesh.n_vertices(); ++v) e[v] = (mesh.position(v) - mesh.position(0)).norm();
  e.array() -= e.minCoeff();
  const double h = mesh.mean_edge_length();
  for (const char* m : kRules) {
    const OperatorSet ops = build_operators(mesh, parse_laplacian(m), true);
    out["inverted"][m] = ops.quality.n_inverted;
    out["table4"][m] = number(rmse(HeatGeodesics(ops, h, {}).distance(0), e));
    HeatGeodesicsOptions unlumped;
    unlumped.lumped_mass = false;
    unlumped.mass_weighted_source = false;
    out["table6"][m] = number(rmse(HeatGeodesics(ops, h, unlumped).distance(0), e));
  }
  return out;
}

nlohmann::json split_poisson(const std::vector<int>& resolutions) {
  nlohmann::json out;
  for (const char* m : kPoissonRules) {
    ConvergenceOptions c;  // `polydec poisson --family sawtooth --laplacian M`
    c.resolutions = resolutions;
    c.laplacian = parse_laplacian(m);
    c.families = {"sawtooth"};
    const ConvergenceSeries series = franke_convergence(c).front();
    std::vector<double> h, err;
    for (const PoissonError& e : series.errors) {
      h.push_back(e.h);
      err.push_back(e.l2_error);
    }
    out[m] = {{"h", h}, {"l2_error", err}, {"slope", number(series.slope)}};
  }
  for (int n : resolutions) {
    const SplitRefinement s = split_refine(sawtooth_grid(n, n));
    out["fans"].push_back({{"n", n}, {"faces", n * n}, {"before", quality(s.before)}, {"faces_split", s.n_faces_split}});
  }
  out["resolutions"] = resolutions;
  return out;
}

std::string split_faces_markdown(const nlohmann::json& r) {
  std::string s =
      "## Beyond the paper: several virtual vertices in one face\n\n"
      "**Not in the paper** (its section 6 leaves non-convex faces open; docs/extensions.md). A face whose "
      "squared-area fan has an inverted or degenerate triangle is cut by interior diagonals into the fewest pieces "
      "(2 to 4) whose own squared-area fans are valid; one virtual vertex per piece, S = P^T S^f P (`--laplacian "
      "split`). Faces with a valid fan are unchanged. Fans: faces with an invalid fan / inverted fan triangles, "
      "before -> after; worst: the smallest 2 area / longest edge^2 of a fan triangle. Tables 4 and 6 as above: "
      "`polydec geodesics MESH --source 0 --laplacian RULE --euclidean` (lumped) and with `--mass unlumped "
      "--delta-source` (Table 6's un-lumped column).\n\n";
  if (!r.contains("split_faces")) return s + "(not run)\n\n";
  s += "| mesh | faces split / all | fans affected | inverted | worst | table | ours | centroid | abs-area | convex | "
       "trace-min | split |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [mesh, row] : r["split_faces"].items()) {
    const auto& f = row["fans"];
    for (const char* t : {"table4", "table6"}) {
      const bool first = std::string(t) == "table4";
      s += fmt::format("| {} | {} | {} | {} | {} | {} |", first ? mesh : "",
                       first ? fmt::format("{} / {}", f["faces_split"].get<int>(), f["faces"].get<int>()) : "",
                       first ? fmt::format("{} -> {}", f["before"]["faces_affected"].get<int>(),
                                           f["after"]["faces_affected"].get<int>())
                             : "",
                       first ? fmt::format("{} -> {}", f["before"]["inverted"].get<int>(), f["after"]["inverted"].get<int>())
                             : "",
                       first ? fmt::format("{} -> {}", cell(f["worst_before"], "{:.3f}"), cell(f["worst_after"], "{:.3f}")) : std::string(),
                       first ? "4 (lumped)" : "6 (un-lumped)");
      for (const char* m : kRules) s += fmt::format(" {} |", cell(row[t][m], "{:.4f}"));
      s += "\n";
    }
  }
  s += "\n";
  if (r.contains("split_poisson")) {
    const auto& p = r["split_poisson"];
    s += "Franke Poisson problem (Figure 9's, lumped mass) on `sawtooth_grid(n, n)` (two teeth of 0.7 cell "
         "heights per cell edge: every cell above the bottom row has an invalid squared-area fan); L2 errors and "
         "the fitted slope against h:\n\n| n |";
    for (const char* m : kPoissonRules) s += fmt::format(" {} |", m);
    s += "\n|---|";
    for (size_t k = 0; k < std::size(kPoissonRules); ++k) s += "---|";
    s += "\n";
    for (size_t i = 0; i < p["resolutions"].size(); ++i) {
      s += fmt::format("| {} |", p["resolutions"][i].get<int>());
      for (const char* m : kPoissonRules) s += fmt::format(" {} |", cell(p[m]["l2_error"][i], "{:.4e}"));
      s += "\n";
    }
    s += "| slope |";
    for (const char* m : kPoissonRules) s += fmt::format(" {} |", cell(p[m]["slope"], "{:.3f}"));
    s += "\n\n";
  }
  return s;
}

}  // namespace polydec
