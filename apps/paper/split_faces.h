// apps/paper/split_faces.h — the "beyond the paper: several virtual vertices in one face" section of
// `polydec paper` (the paper's section 6 leaves non-convex faces open; dec/surface/split_refinement.h):
// fan diagnostics before and after splitting, Tables 4 and 6 (heat geodesics, both masses) for the
// split operator beside every single-vertex rule, and the Franke Poisson study on sawtooth grids.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "polydec/dec/mesh/mesh.h"

namespace polydec {

// One planar mesh (source vertex 0, as Tables 4 and 6): {"fans": the split's diagnostics (faces
// affected, inverted and degenerate fan triangles before and after, worst quality 2 area / longest^2
// before and after, faces split, unsplittable, pieces histogram), "table4": method -> RMSE with the
// lumped mass, "table6": method -> RMSE with the Galerkin mass and a delta source, "inverted":
// method -> inverted fan triangles} for ours, centroid, abs-area, convex, trace-min and split.
nlohmann::json split_face_rows(const Mesh& mesh);

// The Franke Poisson study (franke_convergence of apps/applications/poisson.h, family "sawtooth", lumped
// mass) for ours, trace-min and split: method -> {"h", "l2_error", "slope"}, plus "fans" (faces affected at each n).
nlohmann::json split_poisson(const std::vector<int>& resolutions);

// The report section (Markdown) for results["split_faces"] (mesh -> split_face_rows) and
// results["split_poisson"]; "(not run)" when absent.
std::string split_faces_markdown(const nlohmann::json& results);

}  // namespace polydec
