// dec/mesh/volume_cells.h — recognizing a cell's shape from its face structure (tetrahedron,
// pyramid, wedge, hexahedron or other polyhedron) and its vertices in VTK's order, for the
// writers and `polydec info`.
#pragma once

#include <array>

#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec {

enum class CellShape { tetrahedron, pyramid, wedge, hexahedron, other };

// Lower-case name: "tetrahedron", "pyramid", "wedge", "hexahedron", "other".
const char* cell_shape_name(CellShape shape);

// The shape of cell c judged by its faces alone (4 triangles; a quadrilateral and 4 triangles;
// 2 triangles and 3 quadrilaterals; 6 quadrilaterals — with the combinatorics of the named
// solid, checked by rebuilding its faces from the VTK order). For the four named shapes,
// `vtk_order` (if given) receives the cell's vertices in VTK's order (dec/mesh/polyhedron_builder.h),
// oriented so that VTK's outward faces are the cell's outward half-faces.
CellShape cell_shape(const VolumeMesh& mesh, int c, std::array<int, 8>* vtk_order = nullptr);

}  // namespace polydec
