// dec/mesh/polyhedron_builder.cpp — face identification by vertex set for PolyhedronSoupBuilder.
#include "polydec/dec/mesh/polyhedron_builder.h"

#include <algorithm>

namespace polydec {
namespace polyhedron_builder_detail {
namespace {

unsigned long long hash_sorted(const std::vector<int>& key) {
  unsigned long long h = 1469598103934665603ull ^ key.size();
  for (int v : key) {
    h ^= (unsigned long long)(unsigned)v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h *= 1099511628211ull;
  }
  return h;
}

const std::vector<std::vector<int>> kTetra{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
const std::vector<std::vector<int>> kHexahedron{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
const std::vector<std::vector<int>> kWedge{{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}};
const std::vector<std::vector<int>> kPyramid{{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
const std::vector<std::vector<int>> kNone;

}  // namespace
}  // namespace polyhedron_builder_detail

const std::vector<std::vector<int>>& vtk_cell_faces(int vtk_type) {
  using namespace polyhedron_builder_detail;
  switch (vtk_type) {
    case kVtkTetra:
      return kTetra;
    case kVtkHexahedron:
      return kHexahedron;
    case kVtkWedge:
      return kWedge;
    case kVtkPyramid:
      return kPyramid;
    default:
      return kNone;
  }
}

int vtk_cell_size(int vtk_type) {
  switch (vtk_type) {
    case kVtkTetra:
      return 4;
    case kVtkHexahedron:
      return 8;
    case kVtkWedge:
      return 6;
    case kVtkPyramid:
      return 5;
    default:
      return 0;
  }
}

bool PolyhedronSoupBuilder::add_vtk_cell(int vtk_type, std::span<const int> vertices) {
  int poly[4];
  for (const auto& f : vtk_cell_faces(vtk_type)) {
    for (size_t i = 0; i < f.size(); ++i) poly[i] = vertices[f[i]];
    if (add_polygon({poly, f.size()}) < 0) {
      cell_.clear();
      return false;
    }
  }
  end_cell();
  return true;
}

PolyhedronSoupBuilder::PolyhedronSoupBuilder(Eigen::MatrixX3d positions) {
  soup_.positions = std::move(positions);
}

int PolyhedronSoupBuilder::add_polygon(std::span<const int> polygon) {
  key_.assign(polygon.begin(), polygon.end());
  std::sort(key_.begin(), key_.end());
  auto& bucket = by_hash_[polyhedron_builder_detail::hash_sorted(key_)];
  const size_t n = polygon.size();
  for (size_t b = 0; n > 0 && b < bucket.size(); ++b) {  // an empty polygon matches nothing
    const int f = bucket[b];
    const auto face = soup_.face_offsets[f + 1] - soup_.face_offsets[f];
    if (size_t(face) != n) continue;
    other_.assign(soup_.face_indices.begin() + soup_.face_offsets[f],
                  soup_.face_indices.begin() + soup_.face_offsets[f + 1]);
    const std::vector<int> ordered = other_;
    std::sort(other_.begin(), other_.end());
    if (other_ != key_) continue;
    last_face_ = f;
    const size_t p = size_t(std::find(ordered.begin(), ordered.end(), polygon[0]) - ordered.begin());
    bool same = true, reversed = true;
    for (size_t i = 0; i < n; ++i) {
      same = same && polygon[i] == ordered[(p + i) % n];
      reversed = reversed && polygon[i] == ordered[(p + n - i) % n];
    }
    const int h = same ? 2 * f : reversed ? 2 * f + 1 : -1;
    if (h >= 0) cell_.push_back(h);
    return h;
  }
  const int f = soup_.add_face(polygon);
  bucket.push_back(f);
  last_face_ = f;
  cell_.push_back(2 * f);
  return 2 * f;
}

void PolyhedronSoupBuilder::end_cell() {
  soup_.add_cell(cell_);
  cell_.clear();
}

}  // namespace polydec
