// apps/pictures/colormap.h — perceptual colour maps for scalar fields: viridis (matplotlib's default,
// van der Walt & Smith 2015) and turbo (Mikhailov, Google 2019).
//
// Each map is a table of 33 colours at t = k/32, derived by sampling the published 256-entry
// tables, and linearly interpolated in between (largest deviation from the published tables:
// 0.0065 for viridis, 0.0069 for turbo, per channel in [0, 1]). The end points are the
// published end colours.
#pragma once

#include <string>
#include <vector>

#include "polydec/apps/pictures/image.h"

namespace polydec {

enum class Colormap { viridis, turbo };

// Colour of t in [0, 1] (clamped; NaN maps to 0).
Color colormap(Colormap map, double t);

// "viridis" or "turbo"; throws std::invalid_argument otherwise.
Colormap parse_colormap(const std::string& name);
std::vector<std::string> colormap_names();

}  // namespace polydec
