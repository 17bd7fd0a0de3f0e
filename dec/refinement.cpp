// dec/refinement.cpp — virtual vertices for every face and fan-triangle classification.
#include "dec/refinement.h"

namespace polydec {

PolygonPositions face_positions(const Mesh& mesh, int f) {
  const auto face = mesh.face(f);
  PolygonPositions X(face.size(), 3);
  for (size_t k = 0; k < face.size(); ++k) X.row(k) = mesh.positions().row(face[k]);
  return X;
}

Refinement refine(const Mesh& mesh, const RefinementOptions& options) {
  Refinement r;
  r.options = options;
  r.weights.resize(mesh.n_halfedges());
  r.virtual_points.resize(mesh.n_faces(), 3);
  r.fan.assign(mesh.n_halfedges(), FanTriangle::Valid);
  const double tol = options.degenerate_tolerance;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const PolygonPositions X = face_positions(mesh, f);
    const Eigen::VectorXd w = virtual_vertex_weights(X, options.rule);
    const int n = int(X.rows()), h0 = mesh.face_offsets()[f];
    for (int k = 0; k < n; ++k) r.weights[h0 + k] = w[k];
    // x_f = c + sum_k w_k (x_k - c): centred, so that far from the origin no digits are lost.
    const Eigen::RowVector3d c = X.colwise().mean();
    const Eigen::RowVector3d xf = c + w.transpose() * (X.rowwise() - c);
    r.virtual_points.row(f) = xf;

    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // polygon vector area (twice), independent of x_f
    for (int k = 0; k < n; ++k)
      normal += (X.row(k) - c).cross(X.row((k + 1) % n) - c).transpose();
    bool affected = false;
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d a = (X.row(k) - xf).transpose(), b = (X.row((k + 1) % n) - xf).transpose();
      const Eigen::Vector3d area2 = a.cross(b);
      const double longest2 = std::max({a.squaredNorm(), b.squaredNorm(), (b - a).squaredNorm()});
      FanTriangle q = FanTriangle::Valid;
      if (area2.norm() <= tol * longest2)
        q = FanTriangle::Degenerate;
      else if (area2.dot(normal) < 0)
        q = FanTriangle::Inverted;
      r.fan[h0 + k] = q;
      if (q == FanTriangle::Degenerate) ++r.quality.n_degenerate;
      if (q == FanTriangle::Inverted) ++r.quality.n_inverted;
      affected = affected || q != FanTriangle::Valid;
    }
    if (affected) ++r.quality.n_faces_affected;
  }
  return r;
}

Refinement refine(const Mesh& mesh, const Refinement& previous) { return refine(mesh, previous.options); }

Mesh refined_mesh(const Mesh& mesh, const Refinement& refinement) {
  const int nv = mesh.n_vertices(), nf = mesh.n_faces();
  PolygonSoup soup;
  soup.positions.resize(nv + nf, 3);
  soup.positions.topRows(nv) = mesh.positions();
  soup.positions.bottomRows(nf) = refinement.virtual_points;
  soup.face_indices.reserve(3 * mesh.n_halfedges());
  soup.face_offsets.reserve(mesh.n_halfedges() + 1);
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    const int tri[3] = {mesh.halfedge_source(h), mesh.halfedge_target(h), nv + mesh.halfedge_face(h)};
    soup.add_face(tri);
  }
  return Mesh(std::move(soup));
}

}  // namespace polydec
