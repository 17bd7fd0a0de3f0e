// apps/pictures/image.cpp — raster image, anti-aliased primitives, PNG encoding. This file holds the one
// stb_image_write implementation of the library.
#include "polydec/apps/pictures/image.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "polydec/dec/io/mesh_io.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace polydec {

Image::Image(int w, int h, const Color& fill) : width(w), height(h) {
  if (w <= 0 || h <= 0) throw std::invalid_argument("Image: width and height must be positive");
  rgb.resize(size_t(3) * w * h);
  for (size_t i = 0; i < size_t(w) * h; ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = float(fill[c]);
}

Color Image::pixel(int x, int y) const {
  const size_t i = 3 * (size_t(y) * width + x);
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

void Image::set(int x, int y, const Color& c) {
  if (!contains(x, y)) return;
  const size_t i = 3 * (size_t(y) * width + x);
  for (int k = 0; k < 3; ++k) rgb[i + k] = float(c[k]);
}

void Image::blend(int x, int y, const Color& c, double alpha) {
  if (!contains(x, y) || !(alpha > 0)) return;
  alpha = std::min(alpha, 1.0);
  const size_t i = 3 * (size_t(y) * width + x);
  for (int k = 0; k < 3; ++k) rgb[i + k] = float((1 - alpha) * rgb[i + k] + alpha * c[k]);
}

void Image::fill_rect(int x0, int y0, int x1, int y1, const Color& c) {
  for (int y = std::max(y0, 0); y < std::min(y1, height); ++y)
    for (int x = std::max(x0, 0); x < std::min(x1, width); ++x) set(x, y, c);
}

Image Image::downsample(int k) const {
  if (k == 1) return *this;
  Image out(width / k, height / k, Color::Zero());
  const float inv = 1.0f / float(k * k);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c) {
        float s = 0;
        for (int j = 0; j < k; ++j)
          for (int i = 0; i < k; ++i) s += rgb[3 * (size_t(y * k + j) * width + (x * k + i)) + c];
        out.rgb[3 * (size_t(y) * out.width + x) + c] = s * inv;
      }
  return out;
}

namespace {

// Distance from p to the segment [a, b].
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - a - t * ab).norm();
}

}  // namespace

void draw_line(Image& img, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Color& c, double width) {
  const double r = 0.5 * width + 1;
  const int x0 = int(std::floor(std::min(a.x(), b.x()) - r)), x1 = int(std::ceil(std::max(a.x(), b.x()) + r));
  const int y0 = int(std::floor(std::min(a.y(), b.y()) - r)), y1 = int(std::ceil(std::max(a.y(), b.y()) + r));
  for (int y = std::max(y0, 0); y <= std::min(y1, img.height - 1); ++y)
    for (int x = std::max(x0, 0); x <= std::min(x1, img.width - 1); ++x) {
      const double d = segment_distance({x + 0.5, y + 0.5}, a, b);
      img.blend(x, y, c, std::clamp(0.5 * width + 0.5 - d, 0.0, 1.0));
    }
}

void draw_disc(Image& img, const Eigen::Vector2d& m, double radius, const Color& c) {
  const int x0 = int(std::floor(m.x() - radius - 1)), x1 = int(std::ceil(m.x() + radius + 1));
  const int y0 = int(std::floor(m.y() - radius - 1)), y1 = int(std::ceil(m.y() + radius + 1));
  for (int y = std::max(y0, 0); y <= std::min(y1, img.height - 1); ++y)
    for (int x = std::max(x0, 0); x <= std::min(x1, img.width - 1); ++x) {
      const double d = (Eigen::Vector2d(x + 0.5, y + 0.5) - m).norm();
      img.blend(x, y, c, std::clamp(radius + 0.5 - d, 0.0, 1.0));
    }
}

std::vector<unsigned char> encode_png(const Image& img) {
  std::vector<unsigned char> px(img.rgb.size());
  for (size_t i = 0; i < px.size(); ++i)
    px[i] = (unsigned char)std::lround(255.0 * std::clamp(img.rgb[i], 0.0f, 1.0f));
  std::vector<unsigned char> out;
  auto sink = [](void* ctx, void* data, int size) {
    auto* v = static_cast<std::vector<unsigned char>*>(ctx);
    v->insert(v->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
  };
  if (!stbi_write_png_to_func(sink, &out, img.width, img.height, 3, px.data(), 3 * img.width))
    throw std::runtime_error("PNG encoding failed");
  return out;
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw FileError(path, 0, -1, "cannot open for writing");
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw FileError(path, 0, -1, "write failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw FileError(path, 0, -1, "cannot move the written file into place: " + ec.message());
  }
}

void write_png(const std::string& path, const Image& img) {
  const std::vector<unsigned char> bytes = encode_png(img);
  write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace polydec
