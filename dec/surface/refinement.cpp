// dec/surface/refinement.cpp — virtual vertices for every face and fan-triangle classification.
#include "polydec/dec/surface/refinement.h"

#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/detail/threads.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>
#include <vector>

namespace polydec {

PolygonPositions face_positions(const Mesh& mesh, int f) {
  const auto face = mesh.face(f);
  PolygonPositions X(face.size(), 3);
  for (size_t k = 0; k < face.size(); ++k) X.row(k) = mesh.positions().row(face[k]);
  return X;
}

namespace {

// The planarity decision of a face with the n corners x (row by row): the options' tolerance,
// else the mesh's, else the mesh's coordinate noise (`noise`, absolute) or the corners' own
// double round-off, whichever is larger.
PlanarityCut face_planarity(const Mesh& mesh, const RefinementOptions& o, double noise, const double* x, int n) {
  return planarity_cut(
      o.planarity_tolerance > 0 ? o.planarity_tolerance : mesh.precision().planarity_tolerance, noise, x, n);
}

// Classifies the n fan triangles (x_k, x_{k+1}, xf) of a face with corners x and centred corners Y
// (row by row) into fan[0..n), counting them into `count`.
void classify_fan(const double* x, const double* Y, int n, const double* xf, double tol, FanTriangle* fan,
                  FanQuality& count) {
  // Polygon vector area (twice), independent of x_f.
  double normal[3] = {0, 0, 0};
  for (int k = 0; k < n; ++k) {
    const double* p = Y + 3 * k;
    const double* q = Y + 3 * (k + 1 == n ? 0 : k + 1);
    normal[0] += p[1] * q[2] - p[2] * q[1];
    normal[1] += p[2] * q[0] - p[0] * q[2];
    normal[2] += p[0] * q[1] - p[1] * q[0];
  }
  bool affected = false;
  for (int k = 0; k < n; ++k) {
    const double* p = x + 3 * k;
    const double* q = x + 3 * (k + 1 == n ? 0 : k + 1);
    const double a[3] = {p[0] - xf[0], p[1] - xf[1], p[2] - xf[2]};
    const double b[3] = {q[0] - xf[0], q[1] - xf[1], q[2] - xf[2]};
    const double area2[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double longest2 = std::max({a[0] * a[0] + a[1] * a[1] + a[2] * a[2], b[0] * b[0] + b[1] * b[1] + b[2] * b[2],
                                      e[0] * e[0] + e[1] * e[1] + e[2] * e[2]});
    const double norm = std::sqrt(area2[0] * area2[0] + area2[1] * area2[1] + area2[2] * area2[2]);
    FanTriangle quality = FanTriangle::Valid;
    if (norm <= tol * longest2)
      quality = FanTriangle::Degenerate;
    else if (area2[0] * normal[0] + area2[1] * normal[1] + area2[2] * normal[2] < 0)
      quality = FanTriangle::Inverted;
    fan[k] = quality;
    if (quality == FanTriangle::Degenerate) ++count.n_degenerate;
    if (quality == FanTriangle::Inverted) ++count.n_inverted;
    affected = affected || quality != FanTriangle::Valid;
  }
  if (affected) ++count.n_faces_affected;
}

// Virtual vertex and fan classification of face f with N corners (0: any), written into r.
// x, Y and work are scratch of 3 * max_face_size doubles each; `noise` is the mesh's absolute
// coordinate noise (Mesh::coordinate_noise()).
template <int N>
void refine_face(const Mesh& mesh, int f, Refinement& r, FanQuality& count, double noise, double* x, double* Y,
                 double* work) {
  const int h0 = mesh.face_offsets()[f], n = N > 0 ? N : mesh.face_offsets()[f + 1] - h0;
  const int* face = mesh.face_indices().data() + h0;
  const Eigen::MatrixX3d& P = mesh.positions();
  double c[3] = {0, 0, 0};
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) {
      x[3 * k + d] = P(face[k], d);
      c[d] += x[3 * k + d];
    }
  for (int d = 0; d < 3; ++d) c[d] /= n;
  double* w = r.weights.data() + h0;
  const PlanarityCut planarity = face_planarity(mesh, r.options, noise, x, n);
  if (r.options.rule == VirtualVertexRule::SquaredArea) {
    squared_area_weights(x, n, w, work, planarity);
  } else if (r.options.rule == VirtualVertexRule::Centroid) {
    for (int k = 0; k < n; ++k) w[k] = 1.0 / n;
  } else {  // the other rules (dec/surface/virtual_vertex.h) through their general routes
    const Eigen::VectorXd wr = virtual_vertex_weights(face_positions(mesh, f), r.options.rule, planarity);
    for (int k = 0; k < n; ++k) w[k] = wr[k];
  }
  // x_f = c + sum_k w_k (x_k - c): centred, so that far from the origin no digits are lost.
  double s[3] = {0, 0, 0};
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) {
      Y[3 * k + d] = x[3 * k + d] - c[d];
      s[d] += w[k] * Y[3 * k + d];
    }
  const double xf[3] = {c[0] + s[0], c[1] + s[1], c[2] + s[2]};
  for (int d = 0; d < 3; ++d) r.virtual_points(f, d) = xf[d];
  classify_fan(x, Y, n, xf, r.options.degenerate_tolerance, r.fan.data() + h0, count);
}

// Moves the virtual points of r to their lift (r.options.lift) and classifies the fans anew.
void lift_virtual_points(const Mesh& mesh, Refinement& r) {
  r.virtual_points = lifted_virtual_points(mesh, r.virtual_points, r.options.lift);
  r.quality = FanQuality();
  std::vector<double> x(3 * size_t(mesh.max_face_size())), Y(x.size());
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size());
    double c[3] = {0, 0, 0};
    for (int k = 0; k < n; ++k)
      for (int d = 0; d < 3; ++d) {
        x[3 * k + d] = mesh.positions()(face[k], d);
        c[d] += x[3 * k + d];
      }
    for (int k = 0; k < n; ++k)
      for (int d = 0; d < 3; ++d) Y[3 * k + d] = x[3 * k + d] - c[d] / n;
    const double xf[3] = {r.virtual_points(f, 0), r.virtual_points(f, 1), r.virtual_points(f, 2)};
    classify_fan(x.data(), Y.data(), n, xf, r.options.degenerate_tolerance, r.fan.data() + mesh.face_offsets()[f],
                 r.quality);
  }
}

}  // namespace

Refinement refine(const Mesh& mesh, const RefinementOptions& options) {
  if (!(options.planarity_tolerance >= 0 && options.planarity_tolerance < 1))
    throw std::invalid_argument(fmt::format("planarity tolerance {:g} outside [0, 1)", options.planarity_tolerance));
  Refinement r;
  r.options = options;
  // Large outputs on huge pages where available (first-touch faults dominate otherwise).
  assign_on_huge_pages(r.weights, size_t(mesh.n_halfedges()));
  r.virtual_points.resize(mesh.n_faces(), 3);
  advise_huge_pages(r.virtual_points.data(), sizeof(double) * 3 * mesh.n_faces());
  assign_on_huge_pages(r.fan, size_t(mesh.n_halfedges()), FanTriangle::Valid);
  // Faces are independent: T threads take contiguous face ranges, each with its own scratch
  // (sized once for the largest face: corner positions, centred positions, the weights' work
  // space; no allocation per face) and its own counts, summed at the end.
  const int nf = mesh.n_faces(), nmax = mesh.max_face_size();
  const int T = std::min(resolve_threads(options.threads), std::max(1, nf / 4096));  // >= 4096 faces per thread
  std::vector<FanQuality> counts(T);
  const double noise = mesh.precision().noise > 0 ? mesh.coordinate_noise() : 0.0;
  auto work = [&](int t) {
    std::vector<double> buffer(9 * size_t(nmax));
    double* x = buffer.data();
    double* Y = x + 3 * nmax;
    double* scratch = Y + 3 * nmax;
    const int* offsets = mesh.face_offsets().data();
    const auto [f0, f1] = part_of(nf, t, T);
    for (int f = int(f0); f < int(f1); ++f) {
      switch (offsets[f + 1] - offsets[f]) {
        case 3: refine_face<3>(mesh, f, r, counts[t], noise, x, Y, scratch); break;
        case 4: refine_face<4>(mesh, f, r, counts[t], noise, x, Y, scratch); break;
        case 5: refine_face<5>(mesh, f, r, counts[t], noise, x, Y, scratch); break;
        case 6: refine_face<6>(mesh, f, r, counts[t], noise, x, Y, scratch); break;
        default: refine_face<0>(mesh, f, r, counts[t], noise, x, Y, scratch); break;
      }
    }
  };
  run_on_threads(T, work);
  for (const FanQuality& c : counts) {
    r.quality.n_degenerate += c.n_degenerate;
    r.quality.n_inverted += c.n_inverted;
    r.quality.n_faces_affected += c.n_faces_affected;
  }
  if (options.lift.kind != VirtualLiftKind::None) lift_virtual_points(mesh, r);
  return r;
}

Refinement refine(const Mesh& mesh, const Refinement& previous) { return refine(mesh, previous.options); }

Mesh refined_mesh(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "refined_mesh");
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
