// apps/paper/sphere_spectrum.h — one more table of `polydec paper`: the first 100 eigenvalues of
// -S x = lambda M x (lumped M) on unit spheres against the analytic spectrum l(l+1) (multiplicity
// 2l + 1, l = 0..9 gives exactly 100), for every Laplacian, as the 2023 polygon-Laplacian survey
// compares them (docs/spectral.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/virtual_lift.h"

namespace polydec {

// Relative errors |lambda_i / (l(l+1)) - 1| over i = 1..99 for the operator `method` (a name of
// operators/registry/laplacians.h) on `mesh`, its virtual vertices placed by `lift` (OperatorOptions::lift):
// {"mean": ..., "max": ..., "per_band": [l = 1..9 maxima]}. Values are null when the solver fails (the
// message under "error").
nlohmann::json sphere_spectrum_errors(const Mesh& mesh, const std::string& method, const VirtualLift& lift = {});

// The report section (Markdown) for results["spectrum100"] (mesh -> method -> the above).
std::string sphere_spectrum_markdown(const nlohmann::json& results, const std::vector<std::string>& methods);

}  // namespace polydec
