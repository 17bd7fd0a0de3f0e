// operators/comparison/volume_diamond.cpp — the volume Diamond Laplacian [BBA21]: sub-diamonds per face edge,
// gradient by the discrete Gauss formula, coarsened by the volume prolongation.
#include "polydec/operators/comparison/volume_diamond.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "polydec/operators/detail/volume_refinement_in_use.h"

namespace polydec {

FineDiamonds volume_diamonds(const VolumeMesh& mesh, const VolumeRefinement& refinement) {
  check_refinement(mesh, refinement, "volume_diamonds");
  const int nV = mesh.n_vertices(), nF = mesh.n_faces(), nC = mesh.n_cells();
  FineDiamonds d;
  d.n_points = nV + nF + nC;
  d.weight = Eigen::VectorXd::Zero(long(mesh.face_indices().size()));
  d.mass = Eigen::VectorXd::Zero(d.n_points);
  d.gradient.reserve(mesh.face_indices().size() * 3 * 5);
  auto pos = [&](int r) { return refined_position(mesh, refinement, r); };

  int k = 0;  // sub-diamond index
  std::vector<int> verts;
  for (int f = 0; f < nF; ++f) {
    const auto cells = mesh.face_cells(f);
    // The lower tip's cell sees the face's vertex order as outward (normal towards the upper tip).
    const auto face = mesh.face(f);
    verts.assign(face.begin(), face.end());
    int lower = cells[0], upper = cells[1];
    if (lower < 0) {
      std::swap(lower, upper);
      std::reverse(verts.begin(), verts.end());
    }
    const int F = nV + f, L = nV + nF + lower, U = upper >= 0 ? nV + nF + upper : -1;
    const int n = int(verts.size());
    for (int e = 0; e < n; ++e, ++k) {
      const int p = verts[e], q = verts[(e + 1) % n];
      const std::array<int, 3> base{p, q, F};
      // The closed boundary: lower lateral triangles (t, s, L), upper ones (s, t, U) or the base.
      std::array<std::array<int, 3>, 6> tris;
      int n_tris = 0;
      for (int s = 0; s < 3; ++s) {
        const int a = base[s], b = base[(s + 1) % 3];
        tris[n_tris++] = {b, a, L};
        if (U >= 0) tris[n_tris++] = {a, b, U};
      }
      if (U < 0) tris[n_tris++] = base;

      const std::array<int, 5> corners{p, q, F, L, U >= 0 ? U : F};
      std::array<Eigen::Vector3d, 5> x;
      for (int c = 0; c < 5; ++c) x[c] = pos(corners[c]);
      const Eigen::Vector3d o = (x[0] + x[1] + x[2]) / 3;
      double longest = 0;
      for (int a = 0; a < 5; ++a)
        for (int b = a + 1; b < 5; ++b) longest = std::max(longest, (x[a] - x[b]).norm());
      auto at = [&](int r) {
        for (int c = 0; c < 5; ++c)
          if (corners[c] == r) return x[c];
        return x[0];  // unreachable: every triangle corner is a diamond corner
      };
      std::array<Eigen::Vector3d, 6> area;
      double volume = 0;
      for (int t = 0; t < n_tris; ++t) {
        const Eigen::Vector3d a = at(tris[t][0]), b = at(tris[t][1]), c = at(tris[t][2]);
        area[t] = (b - a).cross(c - a) / 2;
        volume += area[t].dot((a + b + c) / 3 - o) / 3;
      }
      if (!(std::abs(volume) * 6 > kDiamondDegenerateTolerance * longest * longest * longest)) {
        ++d.n_degenerate;
        continue;
      }
      if (volume < 0) ++d.n_folded;
      for (int t = 0; t < n_tris; ++t)
        for (int r : tris[t])
          for (int c = 0; c < 3; ++c) d.gradient.emplace_back(3 * k + c, r, area[t][c] / (3 * volume));
      const double w = std::abs(volume);
      d.weight[k] = w;
      d.mass[L] += w / 4;
      d.mass[U >= 0 ? U : F] += w / 4;
      for (int r : base) d.mass[r] += w / 6;
    }
  }
  return d;
}

VolumeLaplacian assemble_volume_diamond(const VolumeMesh& mesh, const VolumeRefinement& refinement) {
  check_refinement(mesh, refinement, "assemble_volume_diamond");
  VolumeLaplacian V;
  coarsen_diamonds(volume_diamonds(mesh, refinement), volume_prolongation(mesh, refinement), V.S, V.M,
                   V.M_lumped, nullptr, nullptr);
  V.quality = refinement.quality;
  return V;
}

OperatorSet volume_diamond_operators(const VolumeMesh& mesh, const VolumeOperatorOptions& options) {
  OperatorSet ops;
  ops.name = "diamond (volume)";
  ops.n_input_vertices = mesh.n_vertices();
  ops.mean_edge_length = mesh.mean_edge_length();
  detail::VolumeRefinementInUse in_use(mesh, options.refinement);
  const VolumeRefinement& R = in_use.get();
  ops.sub_tet_quality = R.quality;
  fill_diamond_operators(volume_diamonds(mesh, R), volume_prolongation(mesh, R), options.with_gradient, ops);
  if (options.keep_refinement) ops.volume_refinement = in_use.release();
  return ops;
}

}  // namespace polydec
