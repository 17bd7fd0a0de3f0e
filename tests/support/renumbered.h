// tests/support/renumbered.h — meshes with their vertices renumbered by a permutation (vertex v
// becomes perm[v]; faces and cells keep their order), for tests of results that must not depend
// on the numbering and of orders computed from it.
#pragma once

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec::test {

// A random permutation of 0, ..., n-1 (std::mt19937 seeded with `seed`).
inline std::vector<int> random_permutation(int n, unsigned seed) {
  std::vector<int> perm(static_cast<size_t>(n));
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(seed));
  return perm;
}

// The soup's positions and faces with vertex v renamed perm[v].
template <class Soup, class M>
Soup renumbered_soup(const M& mesh, const std::vector<int>& perm) {
  Soup s;
  s.positions.resize(mesh.n_vertices(), 3);
  for (int v = 0; v < mesh.n_vertices(); ++v) s.positions.row(perm[size_t(v)]) = mesh.positions().row(v);
  std::vector<int> face;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    face.clear();
    for (int v : mesh.face(f)) face.push_back(perm[size_t(v)]);
    s.add_face(face);
  }
  return s;
}

inline Mesh renumbered(const Mesh& mesh, const std::vector<int>& perm) {
  return Mesh(renumbered_soup<PolygonSoup>(mesh, perm));
}

inline VolumeMesh renumbered(const VolumeMesh& mesh, const std::vector<int>& perm) {
  PolyhedronSoup s = renumbered_soup<PolyhedronSoup>(mesh, perm);
  for (int c = 0; c < mesh.n_cells(); ++c) s.add_cell(mesh.cell(c));
  return VolumeMesh(std::move(s));
}

}  // namespace polydec::test
