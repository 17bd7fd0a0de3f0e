// dec/volume/refinement_check.cpp — size checks of a volume refinement against its mesh
// (dec/volume/refinement.h): integer compares only, a message on mismatch.
#include <fmt/format.h>

#include <stdexcept>
#include <string>

#include "polydec/dec/volume/refinement.h"

namespace polydec {

namespace refinement_check_detail {
namespace {

[[noreturn]] void refuse(const char* caller, const std::string& mesh, const std::string& what) {
  throw std::invalid_argument(
      fmt::format("{}: the refinement does not belong to this mesh ({}): {}", caller, mesh, what));
}

std::string describe(const VolumeMesh& m) {
  return fmt::format("{} faces, {} cells", m.n_faces(), m.n_cells());
}

// The arrays' sizes: face points and weights, cell points, both offset arrays.
void check_volume_arrays(const VolumeMesh& m, const VolumeRefinement& r, const char* caller) {
  const long nF = m.n_faces(), nC = m.n_cells(), corners = long(m.face_indices().size());
  if (r.face_points.rows() != nF)
    refuse(caller, describe(m), fmt::format("it has {} face points for {} faces", r.face_points.rows(), nF));
  if (long(r.face_weights.size()) != corners)
    refuse(caller, describe(m),
           fmt::format("it has {} face weights for {} face corners", r.face_weights.size(), corners));
  if (r.cell_points.rows() != nC)
    refuse(caller, describe(m), fmt::format("it has {} cell points for {} cells", r.cell_points.rows(), nC));
  if (long(r.cell_weight_offsets.size()) != nC + 1)
    refuse(caller, describe(m),
           fmt::format("it has {} cell weight offsets for {} cells", r.cell_weight_offsets.size(), nC));
  if (long(r.tet_offsets.size()) != nC + 1)
    refuse(caller, describe(m),
           fmt::format("it has {} sub-tetrahedron offsets for {} cells", r.tet_offsets.size(), nC));
}

// Cell c's counts: as many weights as vertices, as many sub-tetrahedra as face corners.
void check_volume_cell(const VolumeMesh& m, const VolumeRefinement& r, int c, const char* caller) {
  const long weights = long(r.cell_weight_offsets[c + 1]) - r.cell_weight_offsets[c];
  if (weights != long(m.cell_vertices(c).size()))
    refuse(caller, describe(m),
           fmt::format("cell {} has {} weights for {} vertices", c, weights, m.cell_vertices(c).size()));
  long corners = 0;
  for (int hf : m.cell(c)) corners += m.face_size(hf / 2);
  const long tets = long(r.tet_offsets[c + 1]) - r.tet_offsets[c];
  if (tets != corners)
    refuse(caller, describe(m),
           fmt::format("cell {} has {} sub-tetrahedra for {} face corners", c, tets, corners));
}

}  // namespace
}  // namespace refinement_check_detail

void check_refinement(const VolumeMesh& mesh, const VolumeRefinement& refinement, const char* caller) {
  using namespace refinement_check_detail;
  const VolumeRefinement& r = refinement;
  check_volume_arrays(mesh, r, caller);
  const int nC = mesh.n_cells();
  if (r.cell_weight_offsets[0] != 0 || r.tet_offsets[0] != 0)
    refuse(caller, describe(mesh),
           fmt::format("its cell weight and sub-tetrahedron offsets start at {} and {} instead of 0",
                       r.cell_weight_offsets[0], r.tet_offsets[0]));
  for (int c = 0; c < nC; ++c) check_volume_cell(mesh, r, c, caller);
  if (size_t(r.cell_weight_offsets[nC]) != r.cell_weights.size())
    refuse(caller, describe(mesh),
           fmt::format("it has {} cell weights for offsets ending at {}", r.cell_weights.size(),
                       r.cell_weight_offsets[nC]));
  if (size_t(r.tet_offsets[nC]) != r.tets.size())
    refuse(
        caller, describe(mesh),
        fmt::format("it has {} sub-tetrahedra for offsets ending at {}", r.tets.size(), r.tet_offsets[nC]));
}

void check_refinement_cell(const VolumeMesh& mesh, const VolumeRefinement& refinement, int c,
                           const char* caller) {
  using namespace refinement_check_detail;
  const VolumeRefinement& r = refinement;
  if (c < 0 || c >= mesh.n_cells())
    throw std::invalid_argument(
        fmt::format("{}: cell {} out of range ({} cells)", caller, c, mesh.n_cells()));
  check_volume_arrays(mesh, r, caller);
  check_volume_cell(mesh, r, c, caller);
  if (r.cell_weight_offsets[c] < 0 || size_t(r.cell_weight_offsets[c + 1]) > r.cell_weights.size())
    refuse(caller, describe(mesh),
           fmt::format("cell {}'s weights {} .. {} lie outside its {} cell weights", c,
                       r.cell_weight_offsets[c], r.cell_weight_offsets[c + 1], r.cell_weights.size()));
  if (r.tet_offsets[c] < 0 || size_t(r.tet_offsets[c + 1]) > r.tets.size())
    refuse(caller, describe(mesh),
           fmt::format("cell {}'s sub-tetrahedra {} .. {} lie outside its {} sub-tetrahedra", c,
                       r.tet_offsets[c], r.tet_offsets[c + 1], r.tets.size()));
}

void check_refined_vertex(const VolumeMesh& mesh, const VolumeRefinement& refinement, int r,
                          const char* caller) {
  using namespace refinement_check_detail;
  const long nV = mesh.n_vertices(), nF = mesh.n_faces(), nC = mesh.n_cells();
  if (r < 0 || r >= nV + nF + nC)
    throw std::invalid_argument(fmt::format(
        "{}: refined vertex {} out of range ({} + {} + {} refined vertices)", caller, r, nV, nF, nC));
  if (refinement.face_points.rows() != nF)
    refuse(caller, describe(mesh),
           fmt::format("it has {} face points for {} faces", refinement.face_points.rows(), nF));
  if (refinement.cell_points.rows() != nC)
    refuse(caller, describe(mesh),
           fmt::format("it has {} cell points for {} cells", refinement.cell_points.rows(), nC));
}

}  // namespace polydec
