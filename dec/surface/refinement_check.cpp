// dec/surface/refinement_check.cpp — size checks of a surface refinement against its mesh
// (dec/surface/refinement.h): integer compares only, a message on mismatch.
#include <fmt/format.h>

#include <stdexcept>

#include "polydec/dec/surface/refinement.h"

namespace polydec {

void check_refinement(const Mesh& mesh, const Refinement& refinement, const char* caller) {
  const long nF = mesh.n_faces(), nH = mesh.n_halfedges();
  const auto check = [&](long have, long want, const char* what, const char* per) {
    if (have != want)
      throw std::invalid_argument(fmt::format(
          "{}: the refinement does not belong to this mesh ({} faces, {} halfedges): it has {} {} for {} {}",
          caller, nF, nH, have, what, want, per));
  };
  check(refinement.virtual_points.rows(), nF, "virtual points", "faces");
  check(long(refinement.weights.size()), nH, "weights", "halfedges");
  check(long(refinement.fan.size()), nH, "fan triangles", "halfedges");
}

}  // namespace polydec
