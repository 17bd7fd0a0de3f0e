// apps/pictures/plot.h — small 2D plots written as SVG or PNG: a log-log convergence plot (error against
// mesh size h, several named series with markers and lines, decade ticks, a legend with each
// series' fitted slope) and, with the log scales switched off, a plain line plot.
//
// Usage:
//   std::vector<PlotSeries> s = {{"quads", h_quad, err_quad}, {"hexagons", h_hex, err_hex}};
//   write_plot("convergence.svg", s, {.title = "Poisson, Franke function"});
//
// On a log axis, points with a non-positive or non-finite coordinate are left out (and do not
// count in the fit). Each series gets its own colour and marker (circle, square, triangle,
// diamond, ...). The SVG marks every data marker with class="marker" and every series line
// with class="series", for tools and tests.
#pragma once

#include <string>
#include <vector>

#include "polydec/apps/pictures/image.h"

namespace polydec {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;  // same length
};

struct PlotOptions {
  std::string title;
  std::string x_label = "h";
  std::string y_label = "error";
  int width = 640, height = 480;  // pixels (SVG user units)
  bool log_x = true, log_y = true;
  bool fit_slopes = true;  // "name (slope 2.01)" in the legend; log-log plots only
  bool lines = true, markers = true;
};

// The plot as SVG text. Throws std::invalid_argument for series with x and y of different
// lengths or invalid sizes.
std::string plot_svg(const std::vector<PlotSeries>& series, const PlotOptions& options);
// The same plot drawn with the built-in raster primitives and 5x7 font.
Image plot_image(const std::vector<PlotSeries>& series, const PlotOptions& options);

// Writes SVG (".svg") or PNG (".png"), chosen by the extension, atomically (temporary file,
// then rename). Throws FileError naming the path when it cannot be written, and
// std::invalid_argument for another extension.
void write_plot(const std::string& path, const std::vector<PlotSeries>& series, const PlotOptions& options);

}  // namespace polydec
