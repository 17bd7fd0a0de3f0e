// apps/pictures/image.h — a small RGB raster image (colour values in [0, 1], sRGB-encoded, top row
// first), drawing primitives with analytic anti-aliasing, and PNG output through
// stb_image_write. Shared by the mesh renderer (apps/pictures/render.h) and the plots (apps/pictures/plot.h).
#pragma once

#include "polydec/dec/mesh/eigen_abi.h"
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace polydec {

using Color = Eigen::Vector3d;  // r, g, b in [0, 1]

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 * width * height, row-major, row 0 at the top

  Image() = default;
  Image(int width, int height, const Color& fill);

  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  Color pixel(int x, int y) const;
  void set(int x, int y, const Color& c);
  // c over the pixel with opacity alpha in [0, 1]; ignored outside the image.
  void blend(int x, int y, const Color& c, double alpha);
  // Axis-aligned filled rectangle [x0, x1) x [y0, y1), clipped to the image.
  void fill_rect(int x0, int y0, int x1, int y1, const Color& c);

  // Box-filtered reduction by an integer factor k (width and height divisible by k).
  Image downsample(int k) const;
};

// Anti-aliased line segment of the given width (pixels) between points in pixel coordinates
// (pixel (i, j) covers [i, i+1) x [j, j+1)).
void draw_line(Image& img, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Color& c, double width);
// Anti-aliased filled disc.
void draw_disc(Image& img, const Eigen::Vector2d& centre, double radius, const Color& c);

// PNG bytes (8-bit RGB) of the image.
std::vector<unsigned char> encode_png(const Image& img);
// Writes the PNG to `path` through a temporary file in the same folder renamed into place,
// so a reader never sees a half-written file. Throws FileError (dec/io/mesh_io.h) naming the path.
void write_png(const std::string& path, const Image& img);

// Writes `bytes` to `path` the same way (temporary file `path`.tmp, then rename).
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace polydec
