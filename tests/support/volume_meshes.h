// tests/support/volume_meshes.h — small procedural polyhedral meshes for the volume operator
// and DEC tests, built through PolyhedronSoup from cells given as outward polygons: single cells
// (tetrahedron, hexahedron, pyramid), hexahedral and 6-tets-per-cube grids (optionally sheared or
// jittered), a hexahedral solid torus, and large cells made by merging neighbours.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec::test {

// Cells as lists of outward polygons over `positions`; faces shared by two cells are stored once
// (the second cell uses the opposite half-face).
inline VolumeMesh volume_from_cells(const Eigen::MatrixX3d& positions,
                                    const std::vector<std::vector<std::vector<int>>>& cells) {
  PolyhedronSoup soup;
  soup.positions = positions;
  std::map<std::vector<int>, std::pair<int, std::vector<int>>> faces;  // sorted key -> (face, as stored)
  for (const auto& cell : cells) {
    std::vector<int> hf;
    for (const auto& poly : cell) {
      std::vector<int> key = poly;
      std::sort(key.begin(), key.end());
      auto it = faces.find(key);
      if (it == faces.end()) {
        const int f = soup.add_face(poly);
        faces.emplace(key, std::make_pair(f, poly));
        hf.push_back(2 * f);
      } else {
        // Same cyclic order as stored -> 2f, reversed -> 2f + 1.
        const auto& stored = it->second.second;
        const int n = int(poly.size());
        const int start = int(std::find(stored.begin(), stored.end(), poly[0]) - stored.begin());
        const bool same = stored[(start + 1) % n] == poly[1];
        hf.push_back(2 * it->second.first + (same ? 0 : 1));
      }
    }
    soup.add_cell(hf);
  }
  return VolumeMesh(std::move(soup));
}

// The six outward quads of a hexahedron with corners c[x + 2y + 4z] (x, y, z in {0, 1}, a
// right-handed frame).
inline std::vector<std::vector<int>> hex_faces(const int c[8]) {
  return {{c[0], c[4], c[6], c[2]}, {c[1], c[3], c[7], c[5]}, {c[0], c[1], c[5], c[4]},
          {c[2], c[6], c[7], c[3]}, {c[0], c[2], c[3], c[1]}, {c[4], c[5], c[7], c[6]}};
}

// The four outward triangles of tetrahedron (a, b, c, d), oriented by its signed volume.
inline std::vector<std::vector<int>> tet_faces(const Eigen::MatrixX3d& X, int a, int b, int c, int d) {
  const Eigen::Vector3d pa = X.row(a), pb = X.row(b), pc = X.row(c), pd = X.row(d);
  if ((pb - pa).dot((pc - pa).cross(pd - pa)) < 0) std::swap(c, d);
  return {{a, c, b}, {a, b, d}, {a, d, c}, {b, c, d}};
}

inline int grid_index(int i, int j, int k, int nx, int ny) { return i + (nx + 1) * (j + (ny + 1) * k); }

inline Eigen::MatrixX3d grid_positions(int nx, int ny, int nz) {
  Eigen::MatrixX3d X((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        X.row(grid_index(i, j, k, nx, ny)) << double(i) / nx, double(j) / ny, double(k) / nz;
  return X;
}

// Moves every interior vertex by a uniform random offset of up to `amount` times the spacing.
inline void jitter_interior(Eigen::MatrixX3d& X, int nx, int ny, int nz, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  for (int k = 1; k < nz; ++k)
    for (int j = 1; j < ny; ++j)
      for (int i = 1; i < nx; ++i) {
        auto r = X.row(grid_index(i, j, k, nx, ny));
        r(0) += u(rng) / nx, r(1) += u(rng) / ny, r(2) += u(rng) / nz;
      }
}

// nx x ny x nz hexahedra on the unit cube, positions optionally replaced.
inline VolumeMesh hex_grid_mesh(int nx, int ny, int nz, const Eigen::MatrixX3d* positions = nullptr) {
  const Eigen::MatrixX3d X = positions ? *positions : grid_positions(nx, ny, nz);
  std::vector<std::vector<std::vector<int>>> cells;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        int c[8];
        for (int b = 0; b < 8; ++b)
          c[b] = grid_index(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1), nx, ny);
        cells.push_back(hex_faces(c));
      }
  return volume_from_cells(X, cells);
}

// Six tetrahedra per cube (Kuhn triangulation: paths 000 -> 111 along the axes).
inline VolumeMesh tet_grid_mesh(int nx, int ny, int nz, const Eigen::MatrixX3d* positions = nullptr) {
  const Eigen::MatrixX3d X = positions ? *positions : grid_positions(nx, ny, nz);
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::vector<std::vector<std::vector<int>>> cells;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : perms) {
          int o[3] = {0, 0, 0}, v[4];
          v[0] = grid_index(i, j, k, nx, ny);
          for (int s = 0; s < 3; ++s) {
            o[p[s]] = 1;
            v[s + 1] = grid_index(i + o[0], j + o[1], k + o[2], nx, ny);
          }
          cells.push_back(tet_faces(X, v[0], v[1], v[2], v[3]));
        }
  return volume_from_cells(X, cells);
}

// A hexahedral solid torus: n_around segments, a 2 x 2 grid of quads as cross-section (major
// radius 3, cross-section half-width 1).
inline VolumeMesh hex_solid_torus(int n_around) {
  auto id = [&](int i, int a, int b) { return ((i % n_around) * 3 + a) * 3 + b; };
  Eigen::MatrixX3d X(n_around * 9, 3);
  for (int i = 0; i < n_around; ++i)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const double t = 2 * M_PI * i / n_around, r = 3.0 + (a - 1);
        X.row(id(i, a, b)) << r * std::cos(t), r * std::sin(t), double(b - 1);
      }
  std::vector<std::vector<std::vector<int>>> cells;
  for (int i = 0; i < n_around; ++i)
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        // Frame (radial, around, height) is right-handed.
        int c[8];
        for (int s = 0; s < 8; ++s) c[s] = id(i + ((s >> 1) & 1), a + (s & 1), b + ((s >> 2) & 1));
        cells.push_back(hex_faces(c));
      }
  return volume_from_cells(X, cells);
}

// One square pyramid (apex above the centre of the unit square base).
inline VolumeMesh single_pyramid(double height = 0.7) {
  Eigen::MatrixX3d X(5, 3);
  X << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, height;
  return volume_from_cells(X, {{{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}});
}

// One prism over a regular n-gon (2n vertices).
inline VolumeMesh prism_volume(int n, double height = 0.8) {
  Eigen::MatrixX3d X(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    X.row(k) << std::cos(a), std::sin(a), 0.0;
    X.row(n + k) << std::cos(a), std::sin(a), height;
  }
  std::vector<std::vector<int>> faces;
  std::vector<int> bottom, top;
  for (int k = 0; k < n; ++k) bottom.push_back(n - 1 - k), top.push_back(n + k);
  faces.push_back(bottom);
  faces.push_back(top);
  for (int k = 0; k < n; ++k) faces.push_back({k, (k + 1) % n, n + (k + 1) % n, n + k});
  return volume_from_cells(X, {faces});
}

// Merges pairs of neighbouring cells into one (their shared face removed), greedily over the
// interior faces in order: a pair is merged when neither cell is merged yet, they share only this
// face and together they have at least `min_vertices` vertices. Two balls glued along a disk are
// a ball, so every cell stays a valid polyhedron; on truncated_octahedra_volume(3) this makes
// Voronoi-like cells of up to 42 vertices (applied twice, up to 70).
inline VolumeMesh merge_neighbour_cells(const VolumeMesh& mesh, int min_vertices) {
  std::vector<int> group(size_t(mesh.n_cells()), -1);
  std::vector<char> removed(size_t(mesh.n_faces()), 0);
  int n_groups = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto cells = mesh.face_cells(f);
    if (cells[0] < 0 || cells[1] < 0 || group[size_t(cells[0])] >= 0 || group[size_t(cells[1])] >= 0) continue;
    std::vector<int> v(mesh.cell_vertices(cells[0]).begin(), mesh.cell_vertices(cells[0]).end());
    v.insert(v.end(), mesh.cell_vertices(cells[1]).begin(), mesh.cell_vertices(cells[1]).end());
    std::sort(v.begin(), v.end());
    if (int(std::unique(v.begin(), v.end()) - v.begin()) < min_vertices) continue;
    // Only neighbours through a single face (glued along two disks they would make a solid torus).
    int shared = 0;
    for (int hf : mesh.cell(cells[0])) {
      const auto other = mesh.face_cells(hf / 2);
      shared += (other[0] == cells[1] || other[1] == cells[1]) ? 1 : 0;
    }
    if (shared != 1) continue;
    group[size_t(cells[0])] = group[size_t(cells[1])] = n_groups++;
    removed[size_t(f)] = 1;
  }
  for (int c = 0; c < mesh.n_cells(); ++c)
    if (group[size_t(c)] < 0) group[size_t(c)] = n_groups++;
  PolyhedronSoup soup;
  soup.positions = mesh.positions();
  std::vector<int> new_face(size_t(mesh.n_faces()), -1);
  for (int f = 0; f < mesh.n_faces(); ++f)
    if (!removed[size_t(f)]) new_face[size_t(f)] = soup.add_face(mesh.face(f));
  std::vector<std::vector<int>> cells(static_cast<size_t>(n_groups));
  for (int c = 0; c < mesh.n_cells(); ++c)
    for (int hf : mesh.cell(c))
      if (!removed[size_t(hf / 2)]) cells[size_t(group[size_t(c)])].push_back(2 * new_face[size_t(hf / 2)] + (hf & 1));
  for (const auto& hf : cells) soup.add_cell(hf);
  return VolumeMesh(std::move(soup));
}

// The same mesh with every face's vertex list rotated (face f starts at its corner f mod n) and
// every cell's half-faces in reverse order: the same complex, numbered alike, listed differently.
inline VolumeMesh relisted_volume(const VolumeMesh& mesh) {
  PolyhedronSoup soup;
  soup.positions = mesh.positions();
  for (int f = 0; f < mesh.n_faces(); ++f) {
    std::vector<int> face(mesh.face(f).begin(), mesh.face(f).end());
    std::rotate(face.begin(), face.begin() + f % int(face.size()), face.end());
    soup.add_face(face);
  }
  for (int c = 0; c < mesh.n_cells(); ++c) {
    std::vector<int> hf(mesh.cell(c).begin(), mesh.cell(c).end());
    std::reverse(hf.begin(), hf.end());
    soup.add_cell(hf);
  }
  return VolumeMesh(std::move(soup));
}

// Cell c's outward faces, each rotated to start at its smallest vertex, sorted: the cell up to
// face numbering and order (for comparing meshes read from different files).
inline std::vector<std::vector<int>> outward_faces(const VolumeMesh& m, int c) {
  std::vector<std::vector<int>> faces;
  for (int h : m.cell(c)) {
    const auto f = m.face(h / 2);
    std::vector<int> p(f.begin(), f.end());
    if (h & 1) std::reverse(p.begin() + 1, p.end());
    std::rotate(p.begin(), std::min_element(p.begin(), p.end()), p.end());
    faces.push_back(p);
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

}  // namespace polydec::test
