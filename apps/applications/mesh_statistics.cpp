// apps/applications/mesh_statistics.cpp — counts, topology, planarity and convexity of a mesh.
#include "polydec/apps/applications/mesh_statistics.h"

#include <Eigen/Dense>

namespace polydec {

MeshStatistics mesh_statistics(const Mesh& mesh) {
  MeshStatistics s;
  s.vertices = mesh.n_vertices();
  s.faces = mesh.n_faces();
  s.edges = mesh.n_edges();
  s.halfedges = mesh.n_halfedges();
  s.boundary_edges = mesh.n_boundary_edges();
  s.unreferenced_vertices = mesh.n_unreferenced_vertices();
  s.components = mesh.n_components();
  for (const auto& loop : mesh.boundary_loops()) s.boundary_loop_lengths.push_back(int(loop.size()));
  for (int f = 0; f < mesh.n_faces(); ++f) ++s.valence_histogram[mesh.face_size(f)];
  // Unreferenced vertices are not part of the surface: leave them out of chi for the genus.
  s.euler_characteristic = mesh.euler_characteristic();
  const int chi_surface = s.euler_characteristic - s.unreferenced_vertices;
  s.genus = (2 * s.components - int(s.boundary_loop_lengths.size()) - chi_surface) / 2;
  s.mean_edge_length = mesh.mean_edge_length();
  s.bounding_box_diagonal = mesh.bounding_box_diagonal();

  double sum = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const PolygonPositions X = face_positions(mesh, f);
    const int n = int(X.rows());
    const Eigen::RowVector3d c = X.colwise().mean();
    const PolygonPositions Y = X.rowwise() - c;
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(Y), Eigen::ComputeThinV);
    const Eigen::Vector3d normal = svd.matrixV().col(2);
    double diameter = 0;
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b) diameter = std::max(diameter, (X.row(a) - X.row(b)).norm());
    const double dev = diameter > 0 ? (Y * normal).cwiseAbs().maxCoeff() / diameter : 0.0;
    s.max_nonplanarity = std::max(s.max_nonplanarity, dev);
    sum += dev;
    if (dev > s.planarity_tolerance) ++s.nonplanar_faces;
    // Convexity in the plane: all turns have the sign of the polygon's orientation.
    Eigen::Vector3d area = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k) area += Y.row(k).transpose().cross(Y.row((k + 1) % n).transpose());
    bool convex = true;
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d e0 = (X.row((k + 1) % n) - X.row(k)).transpose();
      const Eigen::Vector3d e1 = (X.row((k + 2) % n) - X.row((k + 1) % n)).transpose();
      if (e0.cross(e1).dot(area) < 0) convex = false;
    }
    (convex ? s.convex_faces : s.nonconvex_faces)++;
  }
  s.mean_nonplanarity = mesh.n_faces() ? sum / mesh.n_faces() : 0.0;
  s.fan = refine(mesh).quality;
  return s;
}

}  // namespace polydec
