// dec/mesh/volume_generators.cpp — the generated volume meshes of dec/mesh/volume_generators.h.
#include "polydec/dec/mesh/volume_generators.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <tuple>

#include "polydec/dec/mesh/polyhedron_builder.h"

namespace polydec {
namespace volume_generators_detail {
namespace {

void check_counts(int nx, int ny, int nz, const char* what) {
  if (nx < 1 || ny < 1 || nz < 1 || double(nx + 1) * (ny + 1) * (nz + 1) > 1e9)
    throw std::invalid_argument(fmt::format(
        "{}: cell counts {} x {} x {} must be at least 1 (and at most ~1e9 vertices)", what, nx, ny, nz));
}

Eigen::MatrixX3d grid_positions(int nx, int ny, int nz, int extra) {
  Eigen::MatrixX3d X(Eigen::Index(nx + 1) * (ny + 1) * (nz + 1) + extra, 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        X.row(i + (nx + 1) * (j + Eigen::Index(ny + 1) * k)) << double(i) / nx, double(j) / ny,
            double(k) / nz;
  return X;
}

// The 8 corners of cube (i, j, k) in VTK hexahedron order.
std::array<int, 8> cube_corners(int nx, int ny, int i, int j, int k) {
  auto id = [&](int a, int b, int c) { return a + (nx + 1) * (b + (ny + 1) * c); };
  return {id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
          id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
}

double tet_volume6(const Eigen::MatrixX3d& X, const std::array<int, 4>& t) {
  const Eigen::Vector3d a = X.row(t[0]), b = X.row(t[1]), c = X.row(t[2]), d = X.row(t[3]);
  return (b - a).cross(c - a).dot(d - a);
}

// A convex cell {x : n_k . x <= d_k} with integer planes whose vertices are integer points:
// vertices from plane triples (Cramer's rule, kept when integral and inside), faces as the
// vertices on each plane ordered counter-clockwise seen from outside.
struct Plane {
  std::array<long long, 3> n;
  long long d;
};

std::vector<std::vector<std::array<long long, 3>>> integer_convex_cell(std::vector<Plane> planes) {
  // The same plane twice (a box side that is also a bisector) would give its face twice.
  for (auto& p : planes) {
    const long long g =
        std::gcd(std::gcd(std::gcd(std::abs(p.n[0]), std::abs(p.n[1])), std::abs(p.n[2])), std::abs(p.d));
    if (g > 1) p = {{p.n[0] / g, p.n[1] / g, p.n[2] / g}, p.d / g};
  }
  std::sort(planes.begin(), planes.end(),
            [](const Plane& a, const Plane& b) { return std::tie(a.n, a.d) < std::tie(b.n, b.d); });
  planes.erase(std::unique(planes.begin(), planes.end(),
                           [](const Plane& a, const Plane& b) { return a.n == b.n && a.d == b.d; }),
               planes.end());
  std::vector<std::array<long long, 3>> verts;
  const size_t np = planes.size();
  for (size_t a = 0; a < np; ++a)
    for (size_t b = a + 1; b < np; ++b)
      for (size_t c = b + 1; c < np; ++c) {
        const auto &p = planes[a].n, &q = planes[b].n, &r = planes[c].n;
        auto det3 = [](const std::array<long long, 3>& x, const std::array<long long, 3>& y,
                       const std::array<long long, 3>& z) {
          return x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) +
                 x[2] * (y[0] * z[1] - y[1] * z[0]);
        };
        const long long D = det3(p, q, r);
        if (D == 0) continue;
        std::array<long long, 3> x;
        bool integral = true;
        for (int k = 0; k < 3 && integral; ++k) {
          auto pk = p, qk = q, rk = r;
          pk[k] = planes[a].d, qk[k] = planes[b].d, rk[k] = planes[c].d;
          const long long N = det3(pk, qk, rk);
          integral = N % D == 0;
          x[k] = integral ? N / D : 0;
        }
        if (!integral) continue;
        bool inside = true;
        for (const auto& pl : planes)
          inside = inside && pl.n[0] * x[0] + pl.n[1] * x[1] + pl.n[2] * x[2] <= pl.d;
        if (inside && std::find(verts.begin(), verts.end(), x) == verts.end()) verts.push_back(x);
      }
  std::vector<std::vector<std::array<long long, 3>>> faces;
  for (const auto& pl : planes) {
    std::vector<std::array<long long, 3>> on;
    for (const auto& x : verts)
      if (pl.n[0] * x[0] + pl.n[1] * x[1] + pl.n[2] * x[2] == pl.d) on.push_back(x);
    if (on.size() < 3) continue;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& x : on) centre += Eigen::Vector3d(double(x[0]), double(x[1]), double(x[2]));
    centre /= double(on.size());
    const Eigen::Vector3d nn =
        Eigen::Vector3d(double(pl.n[0]), double(pl.n[1]), double(pl.n[2])).normalized();
    const Eigen::Vector3d u =
        (Eigen::Vector3d(double(on[0][0]), double(on[0][1]), double(on[0][2])) - centre).normalized();
    const Eigen::Vector3d w = nn.cross(u);
    auto angle = [&](const std::array<long long, 3>& x) {
      const Eigen::Vector3d d = Eigen::Vector3d(double(x[0]), double(x[1]), double(x[2])) - centre;
      return std::atan2(d.dot(w), d.dot(u));
    };
    std::sort(on.begin(), on.end(), [&](const auto& x, const auto& y) { return angle(x) < angle(y); });
    // A point where a third plane touches an edge is no vertex: drop corners collinear with their
    // neighbours (exact in integers); a plane that only touches an edge leaves fewer than 3.
    for (bool changed = true; changed && on.size() >= 3;) {
      changed = false;
      for (size_t i = 0; i < on.size(); ++i) {
        const auto &a = on[(i + on.size() - 1) % on.size()], &b = on[i], &c = on[(i + 1) % on.size()];
        const std::array<long long, 3> u{b[0] - a[0], b[1] - a[1], b[2] - a[2]},
            v{c[0] - b[0], c[1] - b[1], c[2] - b[2]};
        if (u[1] * v[2] - u[2] * v[1] == 0 && u[2] * v[0] - u[0] * v[2] == 0 &&
            u[0] * v[1] - u[1] * v[0] == 0) {
          on.erase(on.begin() + long(i));
          changed = true;
          break;
        }
      }
    }
    if (on.size() >= 3) faces.push_back(std::move(on));
  }
  return faces;
}

VolumeMesh finish(PolyhedronSoupBuilder& builder, const VolumeJitter& jitter) {
  VolumeMesh mesh(builder.take());
  return jitter.amplitude > 0 ? jitter_interior(mesh, jitter) : mesh;
}

}  // namespace
}  // namespace volume_generators_detail

using namespace volume_generators_detail;

VolumeMesh jitter_interior(const VolumeMesh& mesh, const VolumeJitter& jitter) {
  if (!(jitter.amplitude >= 0) || !std::isfinite(jitter.amplitude))
    throw std::invalid_argument(
        fmt::format("jitter amplitude {} must be finite and non-negative", jitter.amplitude));
  const Eigen::MatrixX3d& X0 = mesh.positions();
  std::vector<double> shortest(mesh.n_vertices(), std::numeric_limits<double>::infinity());
  const auto& E = mesh.edges();
  for (Eigen::Index e = 0; e < E.rows(); ++e) {
    const double l = (X0.row(E(e, 0)) - X0.row(E(e, 1))).norm();
    shortest[E(e, 0)] = std::min(shortest[E(e, 0)], l);
    shortest[E(e, 1)] = std::min(shortest[E(e, 1)], l);
  }
  std::mt19937_64 rng(jitter.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixX3d X = X0;
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    Eigen::Vector3d d;
    do d = Eigen::Vector3d(u(rng), u(rng), u(rng));
    while (d.squaredNorm() > 1.0);
    if (mesh.is_boundary_vertex(v) || !std::isfinite(shortest[v])) continue;
    X.row(v) += jitter.amplitude * shortest[v] * d.transpose();
  }
  return mesh.with_positions(std::move(X));
}

VolumeMesh hex_grid_volume(int nx, int ny, int nz, const VolumeJitter& jitter) {
  check_counts(nx, ny, nz, "hex_grid_volume");
  PolyhedronSoupBuilder builder(grid_positions(nx, ny, nz, 0));
  const long cells = long(nx) * ny * nz,
             faces = long(nx + 1) * ny * nz + long(nx) * (ny + 1) * nz + long(nx) * ny * (nz + 1);
  builder.reserve(faces, 4 * faces, cells, 6 * cells);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) builder.add_vtk_cell(kVtkHexahedron, cube_corners(nx, ny, i, j, k));
  return finish(builder, jitter);
}

VolumeMesh cuboctahedra_volume(int n, const VolumeJitter& jitter) {
  check_counts(n, n, n, "cuboctahedra_volume");
  // Points on the half-step lattice (a, b, c) in 0..2n: grid corners (all even) and edge
  // midpoints (exactly one odd); numbered in order of first use.
  const int L = 2 * n + 1;
  std::vector<int> index(size_t(L) * L * L, -1);
  std::vector<std::array<int, 3>> points;
  auto id = [&](int a, int b, int c) {
    int& i = index[(size_t(c) * L + b) * L + a];
    if (i < 0) {
      i = int(points.size());
      points.push_back({a, b, c});
    }
    return i;
  };
  // Cells as polygon lists over lattice ids, oriented afterwards.
  std::vector<std::vector<std::vector<int>>> cells;
  cells.reserve(size_t(9) * n * n * n);
  static constexpr int kSquare[4][2] = {{1, 0}, {2, 1}, {1, 2}, {0, 1}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int O[3] = {2 * i, 2 * j, 2 * k};
        auto at = [&](const std::array<int, 3>& p) { return id(O[0] + p[0], O[1] + p[1], O[2] + p[2]); };
        std::vector<std::vector<int>> cubocta;
        for (int d = 0; d < 3; ++d)
          for (int side : {0, 2}) {
            std::vector<int> square;
            for (const auto& uv : kSquare) {
              std::array<int, 3> p{};
              p[d] = side, p[(d + 1) % 3] = uv[0], p[(d + 2) % 3] = uv[1];
              square.push_back(at(p));
            }
            cubocta.push_back(square);
          }
        for (int corner = 0; corner < 8; ++corner) {
          const std::array<int, 3> c{2 * (corner & 1), (corner & 2), (corner & 4) / 2};
          std::vector<int> tri;
          for (int d = 0; d < 3; ++d) {
            std::array<int, 3> m = c;
            m[d] = 1;
            tri.push_back(at(m));
          }
          cubocta.push_back(tri);
          const int apex = at(c);
          cells.push_back({tri, {apex, tri[0], tri[1]}, {apex, tri[1], tri[2]}, {apex, tri[2], tri[0]}});
        }
        cells.push_back(std::move(cubocta));
      }
  Eigen::MatrixX3d X(points.size(), 3);
  for (size_t v = 0; v < points.size(); ++v)
    for (int d = 0; d < 3; ++d) X(long(v), d) = points[v][d] / (2.0 * n);
  PolyhedronSoupBuilder builder(X);
  for (auto& cell : cells) {
    // Convex cells: a polygon points outward when its normal points away from the cell's centroid.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    int count = 0;
    for (const auto& poly : cell)
      for (int v : poly) centre += X.row(v).transpose(), ++count;
    centre /= count;
    for (auto& poly : cell) {
      const Eigen::Vector3d a = X.row(poly[0]), b = X.row(poly[1]), c = X.row(poly[2]);
      if ((b - a).cross(c - a).dot(a - centre) < 0) std::reverse(poly.begin(), poly.end());
      builder.add_polygon(poly);
    }
    builder.end_cell();
  }
  return finish(builder, jitter);
}

VolumeMesh tet_grid_volume(int nx, int ny, int nz, const VolumeJitter& jitter) {
  check_counts(nx, ny, nz, "tet_grid_volume");
  const Eigen::MatrixX3d X = grid_positions(nx, ny, nz, 0);
  PolyhedronSoupBuilder builder(X);
  // Kuhn paths 0 -> e_a -> e_a + e_b -> (1,1,1) as corner numbers (bit 0: x, bit 1: y, bit 2: z).
  static constexpr int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        auto id = [&](int bits) {
          return (i + (bits & 1)) + (nx + 1) * ((j + ((bits >> 1) & 1)) + (ny + 1) * (k + ((bits >> 2) & 1)));
        };
        for (const auto& p : kPerm) {
          std::array<int, 4> t{id(0), id(1 << p[0]), id((1 << p[0]) | (1 << p[1])), id(7)};
          if (tet_volume6(X, t) < 0) std::swap(t[1], t[2]);
          builder.add_vtk_cell(kVtkTetra, t);
        }
      }
  return finish(builder, jitter);
}

VolumeMesh pyramid_grid_volume(int nx, int ny, int nz, const VolumeJitter& jitter) {
  check_counts(nx, ny, nz, "pyramid_grid_volume");
  const int n_grid = (nx + 1) * (ny + 1) * (nz + 1);
  Eigen::MatrixX3d X = grid_positions(nx, ny, nz, nx * ny * nz);
  const auto& hex = vtk_cell_faces(kVtkHexahedron);
  std::vector<std::array<int, 5>> pyramids;
  int centre = n_grid;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i, ++centre) {
        const auto c = cube_corners(nx, ny, i, j, k);
        X.row(centre) << (i + 0.5) / nx, (j + 0.5) / ny, (k + 0.5) / nz;
        // VTK's pyramid base points toward the apex: the hexahedron's outward face reversed.
        for (const auto& f : hex) pyramids.push_back({c[f[0]], c[f[3]], c[f[2]], c[f[1]], centre});
      }
  PolyhedronSoupBuilder builder(std::move(X));
  for (const auto& p : pyramids) builder.add_vtk_cell(kVtkPyramid, p);
  return finish(builder, jitter);
}

VolumeMesh truncated_octahedra_volume(int n, const VolumeJitter& jitter) {
  check_counts(n, n, n, "truncated_octahedra_volume");
  // Integer coordinates: the box is [0, 4n]^3, corner sites at multiples of 4, centre sites at
  // 4 (i, j, k) + 2; every vertex of the clipped cells is then an integer point.
  const long long L = 4LL * n;
  std::vector<std::array<long long, 3>> sites;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) sites.push_back({4LL * i, 4LL * j, 4LL * k});
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) sites.push_back({4LL * i + 2, 4LL * j + 2, 4LL * k + 2});
  // The 14 lattice neighbours (those outside the box included: the box planes are mirror planes
  // of the lattice, so the clipped cell is the full Voronoi cell intersected with the box).
  std::vector<std::array<long long, 3>> offsets;
  for (int a = 0; a < 3; ++a)
    for (int s = -1; s <= 1; s += 2) {
      std::array<long long, 3> o{0, 0, 0};
      o[a] = 4 * s;
      offsets.push_back(o);
    }
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2)
      for (int sz = -1; sz <= 1; sz += 2) offsets.push_back({2LL * sx, 2LL * sy, 2LL * sz});

  std::map<std::array<long long, 3>, int> vertex_id;
  std::vector<std::vector<std::vector<int>>> cells;
  for (const auto& s : sites) {
    std::vector<Plane> planes;
    for (int a = 0; a < 3; ++a) {
      std::array<long long, 3> e{0, 0, 0};
      e[a] = 1;
      planes.push_back({e, L});
      e[a] = -1;
      planes.push_back({e, 0});
    }
    for (const auto& o : offsets) {
      // |x - s|^2 <= |x - t|^2 with t = s + o:  2 o . x <= |t|^2 - |s|^2.
      long long t2 = 0, s2 = 0;
      for (int a = 0; a < 3; ++a) t2 += (s[a] + o[a]) * (s[a] + o[a]), s2 += s[a] * s[a];
      planes.push_back({{2 * o[0], 2 * o[1], 2 * o[2]}, t2 - s2});
    }
    auto faces = integer_convex_cell(planes);
    std::vector<std::vector<int>> cell;
    for (const auto& f : faces) {
      std::vector<int> poly;
      for (const auto& x : f) {
        const auto [it, inserted] = vertex_id.try_emplace(x, int(vertex_id.size()));
        poly.push_back(it->second);
      }
      cell.push_back(std::move(poly));
    }
    cells.push_back(std::move(cell));
  }
  Eigen::MatrixX3d X(Eigen::Index(vertex_id.size()), 3);
  for (const auto& [x, id] : vertex_id)
    X.row(id) << double(x[0]) / double(L), double(x[1]) / double(L), double(x[2]) / double(L);
  PolyhedronSoupBuilder builder(std::move(X));
  for (const auto& cell : cells) {
    for (const auto& poly : cell)
      if (builder.add_polygon(poly) < 0)
        throw std::logic_error("truncated_octahedra_volume: a face's vertices recur in another cyclic order");
    builder.end_cell();
  }
  return finish(builder, jitter);
}

VolumeMesh hex_torus_volume(int n_around, int n_cross, double R, double r, const VolumeJitter& jitter) {
  if (n_around < 3 || n_cross < 1 || double(n_around) * (n_cross + 1) * (n_cross + 1) > 1e9)
    throw std::invalid_argument(fmt::format(
        "hex_torus_volume: n_around {} must be at least 3, n_cross {} at least 1", n_around, n_cross));
  if (!(r > 0) || !(R > r) || !std::isfinite(R))
    throw std::invalid_argument(fmt::format("hex_torus_volume: radii R = {}, r = {} need 0 < r < R", R, r));
  const int m = n_cross + 1;
  auto id = [&](int a, int i, int j) { return (a % n_around) * m * m + i + m * j; };
  Eigen::MatrixX3d X(Eigen::Index(n_around) * m * m, 3);
  for (int a = 0; a < n_around; ++a) {
    const double phi = 2 * M_PI * a / n_around;
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const double rho = R + r * (2.0 * i / n_cross - 1), z = r * (2.0 * j / n_cross - 1);
        X.row(id(a, i, j)) << rho * std::cos(phi), rho * std::sin(phi), z;
      }
  }
  PolyhedronSoupBuilder builder(X);
  for (int a = 0; a < n_around; ++a)
    for (int j = 0; j < n_cross; ++j)
      for (int i = 0; i < n_cross; ++i) {
        // (i, a, j) as (x, y, z) of a hexahedron in VTK order: radial, around, up.
        std::array<int, 8> c{
            id(a, i, j),     id(a, i + 1, j),     id(a + 1, i + 1, j),     id(a + 1, i, j),
            id(a, i, j + 1), id(a, i + 1, j + 1), id(a + 1, i + 1, j + 1), id(a + 1, i, j + 1)};
        if (tet_volume6(X, {c[0], c[1], c[3], c[4]}) < 0) {
          std::swap(c[1], c[3]);
          std::swap(c[5], c[7]);
        }
        builder.add_vtk_cell(kVtkHexahedron, c);
      }
  return finish(builder, jitter);
}

VolumeMesh hex_ball_volume(int n, const VolumeJitter& jitter) {
  check_counts(n, n, n, "hex_ball_volume");
  Eigen::MatrixX3d X = grid_positions(n, n, n, 0);
  for (Eigen::Index v = 0; v < X.rows(); ++v) {
    const Eigen::Vector3d x = 2.0 * X.row(v).transpose() - Eigen::Vector3d::Ones();
    const double t = x.cwiseAbs().maxCoeff(), l = x.norm();
    const double scale = l == 0     ? 0.0
                         : t == 1.0 ? 1.0 / l  // boundary: exactly on the sphere
                                    : (1 - t) + t * t / l;
    X.row(v) = (x * scale).transpose();
  }
  PolyhedronSoupBuilder builder(std::move(X));
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) builder.add_vtk_cell(kVtkHexahedron, cube_corners(n, n, i, j, k));
  return finish(builder, jitter);
}

}  // namespace polydec
