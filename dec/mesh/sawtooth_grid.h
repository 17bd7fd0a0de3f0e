// dec/mesh/sawtooth_grid.h — a tiling of the unit square by non-convex polygons whose squared-area
// fans are invalid for deep teeth: the test family of several virtual vertices per face
// (dec/surface/split_refinement.h).
#pragma once

#include "polydec/dec/mesh/mesh.h"

namespace polydec {

// nx x ny cells of [0,1]^2. The horizontal lines between rows are saw-tooth lines with `teeth` teeth per
// cell, each rising by `dent` of a cell's height: cell (i, j) has 2 teeth + 1 corners on its bottom
// and as many on its top, 4 teeth + 2 in all, and is a translate of its neighbours (the square's
// bottom and top sides stay straight, with their corners collinear). teeth = 1 is chevron_grid
// (dec/mesh/generators.h); teeth = 2 with dent >= 0.5 is not star-shaped (no single point sees every
// edge). Throws std::invalid_argument for nx, ny, teeth < 1 or dent outside (0, 1).
Mesh sawtooth_grid(int nx, int ny, int teeth = 2, double dent = 0.7);

}  // namespace polydec
