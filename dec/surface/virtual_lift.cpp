// dec/surface/virtual_lift.cpp — given, sphere and local-quadric positions of the virtual vertices.
#include "polydec/dec/surface/virtual_lift.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>
#include <vector>

namespace polydec {

namespace {

// Relative cut below which a pivot of the sphere fit or the quadric fit counts as zero.
constexpr double kFitRank = 1e-10;

Eigen::Vector3d sphere_point(const Eigen::Vector3d& a, const Sphere& s, int f) {
  const Eigen::Vector3d d = a - s.center;
  const double len = d.norm();
  if (!(len > 0) || !std::isfinite(len))
    throw std::invalid_argument(
        fmt::format("sphere lift: the affine virtual point of face {} is at the sphere's center", f));
  return s.center + (s.radius / len) * d;
}

// The quadric lift of face f's affine point a (see the header).
Eigen::Vector3d quadric_point(const Mesh& mesh, int f, const Eigen::Vector3d& a, std::vector<int>& pts) {
  const auto face = mesh.face(f);
  const int n = int(face.size());
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k)
    normal += (mesh.position(face[k]) - a).cross(mesh.position(face[(k + 1) % n]) - a);
  const double area2 = normal.norm();
  if (!(area2 > 0)) return a;
  normal /= area2;
  // Tangent frame: t1 orthogonal to the normal, built from the axis least aligned with it.
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (std::abs(normal[d]) < std::abs(normal[axis])) axis = d;
  const Eigen::Vector3d t1 = normal.cross(Eigen::Vector3d::Unit(axis)).normalized(), t2 = normal.cross(t1);
  // The face's vertices and their edge neighbours (the corners before and after them in each face).
  pts.clear();
  for (int v : face)
    for (int g : mesh.vertex_faces(v)) {
      const auto corners = mesh.face(g);
      const int m = int(corners.size());
      for (int k = 0; k < m; ++k)
        if (corners[k] == v) {
          pts.push_back(v);
          pts.push_back(corners[(k + 1) % m]);
          pts.push_back(corners[(k + m - 1) % m]);
        }
    }
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  double scale = 0;
  for (int v : pts) scale = std::max(scale, (mesh.position(v) - a).norm());
  if (!(scale > 0)) return a;
  Eigen::MatrixXd A(pts.size(), 6);
  Eigen::VectorXd z(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector3d d = mesh.position(pts[i]) - a;
    const double u = d.dot(t1) / scale, v = d.dot(t2) / scale;
    A.row(long(i)) << 1, u, v, u * u, u * v, v * v;
    z[long(i)] = d.dot(normal);
  }
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
  cod.setThreshold(kFitRank);
  const Eigen::VectorXd c = cod.solve(z);
  return a + c[0] * normal;
}

}  // namespace

Sphere best_fit_sphere(const Eigen::MatrixX3d& points) {
  const long m = points.rows();
  if (m < 4) throw std::invalid_argument(fmt::format("best-fit sphere: {} points, at least 4 needed", m));
  const Eigen::RowVector3d mean = points.colwise().mean();
  const Eigen::MatrixX3d Y0 = points.rowwise() - mean;
  const double s = std::sqrt(Y0.squaredNorm() / double(m));
  if (!(s > 0) || !std::isfinite(s)) throw std::invalid_argument("best-fit sphere: the points coincide");
  const Eigen::MatrixX3d Y = Y0 / s;
  // |y|^2 = 2 <c, y> + d with d = r^2 - |c|^2, in the centred, scaled coordinates y.
  Eigen::MatrixXd A(m, 4);
  A.leftCols<3>() = 2 * Y;
  A.col(3).setOnes();
  const Eigen::VectorXd b = Y.rowwise().squaredNorm();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  qr.setThreshold(kFitRank);
  if (qr.rank() < 4) throw std::invalid_argument("best-fit sphere: the points are coplanar (no finite sphere)");
  const Eigen::VectorXd x = qr.solve(b);
  const Eigen::Vector3d c = x.head<3>();
  const double r2 = x[3] + c.squaredNorm();
  if (!(r2 > 0) || !std::isfinite(r2)) throw std::invalid_argument("best-fit sphere: no real sphere fits the points");
  Sphere out;
  out.center = mean.transpose() + s * c;
  out.radius = s * std::sqrt(r2);
  return out;
}

VirtualLift parse_virtual_lift(const std::string& spec) {
  VirtualLift lift;
  if (spec == "none") return lift;
  if (spec == "quadric") {
    lift.kind = VirtualLiftKind::Quadric;
    return lift;
  }
  if (spec == "sphere") {
    lift.kind = VirtualLiftKind::Sphere;
    return lift;
  }
  if (spec.rfind("sphere:", 0) == 0) {
    double v[4];
    size_t pos = 7;
    for (int k = 0; k < 4; ++k) {
      const size_t end = k < 3 ? spec.find(',', pos) : spec.size();
      if (end == std::string::npos) throw std::invalid_argument("virtual lift '" + spec + "': expected sphere:cx,cy,cz,r");
      const std::string item = spec.substr(pos, end - pos);
      size_t used = 0;
      try {
        v[k] = std::stod(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (item.empty() || used != item.size() || !std::isfinite(v[k]))
        throw std::invalid_argument("virtual lift '" + spec + "': '" + item + "' is not a finite number");
      pos = end + 1;
    }
    if (!(v[3] > 0)) throw std::invalid_argument("virtual lift '" + spec + "': the radius must be > 0");
    lift.kind = VirtualLiftKind::Sphere;
    lift.center = Eigen::Vector3d(v[0], v[1], v[2]);
    lift.radius = v[3];
    return lift;
  }
  throw std::invalid_argument("unknown virtual lift '" + spec + "' (none, sphere, sphere:cx,cy,cz,r, quadric)");
}

std::string to_string(const VirtualLift& lift) {
  switch (lift.kind) {
    case VirtualLiftKind::None:
      return "none";
    case VirtualLiftKind::Positions:
      return "positions";
    case VirtualLiftKind::Sphere:
      if (lift.radius > 0)
        return fmt::format("sphere:{:g},{:g},{:g},{:g}", lift.center[0], lift.center[1], lift.center[2], lift.radius);
      return "sphere";
    case VirtualLiftKind::Quadric:
      return "quadric";
  }
  return "unknown";
}

Eigen::MatrixX3d lifted_virtual_points(const Mesh& mesh, const Eigen::MatrixX3d& affine_points,
                                       const VirtualLift& lift) {
  const int nf = mesh.n_faces();
  if (affine_points.rows() != nf)
    throw std::invalid_argument(fmt::format("virtual lift: {} affine points for {} faces", affine_points.rows(), nf));
  switch (lift.kind) {
    case VirtualLiftKind::None:
      return affine_points;
    case VirtualLiftKind::Positions: {
      if (lift.positions.rows() != nf)
        throw std::invalid_argument(
            fmt::format("virtual positions: {} rows for a mesh of {} faces", lift.positions.rows(), nf));
      for (int f = 0; f < nf; ++f)
        if (!lift.positions.row(f).allFinite())
          throw std::invalid_argument(fmt::format("virtual positions: row {} (face {}) is not finite", f, f));
      return lift.positions;
    }
    case VirtualLiftKind::Sphere: {
      Sphere s;
      if (lift.radius == 0) {
        s = best_fit_sphere(mesh.positions());
      } else {
        if (!(lift.radius > 0) || !std::isfinite(lift.radius) || !lift.center.allFinite())
          throw std::invalid_argument(fmt::format("sphere lift: radius {:g} is not a positive finite number, or the "
                                                  "center is not finite",
                                                  lift.radius));
        s.center = lift.center;
        s.radius = lift.radius;
      }
      Eigen::MatrixX3d out(nf, 3);
      for (int f = 0; f < nf; ++f)
        out.row(f) = sphere_point(affine_points.row(f).transpose(), s, f).transpose();
      return out;
    }
    case VirtualLiftKind::Quadric: {
      Eigen::MatrixX3d out(nf, 3);
      std::vector<int> pts;
      for (int f = 0; f < nf; ++f)
        out.row(f) = quadric_point(mesh, f, affine_points.row(f).transpose(), pts).transpose();
      return out;
    }
  }
  return affine_points;
}

}  // namespace polydec
