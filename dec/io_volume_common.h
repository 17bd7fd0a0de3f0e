// dec/io_volume_common.h — internal to the volume readers and writers (not installed API): the
// reader result with the line of every vertex, face and cell, and the per-format entry points.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "polydec/dec/io_volume.h"

namespace polydec::io_detail {

// A volume reader's result: the soup plus the 1-based line each vertex, face and cell came
// from (VTK and MEDIT faces are derived from cells: their line is the first cell's).
struct PolyhedronRead {
  PolyhedronSoup soup;
  std::vector<long> vertex_where, face_where, cell_where;
};

PolyhedronRead read_ovm(std::string_view bytes, const std::string& name);
PolyhedronRead read_vtk(std::string_view bytes, const std::string& name);
PolyhedronRead read_medit(std::string_view bytes, const std::string& name);

std::string write_ovm(const VolumeMesh& mesh);
std::string write_vtk(const VolumeMesh& mesh);
std::string write_medit(const VolumeMesh& mesh, const std::string& name);

}  // namespace polydec::io_detail
