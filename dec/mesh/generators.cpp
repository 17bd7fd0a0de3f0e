// dec/mesh/generators.cpp — sample meshes and mesh transformations.
#include "polydec/dec/mesh/generators.h"

#include <array>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <numbers>
#include <random>

namespace polydec {

namespace {

// Refuses a generated mesh of more than kMaxGeneratedVertices vertices before building it (the
// counts are estimated in double, so that huge arguments cannot overflow).
constexpr double kMaxGeneratedVertices = 1e8;

void check_size(double vertices, const char* what) {
  if (vertices > kMaxGeneratedVertices)
    throw std::invalid_argument(
        fmt::format("{}: about {:.3g} vertices asked for, at most {:g} generated", what, vertices,
                    kMaxGeneratedVertices));
}

PolygonSoup soup_with_positions(const std::vector<Eigen::Vector3d>& pts) {
  PolygonSoup s;
  s.positions.resize(long(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) s.positions.row(long(i)) = pts[i].transpose();
  return s;
}

int prev_corner(const Mesh& m, int h) {
  const int f = m.halfedge_face(h);
  return h == m.face_offsets()[f] ? m.face_offsets()[f + 1] - 1 : h - 1;
}

Eigen::Vector3d face_centroid(const Mesh& m, int f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : m.face(f)) c += m.position(v);
  return c / m.face_size(f);
}

}  // namespace

Mesh quad_grid(int nx, int ny) {
  if (nx < 1 || ny < 1) throw std::invalid_argument("quad_grid: needs at least one cell per direction");
  check_size((nx + 1.0) * (ny + 1.0), "quad_grid");
  std::vector<Eigen::Vector3d> p;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) p.emplace_back(double(i) / nx, double(j) / ny, 0.0);
  PolygonSoup s = soup_with_positions(p);
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::array<int, 4> q{id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      s.add_face(q);
    }
  return Mesh(std::move(s));
}

Mesh triangle_grid(int nx, int ny) {
  const Mesh q = quad_grid(nx, ny);
  PolygonSoup s;
  s.positions = q.positions();
  for (int f = 0; f < q.n_faces(); ++f) {
    const auto c = q.face(f);
    const std::array<int, 3> a{c[0], c[1], c[2]}, b{c[0], c[2], c[3]};
    s.add_face(a);
    s.add_face(b);
  }
  return Mesh(std::move(s));
}

Mesh hex_grid(int nx, int ny) { return dual(triangle_grid(nx, ny)); }

Mesh chevron_grid(int nx, int ny, double dent) {
  if (nx < 1 || ny < 1) throw std::invalid_argument("chevron_grid: needs at least one cell per direction");
  if (!(dent > 0 && dent < 0.5)) throw std::invalid_argument("chevron_grid: dent must lie in (0, 1/2)");
  std::vector<Eigen::Vector3d> p;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) p.emplace_back(double(i) / nx, double(j) / ny, 0.0);
  const int corners = int(p.size());
  for (int j = 0; j <= ny; ++j)  // midpoints of the horizontal edges, bent unless on the boundary
    for (int i = 0; i < nx; ++i)
      p.emplace_back((i + 0.5) / nx, (j + (j > 0 && j < ny ? dent : 0.0)) / ny, 0.0);
  PolygonSoup s = soup_with_positions(p);
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  auto mid = [&](int i, int j) { return corners + j * nx + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::array<int, 6> h{id(i, j), mid(i, j), id(i + 1, j), id(i + 1, j + 1), mid(i, j + 1), id(i, j + 1)};
      s.add_face(h);
    }
  return Mesh(std::move(s));
}

Mesh uv_sphere(int n_lat, int n_lon) {
  if (n_lat < 2 || n_lon < 3) throw std::invalid_argument("uv_sphere: needs n_lat >= 2 and n_lon >= 3");
  check_size(double(n_lat) * n_lon, "uv_sphere");
  std::vector<Eigen::Vector3d> p;
  p.emplace_back(0, 0, 1);
  for (int i = 1; i < n_lat; ++i) {
    const double th = std::numbers::pi * i / n_lat;
    for (int j = 0; j < n_lon; ++j) {
      const double ph = 2 * std::numbers::pi * j / n_lon;
      p.emplace_back(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
    }
  }
  p.emplace_back(0, 0, -1);
  PolygonSoup s = soup_with_positions(p);
  const int south = int(p.size()) - 1;
  auto id = [&](int i, int j) { return 1 + (i - 1) * n_lon + (j % n_lon); };
  for (int j = 0; j < n_lon; ++j) {
    const std::array<int, 3> t{0, id(1, j), id(1, j + 1)};
    s.add_face(t);
  }
  for (int i = 1; i + 1 < n_lat; ++i)
    for (int j = 0; j < n_lon; ++j) {
      const std::array<int, 4> q{id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      s.add_face(q);
    }
  for (int j = 0; j < n_lon; ++j) {
    const std::array<int, 3> t{south, id(n_lat - 1, j + 1), id(n_lat - 1, j)};
    s.add_face(t);
  }
  return Mesh(std::move(s));
}

Mesh cube_sphere(int n) {
  if (n < 1) throw std::invalid_argument("cube_sphere: needs n >= 1");
  check_size(6.0 * (n + 1.0) * (n + 1.0), "cube_sphere");
  // Lattice points on the cube surface [-1,1]^3, merged by integer coordinates.
  std::map<std::array<int, 3>, int> index;
  std::vector<Eigen::Vector3d> p;
  PolygonSoup s;
  auto vid = [&](std::array<int, 3> k) {
    auto [it, inserted] = index.try_emplace(k, int(p.size()));
    if (inserted) p.emplace_back(2.0 * k[0] / n - 1, 2.0 * k[1] / n - 1, 2.0 * k[2] / n - 1);
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          std::array<std::array<int, 3>, 4> c;
          const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
          for (int k = 0; k < 4; ++k) {
            c[k][axis] = side * n;
            c[k][u] = a + du[k];
            c[k][v] = b + dv[k];
          }
          std::array<int, 4> q{vid(c[0]), vid(c[1]), vid(c[2]), vid(c[3])};
          if (side == 0) std::swap(q[1], q[3]);  // outward orientation
          s.add_face(q);
        }
    }
  s.positions.resize(long(p.size()), 3);
  for (size_t i = 0; i < p.size(); ++i) s.positions.row(long(i)) = p[i].normalized().transpose();
  return Mesh(std::move(s));
}

Mesh hex_sphere(int level) {
  if (level < 0) throw std::invalid_argument("hex_sphere: needs level >= 0");
  check_size(20.0 * std::pow(4.0, level), "hex_sphere");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& x : p) x.normalize();
  std::vector<std::array<int, 3>> tris = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                          {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                          {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                          {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = mid.try_emplace(key, int(p.size()));
      if (inserted) p.push_back((p[a] + p[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : tris) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      next.push_back({f[0], a, c});
      next.push_back({f[1], b, a});
      next.push_back({f[2], c, b});
      next.push_back({a, b, c});
    }
    tris = std::move(next);
  }
  PolygonSoup s = soup_with_positions(p);
  for (const auto& f : tris) s.add_face(f);
  return project_to_unit_sphere(dual(Mesh(std::move(s))));
}

PolygonSoup torus_soup(int n_major, int n_minor, double R, double r) {
  if (n_major < 3 || n_minor < 3 || !(R > r) || !(r > 0)) throw std::invalid_argument("torus: bad parameters");
  check_size(double(n_major) * n_minor, "torus");
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < n_major; ++i)
    for (int j = 0; j < n_minor; ++j) {
      const double u = 2 * std::numbers::pi * i / n_major, v = 2 * std::numbers::pi * j / n_minor;
      p.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  PolygonSoup s = soup_with_positions(p);
  auto id = [&](int i, int j) { return (i % n_major) * n_minor + (j % n_minor); };
  for (int i = 0; i < n_major; ++i)
    for (int j = 0; j < n_minor; ++j) {
      const std::array<int, 4> q{id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      s.add_face(q);
    }
  return s;
}

Mesh torus(int n_major, int n_minor, double R, double r) { return Mesh(torus_soup(n_major, n_minor, R, r)); }

Mesh genus2(int subdivisions) {
  if (subdivisions < 0) throw std::invalid_argument("genus2: needs subdivisions >= 0");
  check_size(64.0 * std::pow(4.0, subdivisions), "genus2");  // 52 quads before subdividing
  // Occupancy of a 5 x 3 x 1 block with the cubes (1,1,0) and (3,1,0) removed.
  auto filled = [](int x, int y, int z) {
    if (x < 0 || x >= 5 || y < 0 || y >= 3 || z != 0) return false;
    return !(y == 1 && (x == 1 || x == 3));
  };
  std::map<std::array<int, 3>, int> index;
  std::vector<Eigen::Vector3d> p;
  PolygonSoup s;
  auto vid = [&](std::array<int, 3> k) {
    auto [it, inserted] = index.try_emplace(k, int(p.size()));
    if (inserted) p.emplace_back(k[0], k[1], k[2]);
    return it->second;
  };
  for (int x = 0; x < 5; ++x)
    for (int y = 0; y < 3; ++y)
      for (int z = 0; z < 1; ++z) {
        if (!filled(x, y, z)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int dir = -1; dir <= 1; dir += 2) {
            std::array<int, 3> nb{x, y, z};
            nb[axis] += dir;
            if (filled(nb[0], nb[1], nb[2])) continue;
            // Square on the cube's side facing `dir` along `axis`, oriented outward.
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            std::array<std::array<int, 3>, 4> c;
            const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
            for (int k = 0; k < 4; ++k) {
              c[k] = {x, y, z};
              c[k][axis] += dir > 0 ? 1 : 0;
              c[k][u] += du[k];
              c[k][v] += dv[k];
            }
            std::array<int, 4> q{vid(c[0]), vid(c[1]), vid(c[2]), vid(c[3])};
            if (dir < 0) std::swap(q[1], q[3]);
            s.add_face(q);
          }
      }
  s.positions.resize(long(p.size()), 3);
  for (size_t i = 0; i < p.size(); ++i) s.positions.row(long(i)) = p[i].transpose();
  Mesh m(std::move(s));
  for (int k = 0; k < subdivisions; ++k) m = catmull_clark(m);
  return m;
}

Mesh catmull_clark(const Mesh& m) {
  const int nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
  std::vector<Eigen::Vector3d> fp(nf);
  for (int f = 0; f < nf; ++f) fp[f] = face_centroid(m, f);
  // Faces adjacent to each edge (one or two).
  std::vector<std::array<int, 2>> edge_faces(ne, {-1, -1});
  for (int h = 0; h < m.n_halfedges(); ++h) {
    auto& ef = edge_faces[m.halfedge_edge(h)];
    (ef[0] < 0 ? ef[0] : ef[1]) = m.halfedge_face(h);
  }
  PolygonSoup s;
  s.positions.resize(nv + ne + nf, 3);
  for (int e = 0; e < ne; ++e) {
    const Eigen::Vector3d a = m.position(m.edges()(e, 0)), b = m.position(m.edges()(e, 1));
    const Eigen::Vector3d ep = m.is_boundary_edge(e) ? Eigen::Vector3d(0.5 * (a + b))
                                                     : Eigen::Vector3d((a + b + fp[edge_faces[e][0]] + fp[edge_faces[e][1]]) / 4);
    s.positions.row(nv + e) = ep.transpose();
  }
  for (int f = 0; f < nf; ++f) s.positions.row(nv + ne + f) = fp[f].transpose();
  // Vertex rules: accumulate neighbours over edges.
  std::vector<Eigen::Vector3d> nbr_sum(nv, Eigen::Vector3d::Zero()), bnd_sum(nv, Eigen::Vector3d::Zero());
  std::vector<int> valence(nv, 0);
  for (int e = 0; e < ne; ++e) {
    const int a = m.edges()(e, 0), b = m.edges()(e, 1);
    nbr_sum[a] += m.position(b);
    nbr_sum[b] += m.position(a);
    ++valence[a];
    ++valence[b];
    if (m.is_boundary_edge(e)) {
      bnd_sum[a] += m.position(b);
      bnd_sum[b] += m.position(a);
    }
  }
  for (int v = 0; v < nv; ++v) {
    const Eigen::Vector3d x = m.position(v);
    Eigen::Vector3d y = x;
    if (m.is_boundary_vertex(v)) {
      y = (6 * x + bnd_sum[v]) / 8;
    } else if (valence[v] > 0) {
      Eigen::Vector3d fsum = Eigen::Vector3d::Zero();
      for (int f : m.vertex_faces(v)) fsum += fp[f];
      const double k = valence[v];
      y = (nbr_sum[v] + fsum) / (k * k) + (k - 2) / k * x;
    }
    s.positions.row(v) = y.transpose();
  }
  for (int f = 0; f < nf; ++f) {
    const int b = m.face_offsets()[f], n = m.face_size(f);
    for (int k = 0; k < n; ++k) {
      const int h = b + k, hp = b + (k + n - 1) % n;
      const std::array<int, 4> q{m.halfedge_source(h), nv + m.halfedge_edge(h), nv + ne + f, nv + m.halfedge_edge(hp)};
      s.add_face(q);
    }
  }
  return Mesh(std::move(s));
}

Mesh dual(const Mesh& m) {
  const int nv = m.n_vertices(), nf = m.n_faces(), nh = m.n_halfedges();
  std::vector<Eigen::Vector3d> p;
  p.reserve(nf + 2 * m.n_boundary_edges());
  for (int f = 0; f < nf; ++f) p.push_back(face_centroid(m, f));
  std::vector<int> edge_mid(m.n_edges(), -1), vert_pt(nv, -1);
  for (int e = 0; e < m.n_edges(); ++e)
    if (m.is_boundary_edge(e)) {
      edge_mid[e] = int(p.size());
      p.push_back(0.5 * (m.position(m.edges()(e, 0)) + m.position(m.edges()(e, 1))));
    }
  for (int v = 0; v < nv; ++v)
    if (m.is_boundary_vertex(v)) {
      vert_pt[v] = int(p.size());
      p.push_back(m.position(v));
    }
  // One outgoing halfedge per vertex; for boundary vertices the boundary one.
  std::vector<int> out(nv, -1);
  for (int h = 0; h < nh; ++h) {
    const int v = m.halfedge_source(h);
    if (out[v] < 0 || m.halfedge_opposite(h) < 0) out[v] = h;
  }
  PolygonSoup s = soup_with_positions(p);
  std::vector<int> face;
  for (int v = 0; v < nv; ++v) {
    if (out[v] < 0) continue;  // unreferenced vertex: no dual face
    face.clear();
    const bool boundary = m.halfedge_opposite(out[v]) < 0;
    if (boundary) {
      face.push_back(vert_pt[v]);
      face.push_back(edge_mid[m.halfedge_edge(out[v])]);
    }
    int h = out[v];
    while (true) {
      face.push_back(m.halfedge_face(h));
      const int in = prev_corner(m, h);
      const int next = m.halfedge_opposite(in);
      if (next < 0) {
        face.push_back(edge_mid[m.halfedge_edge(in)]);
        break;
      }
      h = next;
      if (h == out[v]) break;
      if (int(face.size()) > nf + 2) break;
    }
    if (int(face.size()) != int(m.vertex_faces(v).size()) + (boundary ? 3 : 0))
      throw InvalidMeshError("vertex", v, fmt::format("dual: vertex {} is non-manifold (its faces form several fans)", v));
    s.add_face(face);
  }
  return Mesh(std::move(s));
}

Mesh project_to_unit_sphere(const Mesh& m) {
  Eigen::MatrixX3d X = m.positions();
  for (int v = 0; v < X.rows(); ++v) {
    const double n = X.row(v).norm();
    if (!(n > 0)) throw InvalidMeshError("vertex", v, fmt::format("cannot project vertex {} at the origin to the sphere", v));
    X.row(v) /= n;
  }
  return m.with_positions(std::move(X));
}

Mesh add_noise(const Mesh& m, double amplitude, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double a = amplitude * m.mean_edge_length();
  Eigen::MatrixX3d X = m.positions();
  for (int v = 0; v < X.rows(); ++v) {
    Eigen::Vector3d d;
    do d = Eigen::Vector3d(u(rng), u(rng), u(rng));
    while (d.squaredNorm() > 1.0);
    X.row(v) += a * d.transpose();
  }
  return m.with_positions(std::move(X));
}

}  // namespace polydec
