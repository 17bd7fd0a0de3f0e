// dec/volume/mesh_complex.cpp — the volume mesh complex (dec/volume/mesh_complex.h): d0..d2,
// the commuting prolongations P1..P3 solved cell by cell with small dense systems, and the stars
// assembled cell by cell from the sub-tetrahedra.
#include "polydec/dec/volume/mesh_complex.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "polydec/dec/detail/element_pattern.h"
#include "polydec/dec/detail/scale.h"
#include "polydec/dec/volume/prolongation.h"
#include "polydec/dec/volume/whitney.h"

namespace polydec {

namespace volume_mesh_complex_detail {
namespace {

using Triplet = Eigen::Triplet<double>;

int local_index(const std::vector<int>& sorted, int value) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), value);
  if (it == sorted.end() || *it != value) throw std::logic_error("volume mesh complex: local cell missing");
  return int(it - sorted.begin());
}

template <size_t K>
int local_simplex(const std::vector<std::array<int, K>>& sorted, const std::array<int, K>& s) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), s);
  if (it == sorted.end() || *it != s) throw std::logic_error("volume mesh complex: refined simplex missing");
  return int(it - sorted.begin());
}

// Global edge of the vertex pair (a, b), by binary search in the lexicographic VolumeMesh::edges().
int global_edge(const Eigen::MatrixX2i& E, int a, int b) {
  if (a > b) std::swap(a, b);
  int lo = 0, hi = int(E.rows());
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (E(mid, 0) < a || (E(mid, 0) == a && E(mid, 1) < b))
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo == E.rows() || E(lo, 0) != a || E(lo, 1) != b) throw std::logic_error("volume mesh complex: edge missing");
  return lo;
}

// The per-polygon kernel of face f: its weights and its fan triangles' areas, negative for a fan
// triangle against the face's vector area (as signed_fan_areas on surfaces).
PolygonCochainMaps face_kernel(const VolumeMesh& mesh, const VolumeRefinement& R, int f, SpokeRule rule) {
  const auto face = mesh.face(f);
  const int n = int(face.size());
  const Eigen::Vector3d xf = R.face_points.row(f).transpose();
  std::vector<Eigen::Vector3d> cross(static_cast<size_t>(n));
  Eigen::Vector3d N = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    cross[size_t(k)] = (mesh.position(face[size_t(k)]) - xf).cross(mesh.position(face[size_t((k + 1) % n)]) - xf);
    N += cross[size_t(k)];
  }
  std::vector<double> areas(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) areas[size_t(k)] = (cross[size_t(k)].dot(N) < 0 ? -0.5 : 0.5) * cross[size_t(k)].norm();
  return polygon_cochain_maps(R.weights_of_face(mesh, f), areas, rule);
}

// Sign of the refined simplex s (sorted) against the ordered tuple it came from.
template <size_t K>
int permutation_sign(std::array<int, K> a) {
  int sign = 1;
  for (size_t i = 0; i < K; ++i)
    for (size_t j = i + 1; j < K; ++j)
      if (a[i] > a[j]) sign = -sign;
  return sign;
}

template <size_t K>
std::array<int, K> sorted(std::array<int, K> a) {
  std::sort(a.begin(), a.end());
  return a;
}

// Everything of one cell: its local coarse cells, its sub-tetrahedra and the rows of P0..P3 of
// every refined simplex of its sub-tetrahedra over the local coarse cells.
struct CellMaps {
  std::vector<int> verts;     // cell_vertices(c), ascending (global)
  std::vector<int> edges;     // global edges of the closure, ascending
  std::vector<int> faces;     // global faces, in half-face order
  Eigen::VectorXd Z;          // +1 for half-face 2f, -1 for 2f+1 (row c of d2)
  struct Tet {
    std::array<int, 4> v;     // sorted refined vertices
    int o;                    // +1 when (x_i, x_{i+1}, x_f, x_c) in outward order is the sorted orientation
    SubTet quality;
    double volume;            // signed, along the sorted orientation
  };
  std::vector<Tet> tets;
  std::vector<std::array<int, 2>> s1;
  std::vector<std::array<int, 3>> s2;
  Eigen::MatrixXd P0;  // (nVc + nFc + 1) x nVc: rows of the cell's vertices, face points (local order), cell point
  Eigen::MatrixXd P1;  // s1 x edges
  Eigen::MatrixXd P2;  // s2 x faces
  Eigen::VectorXd P3;  // per tet (order of `tets`), over the cell itself
  int n_vertices = 0, n_faces = 0;  // of the mesh

  // Local row of refined vertex r in P0.
  int p0_row(int r) const {
    if (r < n_vertices) return local_index(verts, r);
    if (r < n_vertices + n_faces) {
      const auto it = std::find(faces.begin(), faces.end(), r - n_vertices);
      if (it == faces.end()) throw std::logic_error("volume mesh complex: face point missing");
      return int(verts.size()) + int(it - faces.begin());
    }
    return int(verts.size() + faces.size());
  }
};

// Builds the maps of cell c up to degree `degree` (P_k for k <= degree; P2 needs the
// sub-tetrahedra's targets, so degree >= 2 computes the c_rho in any case).
void build_cell(const VolumeMesh& mesh, const VolumeRefinement& R, int c, int degree, SpokeRule rule,
                CellMaps& W) {
  const int nV = mesh.n_vertices(), nF = mesh.n_faces();
  const int cp = nV + nF + c;
  const Eigen::MatrixX2i& E = mesh.edges();
  W.n_vertices = nV;
  W.n_faces = nF;
  const auto cv = mesh.cell_vertices(c);
  W.verts.assign(cv.begin(), cv.end());
  const auto hfs = mesh.cell(c);
  const int nFc = int(hfs.size()), nVc = int(W.verts.size());
  W.faces.resize(size_t(nFc));
  W.Z.resize(nFc);
  W.edges.clear();
  // side_edge[l][k]: the global, then the local edge of side k of face l (corner k to k+1).
  std::vector<std::vector<int>> side_edge(static_cast<size_t>(nFc));
  for (int l = 0; l < nFc; ++l) {
    W.faces[size_t(l)] = hfs[size_t(l)] / 2;
    W.Z[l] = (hfs[size_t(l)] & 1) ? -1.0 : 1.0;
    const auto face = mesh.face(W.faces[size_t(l)]);
    for (size_t k = 0; k < face.size(); ++k) {
      side_edge[size_t(l)].push_back(global_edge(E, face[k], face[(k + 1) % face.size()]));
      W.edges.push_back(side_edge[size_t(l)].back());
    }
  }
  std::sort(W.edges.begin(), W.edges.end());
  W.edges.erase(std::unique(W.edges.begin(), W.edges.end()), W.edges.end());
  for (auto& sides : side_edge)
    for (int& e : sides) e = local_index(W.edges, e);
  const int nEc = int(W.edges.size());
  if (nVc - nEc + nFc != 2)
    throw std::invalid_argument("volume mesh complex: the boundary of cell " + std::to_string(c) +
                                " is not a sphere (V - E + F = " + std::to_string(nVc - nEc + nFc) + ")");

  // Local incidence: D0 (nEc x nVc), D1 (nFc x nEc).
  Eigen::MatrixXd D0 = Eigen::MatrixXd::Zero(nEc, nVc), D1 = Eigen::MatrixXd::Zero(nFc, nEc);
  for (int e = 0; e < nEc; ++e) {
    D0(e, local_index(W.verts, E(W.edges[size_t(e)], 0))) = -1.0;
    D0(e, local_index(W.verts, E(W.edges[size_t(e)], 1))) = 1.0;
  }
  std::vector<PolygonCochainMaps> K(static_cast<size_t>(nFc));
  for (int l = 0; l < nFc; ++l) {
    const int f = W.faces[size_t(l)];
    const auto face = mesh.face(f);
    const int n = int(face.size());
    for (int k = 0; k < n; ++k) {
      const int a = face[size_t(k)], b = face[size_t((k + 1) % n)];
      D1(l, side_edge[size_t(l)][size_t(k)]) += a < b ? 1.0 : -1.0;
    }
    if (degree >= 1) K[size_t(l)] = face_kernel(mesh, R, f, rule);
  }

  // P0 rows of the cell's refined vertices.
  W.P0 = Eigen::MatrixXd::Zero(nVc + nFc + 1, nVc);
  for (int i = 0; i < nVc; ++i) W.P0(i, i) = 1.0;
  for (int l = 0; l < nFc; ++l) {
    const int f = W.faces[size_t(l)];
    const auto face = mesh.face(f);
    const auto w = R.weights_of_face(mesh, f);
    for (size_t k = 0; k < face.size(); ++k) W.P0(nVc + l, local_index(W.verts, face[k])) += w[k];
  }
  {
    const auto w = R.weights_of_cell(c);
    for (int i = 0; i < nVc; ++i) W.P0(nVc + nFc, i) = w[size_t(i)];
  }

  // Sub-tetrahedra, in the order of VolumeRefinement::tets. Their volumes serve only as ratios
  // (P3): a cell far outside the ordinary sizes takes them relative to its cell point in units of
  // 2^e (dec/detail/scale.h), where they cannot overflow.
  W.tets.clear();
  {
    const Eigen::Vector3d xc = R.cell_points.row(c).transpose();
    double extent = 0;
    for (int v : W.verts) extent = std::fmax(extent, (mesh.position(v) - xc).cwiseAbs().maxCoeff());
    const int e = detail::normalizing_exponent(extent);
    const double inv = std::ldexp(1.0, -e);
    int t = R.tet_offsets[size_t(c)];
    std::vector<int> hv;
    for (int l = 0; l < nFc; ++l) {
      const auto face = mesh.face(W.faces[size_t(l)]);
      hv.assign(face.begin(), face.end());
      if (hfs[size_t(l)] & 1) std::reverse(hv.begin(), hv.end());
      const int n = int(hv.size());
      for (int i = 0; i < n; ++i, ++t) {
        const std::array<int, 4> ordered = {hv[size_t(i)], hv[size_t((i + 1) % n)], nV + W.faces[size_t(l)], cp};
        CellMaps::Tet tet;
        tet.v = sorted(ordered);
        tet.o = permutation_sign(ordered);
        tet.quality = R.tets[size_t(t)];
        Eigen::Vector3d p[4];
        for (int a = 0; a < 4; ++a) {
          p[a] = refined_position(mesh, R, tet.v[size_t(a)]);
          if (e != 0) p[a] = (p[a] - xc) * inv;
        }
        tet.volume = tet_signed_volume(p[0], p[1], p[2], p[3]);
        W.tets.push_back(tet);
      }
    }
  }
  if (degree < 1) return;

  // P1.
  W.s1.clear();
  for (const auto& tet : W.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) W.s1.push_back({tet.v[size_t(a)], tet.v[size_t(b)]});
  std::sort(W.s1.begin(), W.s1.end());
  W.s1.erase(std::unique(W.s1.begin(), W.s1.end()), W.s1.end());
  const int n1 = int(W.s1.size());
  W.P1 = Eigen::MatrixXd::Zero(n1, nEc);
  std::vector<int> interior1;
  for (int r = 0; r < n1; ++r) {
    const int a = W.s1[size_t(r)][0], b = W.s1[size_t(r)][1];
    if (b < nV) {
      W.P1(r, local_index(W.edges, global_edge(E, a, b))) = 1.0;  // sorted a < b: the edge's way
    } else if (b < nV + nF) {
      // Spoke (a, x_f): row of corner a in face f's side basis.
      const int f = b - nV;
      const int l = int(std::find(W.faces.begin(), W.faces.end(), f) - W.faces.begin());
      const auto face = mesh.face(f);
      const int n = int(face.size());
      const int i = int(std::find(face.begin(), face.end(), a) - face.begin());
      for (int k = 0; k < n; ++k) {
        const int p = face[size_t(k)], q = face[size_t((k + 1) % n)];
        W.P1(r, side_edge[size_t(l)][size_t(k)]) += (p < q ? 1.0 : -1.0) * K[size_t(l)].spokes(i, k);
      }
    } else {
      interior1.push_back(r);
    }
  }
  {
    // r D0 = g with g = P0(b) - P0(a): r^T = D0 (L + 1 1^T / n)^-1 g^T (g sums to 0, so this is
    // D0 L^+ g^T, the least-norm solution).
    const int m = int(interior1.size());
    Eigen::MatrixXd G(nVc, m);
    for (int j = 0; j < m; ++j) {
      const auto& s = W.s1[size_t(interior1[size_t(j)])];
      G.col(j) = (W.P0.row(W.p0_row(s[1])) - W.P0.row(W.p0_row(s[0]))).transpose();
    }
    Eigen::MatrixXd L = D0.transpose() * D0;
    L.array() += 1.0 / nVc;
    const Eigen::MatrixXd Y = L.ldlt().solve(G);
    const Eigen::MatrixXd rows = (D0 * Y).transpose();
    for (int j = 0; j < m; ++j) W.P1.row(interior1[size_t(j)]) = rows.row(j);
  }
  if (degree < 2) return;

  // P2.
  W.s2.clear();
  for (const auto& tet : W.tets)
    for (int missing = 0; missing < 4; ++missing) {
      std::array<int, 3> tri;
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != missing) tri[size_t(k++)] = tet.v[size_t(a)];
      W.s2.push_back(tri);
    }
  std::sort(W.s2.begin(), W.s2.end());
  W.s2.erase(std::unique(W.s2.begin(), W.s2.end()), W.s2.end());
  const int n2 = int(W.s2.size());
  W.P2 = Eigen::MatrixXd::Zero(n2, nFc);
  std::vector<int> interior2, slot2(size_t(n2), -1);
  for (int r = 0; r < n2; ++r) {
    const auto& s = W.s2[size_t(r)];
    if (s[2] < nV + nF) {
      // Fan triangle (a, b, x_f): side k of face f runs between a and b.
      const int f = s[2] - nV;
      const int l = int(std::find(W.faces.begin(), W.faces.end(), f) - W.faces.begin());
      const auto face = mesh.face(f);
      const int n = int(face.size());
      const int i = int(std::find(face.begin(), face.end(), s[0]) - face.begin());
      const int k = face[size_t((i + 1) % n)] == s[1] ? i : (i + n - 1) % n;
      const int p = face[size_t(k)], q = face[size_t((k + 1) % n)];
      W.P2(r, l) = (p < q ? 1.0 : -1.0) * K[size_t(l)].fractions[k];
    } else {
      slot2[size_t(r)] = int(interior2.size());
      interior2.push_back(r);
    }
  }
  const int m2 = int(interior2.size());
  {
    // Minimum norm: r^T = (D1 D1^T + Z Z^T)^-1 D1 b^T, b = sum_i (-1)^i P1(rho without i).
    Eigen::MatrixXd B(nEc, m2);
    for (int j = 0; j < m2; ++j) {
      const auto& s = W.s2[size_t(interior2[size_t(j)])];
      B.col(j) = (W.P1.row(local_simplex(W.s1, {s[1], s[2]})) - W.P1.row(local_simplex(W.s1, {s[0], s[2]})) +
                  W.P1.row(local_simplex(W.s1, {s[0], s[1]})))
                     .transpose();
    }
    const Eigen::MatrixXd A = D1 * D1.transpose() + W.Z * W.Z.transpose();
    const Eigen::MatrixXd Y = A.ldlt().solve(D1 * B);
    for (int j = 0; j < m2; ++j) W.P2.row(interior2[size_t(j)]) = Y.col(j).transpose();
  }
  // The c_rho: every tetrahedron tau has P3 row s_tau = (d^tet_2 P2)_tau . Z / |Z|^2
  // = s0_tau + sum over its interior triangles of their sign times c_rho; ask s_tau = vol_tau / vol_c
  // and take the least-norm c = B3^T (B3 B3^T + o o^T)^-1 (t - s0), B3 the tetrahedra x interior
  // triangles incidence, o its left kernel (the tetrahedra's signs against the cell).
  const int nt = int(W.tets.size());
  double vol_c = 0;
  for (const auto& tet : W.tets) vol_c -= tet.o * tet.volume;  // (x_i, x_{i+1}, x_f, x_c) outward is negative
  if (!(vol_c > 0))
    throw std::invalid_argument("volume mesh complex: cell " + std::to_string(c) +
                                " has non-positive refined volume");
  const double zz = W.Z.squaredNorm();
  Eigen::VectorXd y(nt);
  Eigen::MatrixXd L3 = Eigen::MatrixXd::Zero(nt, nt);
  std::vector<std::array<std::pair<int, int>, 4>> tri_of(static_cast<size_t>(nt));  // (local triangle, sign)
  std::vector<std::vector<std::pair<int, int>>> tets_of(static_cast<size_t>(m2));
  for (int t = 0; t < nt; ++t) {
    const auto& v = W.tets[size_t(t)].v;
    double s0 = 0;
    for (int missing = 0; missing < 4; ++missing) {
      std::array<int, 3> tri;
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != missing) tri[size_t(k++)] = v[size_t(a)];
      const int r = local_simplex(W.s2, tri), sign = missing % 2 == 0 ? 1 : -1;
      tri_of[size_t(t)][size_t(missing)] = {r, sign};
      s0 += sign * W.P2.row(r).dot(W.Z) / zz;
      if (slot2[size_t(r)] >= 0) tets_of[size_t(slot2[size_t(r)])].push_back({t, sign});
    }
    y[t] = W.tets[size_t(t)].volume / vol_c - s0;
  }
  for (const auto& list : tets_of)
    for (const auto& [t, s] : list)
      for (const auto& [u, q] : list) L3(t, u) += double(s * q);
  for (int t = 0; t < nt; ++t)
    for (int u = 0; u < nt; ++u) L3(t, u) += double(W.tets[size_t(t)].o * W.tets[size_t(u)].o);
  const Eigen::VectorXd z = L3.ldlt().solve(y);
  for (int j = 0; j < m2; ++j) {
    double cj = 0;
    for (const auto& [t, s] : tets_of[size_t(j)]) cj += s * z[t];
    W.P2.row(interior2[size_t(j)]) += cj * W.Z.transpose();
  }
  if (degree < 3) return;

  // P3 from the commutation.
  W.P3.resize(nt);
  for (int t = 0; t < nt; ++t) {
    double s = 0;
    for (const auto& [r, sign] : tri_of[size_t(t)]) s += sign * W.P2.row(r).dot(W.Z);
    W.P3[t] = s / zz;
  }
}

void check_degree(int k, int lo, int hi, const char* caller) {
  if (k < lo || k > hi)
    throw std::invalid_argument(std::string(caller) + ": k = " + std::to_string(k) + " (" + std::to_string(lo) +
                                ".." + std::to_string(hi) + ")");
}

// What one pass over the cells assembles: P_k for the k in `prolongations` (1..3, rows in the
// numbering of `refined`), the stars up to `star_degree` (-1: none).
struct Request {
  bool prolongations[4] = {false, false, false, false};
  int star_degree = -1;
};

struct Assembled {
  SparseMatrix P[4];
  std::array<SparseMatrix, 4> star;
};

// Index of refined simplex s in `refined`; std::invalid_argument when it is not there (a refined
// complex of another mesh).
template <size_t K>
int refined_row(const SimplexComplex3& refined, const std::array<int, K>& s) {
  const int row = refined.index(s);
  if (row < 0) throw std::invalid_argument("volume mesh complex: the refined complex does not belong to this mesh");
  return row;
}

// Cell c's blocks of star_0..star_min(max_degree, 2), P_k^T star_k^tet P_k over its
// sub-tetrahedra (local[k] over W's vertices, edges, faces), and its star3 entry s3.
void cell_star_blocks(const VolumeMesh& mesh, const VolumeRefinement& R, const CellMaps& W, int max_degree,
                      Eigen::MatrixXd (&local)[3], double& s3) {
  const int nVc = int(W.verts.size()), nEc = int(W.edges.size()), nFc = int(W.faces.size());
  local[0].setZero(nVc, nVc);
  if (max_degree >= 1) local[1].setZero(nEc, nEc);
  if (max_degree >= 2) local[2].setZero(nFc, nFc);
  s3 = 0.0;
  Eigen::Matrix<double, 4, Eigen::Dynamic> R0(4, nVc), R2(4, nFc);
  Eigen::Matrix<double, 6, Eigen::Dynamic> R1(6, nEc);
  for (size_t i = 0; i < W.tets.size(); ++i) {
    const auto& tet = W.tets[i];
    const auto& v = tet.v;
    Eigen::Vector3d p[4];
    for (int a = 0; a < 4; ++a) p[a] = refined_position(mesh, R, v[size_t(a)]);
    for (int a = 0; a < 4; ++a) R0.row(a) = W.P0.row(W.p0_row(v[size_t(a)]));
    local[0].noalias() += R0.transpose() * tet_whitney0_mass(p[0], p[1], p[2], p[3]) * R0;
    if (tet.quality == SubTet::Degenerate) continue;
    if (max_degree >= 1) {
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
          R1.row(tet_local_edge(a, b)) = W.P1.row(local_simplex(W.s1, {v[size_t(a)], v[size_t(b)]}));
      local[1].noalias() += R1.transpose() * tet_whitney1_mass(p[0], p[1], p[2], p[3]) * R1;
    }
    if (max_degree >= 2) {
      for (int missing = 0; missing < 4; ++missing) {
        std::array<int, 3> tri;
        for (int a = 0, k = 0; a < 4; ++a)
          if (a != missing) tri[size_t(k++)] = v[size_t(a)];
        R2.row(tet_local_triangle_without(missing)) = W.P2.row(local_simplex(W.s2, tri));
      }
      local[2].noalias() += R2.transpose() * tet_whitney2_mass(p[0], p[1], p[2], p[3]) * R2;
    }
    if (max_degree >= 3) s3 += W.P3[Eigen::Index(i)] * W.P3[Eigen::Index(i)] * tet_whitney3_mass(p[0], p[1], p[2], p[3]);
  }
}

// Every cell's edges (ascending, as CellMaps::edges) and faces (half-face order, as
// CellMaps::faces), as offsets + indices.
struct CellLists {
  std::vector<int> edge_offsets{0}, edges, face_offsets{0}, faces;
  std::span<const int> edges_of(int c) const {
    return {edges.data() + edge_offsets[size_t(c)], size_t(edge_offsets[size_t(c) + 1] - edge_offsets[size_t(c)])};
  }
  std::span<const int> faces_of(int c) const {
    return {faces.data() + face_offsets[size_t(c)], size_t(face_offsets[size_t(c) + 1] - face_offsets[size_t(c)])};
  }
};

CellLists cell_lists(const VolumeMesh& mesh) {
  CellLists L;
  const Eigen::MatrixX2i& E = mesh.edges();
  std::vector<int> e;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    e.clear();
    for (int hf : mesh.cell(c)) {
      L.faces.push_back(hf / 2);
      const auto face = mesh.face(hf / 2);
      for (size_t k = 0; k < face.size(); ++k) e.push_back(global_edge(E, face[k], face[(k + 1) % face.size()]));
    }
    std::sort(e.begin(), e.end());
    e.erase(std::unique(e.begin(), e.end()), e.end());
    L.edges.insert(L.edges.end(), e.begin(), e.end());
    L.edge_offsets.push_back(int(L.edges.size()));
    L.face_offsets.push_back(int(L.faces.size()));
  }
  return L;
}

// A column-major matrix written entry by entry into columns of known capacity (an upper bound on
// their entries, from the connectivity), then sorted by row within each column and compacted in
// place: it needs no storage beyond the result's (setFromTriplets holds the triplets, a transposed
// copy and the result).
class ColumnFill {
 public:
  // Eigen 3.4's SparseMatrix copies on move: a ColumnFill is set up in place, never moved.
  void init(int rows, const std::vector<long>& capacity) {
    used_.assign(capacity.size(), 0);
    long total = 0;
    for (long n : capacity) total += n;
    if (total > long(std::numeric_limits<int>::max()))
      throw std::length_error("volume mesh complex: a prolongation with more than 2^31 entries");
    M_.resize(rows, Eigen::Index(capacity.size()));
    M_.resizeNonZeros(Eigen::Index(total));
    int* outer = M_.outerIndexPtr();
    outer[0] = 0;
    for (size_t j = 0; j < capacity.size(); ++j) outer[j + 1] = outer[j] + int(capacity[j]);
  }

  void add(int row, int col, double value) {
    const int p = M_.outerIndexPtr()[col] + used_[size_t(col)];
    if (p >= M_.outerIndexPtr()[col + 1])
      throw std::logic_error("volume mesh complex: a column of P holds more entries than counted");
    ++used_[size_t(col)];
    M_.innerIndexPtr()[p] = row;
    M_.valuePtr()[p] = value;
  }

  // Rows ascending in every column, the columns packed; `out` takes the matrix.
  void finish(SparseMatrix& out) {
    int* outer = M_.outerIndexPtr();
    int* inner = M_.innerIndexPtr();
    double* value = M_.valuePtr();
    std::vector<std::pair<int, double>> column;
    int w = 0;
    for (size_t j = 0; j < used_.size(); ++j) {
      const int b = outer[j], n = used_[j];
      if (!std::is_sorted(inner + b, inner + b + n)) {
        column.clear();
        for (int p = b; p < b + n; ++p) column.emplace_back(inner[p], value[p]);
        std::sort(column.begin(), column.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        for (int p = 0; p < n; ++p) inner[b + p] = column[size_t(p)].first, value[b + p] = column[size_t(p)].second;
      }
      if (w != b) {
        std::copy(inner + b, inner + b + n, inner + w);
        std::copy(value + b, value + b + n, value + w);
      }
      outer[j] = w;
      w += n;
    }
    outer[used_.size()] = w;
    M_.data().resize(w);  // within the capacity: no copy
    out.swap(M_);
    used_.clear();
  }

 private:
  SparseMatrix M_;
  std::vector<int> used_;
};

// Capacities of P1's, P2's and P3's columns: a mesh edge's unit row; a face's spokes (dense over
// its sides) and fan triangles (one entry each); a cell's interior rows, dense over its edges
// ((v, x_c), (x_f, x_c)) or faces ((v_i, v_j, x_c) per edge, (v, x_f, x_c) per face corner);
// its sub-tetrahedra (P3).
std::vector<long> column_capacity(const VolumeMesh& mesh, const CellLists& L, int k) {
  const int sizes[4] = {mesh.n_vertices(), mesh.n_edges(), mesh.n_faces(), mesh.n_cells()};
  std::vector<long> cap(size_t(sizes[k]), k == 1 ? 1 : 0);
  if (k < 3)
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const auto face = mesh.face(f);
      const long n = long(face.size());
      if (k == 2) cap[size_t(f)] += n;
      for (size_t i = 0; k == 1 && i < face.size(); ++i)
        cap[size_t(global_edge(mesh.edges(), face[i], face[(i + 1) % face.size()]))] += n;
    }
  for (int c = 0; c < mesh.n_cells(); ++c) {
    long corners = 0;
    for (int f : L.faces_of(c)) corners += long(mesh.face(f).size());
    if (k == 1)
      for (int e : L.edges_of(c)) cap[size_t(e)] += long(mesh.cell_vertices(c).size() + L.faces_of(c).size());
    else if (k == 2)
      for (int f : L.faces_of(c)) cap[size_t(f)] += long(L.edges_of(c).size()) + corners;
    else
      cap[size_t(c)] = corners;
  }
  return cap;
}

// Writes the rows of P_k of cell c's refined simplices not written yet (a face's rows are the
// same from both of its cells), their non-zero entries.
void emit_prolongation(const CellMaps& W, int c, int k, const SimplexComplex3& refined, std::vector<char>& done,
                       ColumnFill& P) {
  auto emit = [&](int row, auto values, auto col_of) {
    if (done[size_t(row)]) return;
    done[size_t(row)] = 1;
    for (Eigen::Index j = 0; j < values.size(); ++j)
      if (values[j] != 0.0) P.add(row, col_of(j), values[j]);
  };
  if (k == 1) {
    for (size_t r = 0; r < W.s1.size(); ++r)
      emit(refined_row(refined, W.s1[r]), W.P1.row(Eigen::Index(r)), [&](Eigen::Index j) { return W.edges[size_t(j)]; });
  } else if (k == 2) {
    for (size_t r = 0; r < W.s2.size(); ++r)
      emit(refined_row(refined, W.s2[r]), W.P2.row(Eigen::Index(r)), [&](Eigen::Index j) { return W.faces[size_t(j)]; });
  } else {
    for (size_t r = 0; r < W.tets.size(); ++r)
      emit(refined_row(refined, W.tets[r].v), W.P3.segment(Eigen::Index(r), 1), [&](Eigen::Index) { return c; });
  }
}

// The pattern of a star (the pairs of nodes sharing a cell) with each cell's slots, column-relative
// where every column has at most 65535 entries (half the memory), else absolute. Columns sorted in
// place: the pattern's arrays are allocated for sum m_c^2 entries but only the first nnz touched.
template <class NodesOf>
detail::ElementPattern star_pattern(int n_nodes, int n_cells, NodesOf nodes_of) {
  using detail::ColumnOrder;
  using detail::SlotKind;
  detail::ElementPattern ep = detail::element_pattern<SlotKind::column_relative, ColumnOrder::sort>(n_nodes, n_cells, nodes_of);
  if (!ep.relative_slots) ep = detail::element_pattern<SlotKind::absolute, ColumnOrder::sort>(n_nodes, n_cells, nodes_of);
  return ep;
}

// Adds the local block of cell c (over `nodes`, in the order the pattern was built with) to A.
void scatter(const detail::ElementPattern& ep, int c, const std::vector<int>& nodes, const Eigen::MatrixXd& local,
             SparseMatrix& A) {
  const int n = int(nodes.size());
  double* value = A.valuePtr();
  const long o = ep.offsets[size_t(c)];
  if (ep.relative_slots) {
    const std::uint16_t* s = ep.relative_slots.get() + o;
    const int* outer = A.outerIndexPtr();
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) value[outer[nodes[size_t(b)]] + s[a * n + b]] += local(a, b);
  } else {
    const int* s = ep.slots.data() + o;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) value[s[a * n + b]] += local(a, b);
  }
}

// One pass over the cells, each cell's maps built once, up to the highest degree asked for: the
// stars summed into their patterns, P_k written into its columns.
Assembled assemble(const VolumeMesh& mesh, const VolumeRefinement& R, const SimplexComplex3* refined,
                   const Request& request, SpokeRule rule) {
  int degree = std::max(request.star_degree, 0);
  for (int k = 1; k < 4; ++k)
    if (request.prolongations[k]) degree = std::max(degree, k);
  const int nV = mesh.n_vertices(), nF = mesh.n_faces(), nC = mesh.n_cells();
  if (degree > 0 && refined && refined->n_vertices() != nV + nF + nC)
    throw std::invalid_argument("volume_mesh_prolongation: the refined complex does not belong to this mesh");
  const int sizes[4] = {nV, mesh.n_edges(), nF, nC};
  Assembled out;
  std::vector<char> done[4];
  ColumnFill P[4];
  detail::ElementPattern pattern[3];
  {
    const CellLists L = cell_lists(mesh);
    for (int k = 1; k < 4; ++k)
      if (request.prolongations[k]) {
        done[k].assign(size_t(refined->n_simplices(k)), 0);
        P[k].init(refined->n_simplices(k), column_capacity(mesh, L, k));
      }
    if (request.star_degree >= 0)
      pattern[0] = star_pattern(nV, nC, [&](int c) { return mesh.cell_vertices(c); });
    if (request.star_degree >= 1) pattern[1] = star_pattern(sizes[1], nC, [&](int c) { return L.edges_of(c); });
    if (request.star_degree >= 2) pattern[2] = star_pattern(nF, nC, [&](int c) { return L.faces_of(c); });
  }
  for (int k = 0; k <= std::min(request.star_degree, 2); ++k) out.star[size_t(k)].swap(pattern[k].pattern);
  Eigen::VectorXd s3;
  if (request.star_degree >= 3) s3.setZero(nC);
  CellMaps W;
  Eigen::MatrixXd local[3];
  for (int c = 0; c < nC; ++c) {
    build_cell(mesh, R, c, degree, rule, W);
    for (int k = 1; k < 4; ++k)
      if (request.prolongations[k]) emit_prolongation(W, c, k, *refined, done[k], P[k]);
    if (request.star_degree < 0) continue;
    double s = 0;
    cell_star_blocks(mesh, R, W, request.star_degree, local, s);
    const std::vector<int>* nodes[3] = {&W.verts, &W.edges, &W.faces};
    for (int k = 0; k <= std::min(request.star_degree, 2); ++k)
      scatter(pattern[k], c, *nodes[k], local[k], out.star[size_t(k)]);
    if (request.star_degree >= 3) s3[c] = s;
  }
  for (int k = 1; k < 4; ++k)
    if (request.prolongations[k]) {
      std::vector<char>().swap(done[k]);
      P[k].finish(out.P[k]);
    }
  if (request.star_degree >= 3) {
    out.star[3].resize(nC, nC);
    out.star[3].resizeNonZeros(nC);
    for (int c = 0; c <= nC; ++c) out.star[3].outerIndexPtr()[c] = c;
    for (int c = 0; c < nC; ++c) out.star[3].innerIndexPtr()[c] = c, out.star[3].valuePtr()[c] = s3[c];
  }
  return out;
}
}  // namespace
}  // namespace volume_mesh_complex_detail

SparseMatrix volume_mesh_d(const VolumeMesh& mesh, int k) {
  using namespace volume_mesh_complex_detail;
  check_degree(k, 0, 2, "volume_mesh_d");
  std::vector<Triplet> t;
  SparseMatrix d;
  if (k == 0) {
    const Eigen::MatrixX2i& E = mesh.edges();
    for (int e = 0; e < E.rows(); ++e) {
      t.emplace_back(e, E(e, 0), -1.0);
      t.emplace_back(e, E(e, 1), 1.0);
    }
    d.resize(mesh.n_edges(), mesh.n_vertices());
  } else if (k == 1) {
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const auto face = mesh.face(f);
      const size_t n = face.size();
      for (size_t i = 0; i < n; ++i) {
        const int a = face[i], b = face[(i + 1) % n];
        t.emplace_back(f, global_edge(mesh.edges(), a, b), a < b ? 1.0 : -1.0);
      }
    }
    d.resize(mesh.n_faces(), mesh.n_edges());
  } else {
    for (int c = 0; c < mesh.n_cells(); ++c)
      for (int hf : mesh.cell(c)) t.emplace_back(c, hf / 2, (hf & 1) ? -1.0 : 1.0);
    d.resize(mesh.n_cells(), mesh.n_faces());
  }
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

SparseMatrix volume_mesh_prolongation(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                      const SimplexComplex3& refined, int k, SpokeRule rule) {
  using namespace volume_mesh_complex_detail;
  check_refinement(mesh, refinement, "volume_mesh_prolongation");
  check_degree(k, 0, 3, "volume_mesh_prolongation");
  if (k == 0) return volume_prolongation(mesh, refinement);
  Request request;
  request.prolongations[k] = true;
  Assembled a = assemble(mesh, refinement, &refined, request, rule);
  SparseMatrix P;
  P.swap(a.P[k]);
  return P;
}

SparseMatrix volume_mesh_prolongation(const VolumeMesh& mesh, const VolumeRefinement& refinement, int k,
                                      SpokeRule rule) {
  volume_mesh_complex_detail::check_degree(k, 0, 3, "volume_mesh_prolongation");
  if (k == 0) return volume_prolongation(mesh, refinement);
  return volume_mesh_prolongation(mesh, refinement, volume_refined_complex(mesh, refinement), k, rule);
}

std::array<SparseMatrix, 4> volume_mesh_stars(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                              int max_degree, SpokeRule rule) {
  using namespace volume_mesh_complex_detail;
  check_refinement(mesh, refinement, "volume_mesh_stars");
  check_degree(max_degree, 0, 3, "volume_mesh_stars");
  check_length_powers(mesh, star_length_powers(max_degree));
  Request request;
  request.star_degree = max_degree;
  return assemble(mesh, refinement, nullptr, request, rule).star;
}

VolumeMeshDec volume_mesh_dec(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                              const SimplexComplex3& refined, int max_degree, SpokeRule rule) {
  using namespace volume_mesh_complex_detail;
  check_refinement(mesh, refinement, "volume_mesh_dec");
  check_degree(max_degree, 0, 3, "volume_mesh_dec");
  Request request;
  for (int k = 1; k <= max_degree; ++k) request.prolongations[k] = true;
  request.star_degree = max_degree;
  Assembled a = assemble(mesh, refinement, &refined, request, rule);
  VolumeMeshDec D;
  for (int k = 0; k < max_degree; ++k) D.d[k] = volume_mesh_d(mesh, k);
  D.P[0] = volume_prolongation(mesh, refinement);
  for (int k = 1; k <= max_degree; ++k) D.P[k].swap(a.P[k]);  // swap: std::move copies an Eigen 3.4 SparseMatrix
  for (int k = 0; k <= max_degree; ++k) D.star[k].swap(a.star[size_t(k)]);
  return D;
}

VolumeMeshCell volume_mesh_cell(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                                const SimplexComplex3& refined, int c, int max_degree, SpokeRule rule) {
  using namespace volume_mesh_complex_detail;
  check_refinement(mesh, refinement, "volume_mesh_cell");
  check_degree(max_degree, 0, 3, "volume_mesh_cell");
  if (c < 0 || c >= mesh.n_cells())
    throw std::invalid_argument("volume_mesh_cell: cell " + std::to_string(c) + " of " + std::to_string(mesh.n_cells()));
  if (max_degree > 0 && refined.n_vertices() != mesh.n_vertices() + mesh.n_faces() + mesh.n_cells())
    throw std::invalid_argument("volume_mesh_cell: the refined complex does not belong to this mesh");
  CellMaps W;
  build_cell(mesh, refinement, c, max_degree, rule, W);
  VolumeMeshCell out;
  out.vertices = W.verts;
  out.edges = W.edges;
  out.faces = W.faces;
  cell_star_blocks(mesh, refinement, W, max_degree, out.star, out.star3);
  for (const auto& s : W.s1)
    if (max_degree >= 1) out.rows[1].push_back(refined_row(refined, s));
  for (const auto& s : W.s2)
    if (max_degree >= 2) out.rows[2].push_back(refined_row(refined, s));
  for (const auto& t : W.tets)
    if (max_degree >= 3) out.rows[3].push_back(refined_row(refined, t.v));
  if (max_degree >= 1) out.P[1] = W.P1;
  if (max_degree >= 2) out.P[2] = W.P2;
  if (max_degree >= 3) out.P[3] = W.P3;
  return out;
}

}  // namespace polydec
