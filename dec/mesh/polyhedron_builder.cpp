// dec/mesh/polyhedron_builder.cpp — face identification by vertex set for PolyhedronSoupBuilder.
#include "polydec/dec/mesh/polyhedron_builder.h"

#include <algorithm>

namespace polydec {
namespace polyhedron_builder_detail {
namespace {

std::uint64_t hash_sorted(const std::vector<int>& key) {
  std::uint64_t h = 1469598103934665603ull ^ key.size();
  for (int v : key) {
    h ^= std::uint64_t(unsigned(v)) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h *= 1099511628211ull;
  }
  // Final mix (splitmix64's), so that the low bits that pick a slot depend on every vertex.
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
  return h ^ (h >> 31);
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

void PolyhedronSoupBuilder::reserve(long faces, long face_indices, long cells, long cell_halffaces) {
  soup_.face_offsets.reserve(size_t(std::max(0L, faces)) + 1);
  soup_.face_indices.reserve(size_t(std::max(0L, face_indices)));
  soup_.cell_offsets.reserve(size_t(std::max(0L, cells)) + 1);
  soup_.cell_halffaces.reserve(size_t(std::max(0L, cell_halffaces)));
  face_hash_low_.reserve(size_t(std::max(0L, faces)));
  while (long(table_.size()) < 2 * faces + 2) grow();
}

void PolyhedronSoupBuilder::grow() {
  std::vector<Slot> old(table_.size() * 2);
  old.swap(table_);
  const size_t mask = table_.size() - 1;
  for (const Slot& s : old) {
    if (s.face < 0) continue;
    size_t i = face_hash_low_[size_t(s.face)] & mask;
    while (table_[i].face >= 0) i = (i + 1) & mask;
    table_[i] = s;
  }
}

int PolyhedronSoupBuilder::add_polygon(std::span<const int> polygon) {
  if (2 * size_t(soup_.n_faces() + 1) > table_.size()) grow();
  key_.assign(polygon.begin(), polygon.end());
  std::sort(key_.begin(), key_.end());
  const std::uint64_t h = polyhedron_builder_detail::hash_sorted(key_);
  const auto tag = std::uint32_t(h >> 32);
  const size_t mask = table_.size() - 1, n = polygon.size();
  size_t i = size_t(h) & mask;
  for (; table_[i].face >= 0; i = (i + 1) & mask) {
    const int f = table_[i].face;
    // An empty polygon matches nothing.
    if (n == 0 || table_[i].tag != tag || size_t(soup_.face_offsets[f + 1] - soup_.face_offsets[f]) != n) continue;
    ordered_.assign(soup_.face_indices.begin() + soup_.face_offsets[f],
                    soup_.face_indices.begin() + soup_.face_offsets[f + 1]);
    other_ = ordered_;
    std::sort(other_.begin(), other_.end());
    if (other_ != key_) continue;
    last_face_ = f;
    const size_t p = size_t(std::find(ordered_.begin(), ordered_.end(), polygon[0]) - ordered_.begin());
    bool same = true, reversed = true;
    for (size_t k = 0; k < n; ++k) {
      same = same && polygon[k] == ordered_[(p + k) % n];
      reversed = reversed && polygon[k] == ordered_[(p + n - k) % n];
    }
    const int half = same ? 2 * f : reversed ? 2 * f + 1 : -1;
    if (half >= 0) cell_.push_back(half);
    return half;
  }
  const int f = soup_.add_face(polygon);
  table_[i] = Slot{tag, f};
  face_hash_low_.push_back(std::uint32_t(h));
  last_face_ = f;
  cell_.push_back(2 * f);
  return 2 * f;
}

void PolyhedronSoupBuilder::end_cell() {
  soup_.add_cell(cell_);
  cell_.clear();
}

}  // namespace polydec
