// apps/paper/virtual_vertices.h — the "beyond the paper: virtual vertices" section of `polydec paper`:
// the paper's operator with its virtual vertices lifted off the polygons' planes (dec/surface/virtual_lift.h,
// the paper's section 6 asks for it) on the unit-sphere meshes of Tables 2 and 3: mean curvature RMSE
// (eq. 29), spherical-harmonics error (eq. 30, l = 1..8), both with the lumped mass, and the first 100
// eigenvalues' relative errors, for the affine point (the paper's), the closest point on the unit sphere
// and the local quadric lift.
#pragma once

#include <nlohmann/json.hpp>

#include "polydec/dec/mesh/mesh.h"

namespace polydec {

// One mesh's rows, keyed by placement ("affine", "sphere", "quadric"): {"table2", "table3", "spectrum100"
// (sphere_spectrum_errors' object; only when `spectrum`), "virtual_off_sphere" (mean and largest
// | |x_f| - 1 | over the faces), "fan_inverted", "fan_degenerate"}. `sphere` lies on the unit sphere.
nlohmann::json virtual_vertex_rows(const Mesh& sphere, bool spectrum);

// The report section (Markdown) for results["virtual_vertices"] (mesh -> the above); "(not run)" when absent.
std::string virtual_vertices_markdown(const nlohmann::json& results);

}  // namespace polydec
