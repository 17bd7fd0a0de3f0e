// apps/pictures/vector_field.cpp — arrows as extra polygons rendered with the surface.
#include "polydec/apps/pictures/vector_field.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace polydec {

void render_vector_field_png(const std::string& path, const Mesh& mesh, const Eigen::VectorXd& vertex_scalar,
                             const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& vectors,
                             RenderOptions render_options, const ArrowOptions& arrows) {
  const int nf = mesh.n_faces(), nv = mesh.n_vertices();
  if (points.rows() != nf || vectors.rows() != nf)
    throw std::invalid_argument("render_vector_field_png: one point and one vector per face expected");
  if (vertex_scalar.size() != 0 && vertex_scalar.size() != nv)
    throw std::invalid_argument("render_vector_field_png: one scalar per vertex expected");
  const double h = mesh.mean_edge_length();
  // Tangent vectors (projected to each face's plane) and the face normals.
  Eigen::MatrixX3d T(nf, 3), N(nf, 3);
  double longest = 0;
  for (int f = 0; f < nf; ++f) {
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    const auto face = mesh.face(f);
    for (size_t i = 0; i < face.size(); ++i)
      a += mesh.position(face[i]).cross(mesh.position(face[(i + 1) % face.size()]));
    const Eigen::Vector3d n = a.norm() > 0 ? Eigen::Vector3d(a.normalized()) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d v = vectors.row(f).transpose();
    N.row(f) = n.transpose();
    T.row(f) = (v - n * n.dot(v)).transpose();
    if (std::isfinite(T.row(f).norm())) longest = std::max(longest, T.row(f).norm());
  }
  PolygonSoup soup;
  std::vector<Eigen::RowVector3d> pos;
  for (int v = 0; v < nv; ++v) pos.push_back(mesh.positions().row(v));
  for (int f = 0; f < nf; ++f) soup.add_face(std::vector<int>(mesh.face(f).begin(), mesh.face(f).end()));
  const double L = arrows.length * h, w = arrows.width * L;
  for (int f = 0; f < nf && longest > 0; ++f) {
    const Eigen::Vector3d t = T.row(f).transpose(), n = N.row(f).transpose();
    const double len = L * t.norm() / longest;
    if (!(len > 0.05 * L) || n.isZero()) continue;  // too short to see
    const Eigen::Vector3d dir = t.normalized(), side = n.cross(dir);
    const Eigen::Vector3d base = points.row(f).transpose() + arrows.lift * h * n - 0.5 * len * dir;
    const double shaft = 0.65 * len, hw = std::min(w, 0.25 * len);
    const int b = int(pos.size());
    for (const Eigen::Vector3d& p :
         {Eigen::Vector3d(base - 0.5 * hw * side), Eigen::Vector3d(base + shaft * dir - 0.5 * hw * side),
          Eigen::Vector3d(base + shaft * dir + 0.5 * hw * side), Eigen::Vector3d(base + 0.5 * hw * side),
          Eigen::Vector3d(base + shaft * dir - 1.2 * hw * side), Eigen::Vector3d(base + len * dir),
          Eigen::Vector3d(base + shaft * dir + 1.2 * hw * side)})
      pos.push_back(p.transpose());
    soup.add_face(std::vector<int>{b, b + 1, b + 2, b + 3});
    soup.add_face(std::vector<int>{b + 4, b + 5, b + 6});
  }
  soup.positions.resize(long(pos.size()), 3);
  for (size_t i = 0; i < pos.size(); ++i) soup.positions.row(long(i)) = pos[i];
  const Mesh scene(std::move(soup));
  // Arrow vertices carry NaN: drawn in the missing colour, i.e. the arrow colour.
  Eigen::VectorXd s = Eigen::VectorXd::Constant(scene.n_vertices(), std::numeric_limits<double>::quiet_NaN());
  if (vertex_scalar.size() == nv) {
    s.head(nv) = vertex_scalar;
    render_options.missing_color = arrows.color;
  } else {
    s.head(nv).setZero();
    render_options.colormap = Colormap::viridis;
    render_options.colorbar = false;
    render_options.scalar_min = -1;
    render_options.scalar_max = 1;
    render_options.missing_color = arrows.color;
  }
  render_png(path, scene, s, render_options);
}

}  // namespace polydec
