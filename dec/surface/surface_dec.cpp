// dec/surface/surface_dec.cpp — surface_dec (dec/surface/hodge_star.h): the complex, d_k, P_k and
// star_k of a polygon mesh in one value.
#include <stdexcept>
#include <string>

#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/surface/prolongation.h"

namespace polydec {

SurfaceDec surface_dec(const Mesh& mesh, const Refinement& refinement, int max_degree) {
  return surface_dec(mesh, refinement, SurfaceDecOptions{.max_degree = max_degree});
}

SurfaceDec surface_dec(const Mesh& mesh, const Refinement& refinement, const SurfaceDecOptions& options) {
  const int max_degree = options.max_degree;
  if (max_degree < 0 || max_degree > 2)
    throw std::invalid_argument("surface_dec: max_degree " + std::to_string(max_degree) + " (0..2)");
  SurfaceDec D;
  D.max_degree = max_degree;
  D.complex = options.complex;
  if (options.complex == DecComplex::Mesh) {
    if (max_degree >= 1) D.d[0] = mesh_d0(mesh);
    if (max_degree >= 2) D.d[1] = mesh_d1(mesh);
    D.P[0] = prolongation(mesh, refinement);
    HodgeStarParts parts;
    parts.star0_lumped = parts.star1 = parts.star2 = false;
    HodgeStars stars = hodge_stars(mesh, refinement, CoarseComplex(), parts);
    D.star[0].swap(stars.star0);
    MeshComplexForms F = mesh_complex_forms(
        mesh, refinement, options.spoke_rule,
        {.P1 = max_degree >= 1, .P2 = max_degree >= 2, .star1 = max_degree >= 1, .star2 = max_degree >= 2});
    D.P[1].swap(F.P1);
    D.star[1].swap(F.star1);
    D.P[2].swap(F.P2);
    if (max_degree >= 2) D.star[2] = SparseMatrix(F.star2.asDiagonal());
    return D;
  }
  D.coarse = CoarseComplex(mesh);
  if (max_degree >= 1) D.d[0] = D.coarse.d0();
  if (max_degree >= 2) D.d[1] = D.coarse.d1();
  D.P[0] = prolongation(mesh, refinement);
  if (max_degree >= 1) D.P[1] = prolongation1(mesh, refinement, D.coarse);
  if (max_degree >= 2) D.P[2] = prolongation2(mesh, refinement, D.coarse);
  HodgeStarParts parts;
  parts.star0_lumped = false;
  parts.star1 = max_degree >= 1;
  parts.star2 = max_degree >= 2;
  HodgeStars stars = hodge_stars(mesh, refinement, D.coarse, parts);
  D.star[0].swap(stars.star0);  // swap, not move: std::move copies an Eigen 3.4 SparseMatrix
  D.star[1].swap(stars.star1);
  D.star[2].swap(stars.star2);
  return D;
}

}  // namespace polydec
