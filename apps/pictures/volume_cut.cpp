// apps/pictures/volume_cut.cpp — planar sections of volume meshes through the sub-tetrahedra of the
// refinement, and the clipped solid behind the plane.
#include "polydec/apps/pictures/volume_cut.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "polydec/operators/volume/laplacian.h"

namespace polydec {

namespace volume_cut_detail {
namespace {

// Refined vertices (mesh vertices, face points, cell points) with their signed distances and
// values, and the points made on the way, keyed by the refined edge (a, b), a <= b, they lie on.
struct Builder {
  const VolumeMesh& mesh;
  const VolumeRefinement& refinement;
  Eigen::VectorXd s, u;  // per refined vertex: signed distance, value (u empty: no scalar)
  std::unordered_map<std::uint64_t, int> index;
  std::vector<Eigen::Vector3d> points;
  std::vector<double> values;
  std::vector<int> offsets{0}, indices;

  Builder(const VolumeMesh& m, const VolumeRefinement& r, const Eigen::VectorXd& vertex_values,
          const CutPlane& plane)
      : mesh(m), refinement(r) {
    if (!plane.normal.allFinite() || !(plane.normal.norm() > 0) || !plane.point.allFinite())
      throw std::invalid_argument("volume cut: the plane needs a finite point and a non-zero finite normal");
    if (vertex_values.size() != 0 && vertex_values.size() != m.n_vertices())
      throw std::invalid_argument(
          fmt::format("volume cut: {} values for {} vertices", vertex_values.size(), m.n_vertices()));
    const int n = m.n_vertices() + m.n_faces() + m.n_cells();
    const Eigen::Vector3d nn = plane.normal.normalized();
    s.resize(n);
    double scale = plane.point.cwiseAbs().maxCoeff();
    for (int r = 0; r < n; ++r) {
      const Eigen::Vector3d x = refined_position(m, refinement, r);
      s[r] = nn.dot(x - plane.point);
      scale = std::max(scale, x.cwiseAbs().maxCoeff());
    }
    // Refined vertices within round-off of the plane lie on it: a face point or cell point of a
    // face or cell in the plane misses it by ~eps times the coordinates, and the tetrahedra
    // around it would otherwise be cut into slivers of arbitrary orientation.
    const double on_plane = 64 * std::numeric_limits<double>::epsilon() * scale;
    for (int r = 0; r < n; ++r)
      if (std::abs(s[r]) <= on_plane) s[r] = 0;
    if (vertex_values.size()) u = volume_prolongation(m, refinement) * vertex_values;
  }

  // The point where the plane crosses refined edge (a, b) (s[a], s[b] of opposite signs or zero);
  // the refined vertex itself when it lies on the plane.
  int crossing(int a, int b) {
    if (s[a] == 0)
      b = a;
    else if (s[b] == 0)
      a = b;
    if (a > b) std::swap(a, b);
    const std::uint64_t key = std::uint64_t(a) * std::uint64_t(s.size()) + std::uint64_t(b);
    const auto [it, inserted] = index.try_emplace(key, int(points.size()));
    if (inserted) {
      const double t = a == b ? 0.0 : s[a] / (s[a] - s[b]);
      points.push_back((1 - t) * refined_position(mesh, refinement, a) +
                       t * refined_position(mesh, refinement, b));
      if (u.size()) values.push_back((1 - t) * u[a] + t * u[b]);
    }
    return it->second;
  }

  // Adds the polygon (point indices) without repeated consecutive points, if 3 or more remain.
  void add(std::vector<int> poly) {
    std::vector<int> p;
    for (size_t i = 0; i < poly.size(); ++i)
      if (poly[i] != poly[(i + 1) % poly.size()]) p.push_back(poly[i]);
    if (p.size() < 3) return;
    indices.insert(indices.end(), p.begin(), p.end());
    offsets.push_back(int(indices.size()));
  }
};

// Section of one sub-tetrahedron (refined vertices v): "front" is s >= 0 (so a face in the plane
// is cut from the tetrahedron behind it only); a triangle or quadrilateral, oriented with normal +n.
void cut_tet(Builder& B, const int v[4], const Eigen::Vector3d& normal) {
  int front[4], back[4], nf = 0, nb = 0;
  for (int a = 0; a < 4; ++a) (B.s[v[a]] >= 0 ? front[nf++] : back[nb++]) = v[a];
  if (nf == 0 || nb == 0) return;
  std::vector<int> poly;
  if (nf == 1 || nb == 1) {
    const int apex = nf == 1 ? front[0] : back[0];
    const int* base = nf == 1 ? back : front;
    for (int k = 0; k < 3; ++k) poly.push_back(B.crossing(apex, base[k]));
  } else {
    poly = {B.crossing(front[0], back[0]), B.crossing(front[0], back[1]), B.crossing(front[1], back[1]),
            B.crossing(front[1], back[0])};
  }
  // Orientation: the polygon's area vector along +n; a piece without area (the plane through an
  // edge and a vertex of the tetrahedron only) is dropped.
  const Eigen::Vector3d o = B.points[poly[0]];
  Eigen::Vector3d area = Eigen::Vector3d::Zero();
  double perimeter = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector3d p = B.points[poly[i]] - o, q = B.points[poly[(i + 1) % poly.size()]] - o;
    area += p.cross(q);
    perimeter += (q - p).norm();
  }
  if (!(area.norm() > 1e-12 * perimeter * perimeter)) return;
  if (area.dot(normal) < 0) std::reverse(poly.begin(), poly.end());
  B.add(std::move(poly));
}

// Degenerate (flat) sub-tetrahedra have no section area; skipped, so their zero-area pieces, of
// arbitrary orientation, do not enter the surface.
void cut_all(Builder& B, const Eigen::Vector3d& normal) {
  for (const RefinedTet& t : refined_tets(B.mesh, B.refinement))
    if (t.quality != SubTet::Degenerate) cut_tet(B, t.v, normal);
}

double polygon_area(const Eigen::MatrixX3d& X, std::span<const int> p) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < p.size(); ++i)
    a += Eigen::Vector3d(X.row(p[i])).cross(Eigen::Vector3d(X.row(p[(i + 1) % p.size()])));
  return 0.5 * a.norm();
}

std::string plane_miss_message(const Builder& B, const CutPlane& plane) {
  const Eigen::VectorXd sv = B.s.head(B.mesh.n_vertices());
  return fmt::format(
      "the cut plane through ({:.6g}, {:.6g}, {:.6g}) with normal ({:.6g}, {:.6g}, {:.6g}) {} the volume "
      "mesh "
      "(signed distances of its vertices from {:.6g} to {:.6g})",
      plane.point.x(), plane.point.y(), plane.point.z(), plane.normal.x(), plane.normal.y(), plane.normal.z(),
      sv.minCoeff() >= 0 ? "keeps nothing of" : "misses", sv.minCoeff(), sv.maxCoeff());
}

}  // namespace
}  // namespace volume_cut_detail

double VolumeCut::area() const {
  double a = 0;
  for (int k = 0; k < n_polygons(); ++k)
    a += volume_cut_detail::polygon_area(
        positions,
        std::span<const int>(indices).subspan(size_t(offsets[k]), size_t(offsets[k + 1] - offsets[k])));
  return a;
}

VolumeCut cut_volume(const VolumeMesh& mesh, const VolumeRefinement& refinement,
                     const Eigen::VectorXd& vertex_values, const CutPlane& plane) {
  check_refinement(mesh, refinement, "cut_volume");
  using namespace volume_cut_detail;
  Builder B(mesh, refinement, vertex_values, plane);
  cut_all(B, plane.normal);
  VolumeCut cut;
  cut.positions.resize(Eigen::Index(B.points.size()), 3);
  for (size_t i = 0; i < B.points.size(); ++i) cut.positions.row(Eigen::Index(i)) = B.points[i].transpose();
  cut.values = Eigen::Map<const Eigen::VectorXd>(B.values.data(), Eigen::Index(B.values.size()));
  cut.offsets = std::move(B.offsets);
  cut.indices = std::move(B.indices);
  return cut;
}

Mesh cut_solid(const VolumeMesh& mesh, const VolumeRefinement& refinement,
               const Eigen::VectorXd& vertex_values, const CutPlane& plane, Eigen::VectorXd* values) {
  check_refinement(mesh, refinement, "cut_solid");
  using namespace volume_cut_detail;
  Builder B(mesh, refinement, vertex_values, plane);
  cut_all(B, plane.normal);
  if (B.offsets.size() == 1) throw std::invalid_argument(plane_miss_message(B, plane));
  // Boundary faces, outward, clipped to s <= 0 (Sutherland-Hodgman); faces in the plane dropped.
  for (int f = 0; f < mesh.n_faces(); ++f) {
    if (!mesh.is_boundary_face(f)) continue;
    std::vector<int> face(mesh.face(f).begin(), mesh.face(f).end());
    if (mesh.face_cells(f)[0] < 0) std::reverse(face.begin(), face.end());
    bool in_plane = true;
    for (int v : face) in_plane = in_plane && B.s[v] == 0;
    if (in_plane) continue;
    std::vector<int> poly;
    for (size_t i = 0; i < face.size(); ++i) {
      const int a = face[i], b = face[(i + 1) % face.size()];
      if (B.s[a] <= 0) poly.push_back(B.crossing(a, a));
      if ((B.s[a] < 0 && B.s[b] > 0) || (B.s[a] > 0 && B.s[b] < 0)) poly.push_back(B.crossing(a, b));
    }
    B.add(std::move(poly));
  }
  PolygonSoup soup;
  soup.positions.resize(Eigen::Index(B.points.size()), 3);
  for (size_t i = 0; i < B.points.size(); ++i) soup.positions.row(Eigen::Index(i)) = B.points[i].transpose();
  soup.face_offsets = std::move(B.offsets);
  soup.face_indices = std::move(B.indices);
  if (values) *values = Eigen::Map<const Eigen::VectorXd>(B.values.data(), Eigen::Index(B.values.size()));
  return Mesh(std::move(soup));
}

CutPlane centre_plane(const VolumeMesh& mesh, const Eigen::Vector3d& normal) {
  CutPlane p;
  p.point = 0.5 * (mesh.positions().colwise().minCoeff() + mesh.positions().colwise().maxCoeff()).transpose();
  p.normal = normal;
  return p;
}

Eigen::Vector3d cut_view_direction(const CutPlane& plane, const Eigen::Vector3d& up) {
  const Eigen::Vector3d n = plane.normal.normalized();
  Eigen::Vector3d u = up - up.dot(n) * n;
  if (!(u.norm() > 1e-6 * up.norm())) u = n.unitOrthogonal();
  u.normalize();
  return -n - 0.5 * u - 0.35 * n.cross(u);
}

void render_volume_cut_png(const std::string& path, const VolumeMesh& mesh,
                           const VolumeRefinement& refinement, const Eigen::VectorXd& vertex_values,
                           const CutPlane& plane, RenderOptions options) {
  check_refinement(mesh, refinement, "render_volume_cut_png");
  Eigen::VectorXd values;
  const Mesh solid = cut_solid(mesh, refinement, vertex_values, plane, &values);
  if (options.view_direction.isZero()) options.view_direction = cut_view_direction(plane, options.up);
  render_png(path, solid, values, options);
}

void render_volume_cut_png(const std::string& path, const VolumeMesh& mesh,
                           const Eigen::VectorXd& vertex_values, const CutPlane& plane,
                           RenderOptions options) {
  render_volume_cut_png(path, mesh, refine_volume(mesh), vertex_values, plane, std::move(options));
}

}  // namespace polydec
