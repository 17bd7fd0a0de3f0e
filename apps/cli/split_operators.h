// apps/cli/split_operators.h — `polydec operators MESH --virtual-vertex split`: the operators with several
// virtual vertices in faces whose squared-area fan is invalid (operators/surface/split_laplacian.h).
#pragma once

#include <string>

#include "polydec/dec/mesh/mesh.h"

namespace polydec::cli {

class PhaseTimer;

// Writes S, M, M_lumped, G, D and P (Matrix Market) of the split operators of `mesh` to `out` and
// reports the fan diagnostics before and after the split (one JSON object with `json`, the phases'
// times from `timer`).
void write_split_operators(const Mesh& mesh, const std::string& mesh_path, const std::string& out, bool json,
                           PhaseTimer& timer);

}  // namespace polydec::cli
