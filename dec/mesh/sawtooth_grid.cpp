// dec/mesh/sawtooth_grid.cpp — the saw-tooth tiling of the unit square.
#include "polydec/dec/mesh/sawtooth_grid.h"

#include <stdexcept>
#include <vector>

namespace polydec {

Mesh sawtooth_grid(int nx, int ny, int teeth, double dent) {
  if (nx < 1 || ny < 1 || teeth < 1) throw std::invalid_argument("sawtooth_grid: needs nx, ny, teeth >= 1");
  if (!(dent > 0 && dent < 1)) throw std::invalid_argument("sawtooth_grid: dent must lie in (0, 1)");
  if (double(nx) * teeth * (ny + 1) > 1e8) throw std::invalid_argument("sawtooth_grid: too many vertices");
  const int per_cell = 2 * teeth, per_line = nx * per_cell + 1;
  PolygonSoup s;
  s.positions.resize(long(ny + 1) * per_line, 3);
  for (int j = 0; j <= ny; ++j)
    for (int k = 0; k < per_line; ++k) {
      const bool raised = k % 2 == 1 && j > 0 && j < ny;
      s.positions.row(long(j) * per_line + k) << double(k) / (nx * per_cell), (j + (raised ? dent : 0.0)) / ny, 0.0;
    }
  std::vector<int> face;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      face.clear();
      for (int k = 0; k <= per_cell; ++k) face.push_back(j * per_line + i * per_cell + k);
      for (int k = per_cell; k >= 0; --k) face.push_back((j + 1) * per_line + i * per_cell + k);
      s.add_face(face);
    }
  return Mesh(std::move(s));
}

}  // namespace polydec
