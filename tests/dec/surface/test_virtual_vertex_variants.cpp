// tests/dec/surface/test_virtual_vertex_variants.cpp — the virtual-vertex variants of section 4.2 / 5.7
// (abs-area, convex) and the trace minimizer of Bunge et al. 2024 (trace-min), per polygon and on
// the non-star-shaped polygons of tetris.obj.
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/surface/refinement.h"
#include "polydec/dec/surface/virtual_vertex.h"
#include "tests/support/support.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <random>

using namespace polydec;

namespace test_virtual_vertex_variants {

namespace {

Eigen::Vector3d point(const PolygonPositions& X, const Eigen::VectorXd& w) { return X.transpose() * w; }

double abs_area(const PolygonPositions& X, const Eigen::Vector3d& x) {
  double s = 0;
  for (int k = 0; k < X.rows(); ++k)
    s += 0.5 * (X.row(k).transpose() - x).cross(X.row((k + 1) % X.rows()).transpose() - x).norm();
  return s;
}

double squared_area(const PolygonPositions& X, const Eigen::Vector3d& x) {
  double s = 0;
  for (int k = 0; k < X.rows(); ++k)
    s += 0.25 * (X.row(k).transpose() - x).cross(X.row((k + 1) % X.rows()).transpose() - x).squaredNorm();
  return s;
}

// Refined fan trace sum of cot-sums around a planar point (z = 0), +inf if a fan triangle is not
// counter-clockwise.
double fan_trace(const PolygonPositions& X, const Eigen::Vector3d& p) {
  double s = 0;
  for (int k = 0; k < X.rows(); ++k) {
    const Eigen::Vector3d a = X.row(k).transpose() - p, b = X.row((k + 1) % X.rows()).transpose() - p;
    const double A = 0.5 * a.cross(b).z();
    if (A <= 0) return INFINITY;
    s += (a.squaredNorm() + b.squaredNorm() + (b - a).squaredNorm()) / (4 * A);
  }
  return s;
}

PolygonPositions regular(int n, double r = 1.0) {
  PolygonPositions X(n, 3);
  for (int k = 0; k < n; ++k) X.row(k) << r * std::cos(2 * M_PI * k / n), r * std::sin(2 * M_PI * k / n), 0.0;
  return X;
}

// A thin L-shaped hexagon (counter-clockwise) whose vertex centroid (1.5, 1.5) lies outside it;
// its kernel is the corner square [0, 0.5]^2.
PolygonPositions thin_l() {
  PolygonPositions X(6, 3);
  X << 0, 0, 0, 4, 0, 0, 4, 0.5, 0, 0.5, 0.5, 0, 0.5, 4, 0, 0, 4, 0;
  return X;
}

// A spiral-like non-star-shaped polygon (no point sees every edge): a "C" with thin arms.
PolygonPositions c_shape() {
  PolygonPositions X(8, 3);
  X << 0, 0, 0, 3, 0, 0, 3, 0.4, 0, 0.4, 0.4, 0, 0.4, 2.6, 0, 3, 2.6, 0, 3, 3, 0, 0, 3, 0;
  return X;
}

const VirtualVertexRule kVariants[] = {VirtualVertexRule::AbsArea, VirtualVertexRule::Convex,
                                       VirtualVertexRule::TraceMin};

}  // namespace

TEST_CASE("virtual-vertex variants: affine weights, symmetry, invariance", "[compare][virtual_vertex]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  for (auto rule : kVariants) {
    INFO(to_string(rule));
    CHECK(parse_virtual_vertex_rule(to_string(rule)) == rule);
    // A regular polygon: by symmetry every variant puts the virtual vertex at the centre with
    // uniform weights.
    for (int n : {3, 5, 8}) {
      const Eigen::VectorXd w = virtual_vertex_weights(regular(n), rule);
      CHECK((w - Eigen::VectorXd::Constant(n, 1.0 / n)).cwiseAbs().maxCoeff() < 1e-7);
    }
    // Random (planar and non-planar) polygons: weights sum to 1, are finite, and do not depend
    // on the polygon's position or scale.
    for (int trial = 0; trial < 10; ++trial) {
      const int n = 4 + trial % 5;
      PolygonPositions X = regular(n);
      for (int k = 0; k < n; ++k) X.row(k) += Eigen::RowVector3d(u(rng), u(rng), trial % 2 ? u(rng) : 0.0);
      const Eigen::VectorXd w = virtual_vertex_weights(X, rule);
      REQUIRE(w.allFinite());
      CHECK(w.sum() == Approx(1.0).epsilon(1e-12));
      for (double s : {1e-8, 1e8}) {
        const PolygonPositions Y = (s * X).rowwise() + Eigen::RowVector3d(3 * s, -2 * s, 5 * s);
        const Eigen::VectorXd ws = virtual_vertex_weights(Y, rule);
        CHECK((ws - w).cwiseAbs().maxCoeff() < 1e-6);
      }
    }
  }
}

TEST_CASE("abs-area: never worse than the centroid and the squared-area point, inside an L", "[compare][virtual_vertex]") {
  const PolygonPositions X = thin_l();
  const double polygon_area = 4 * 0.5 + 0.5 * 3.5;
  const Eigen::Vector3d c = X.colwise().mean().transpose();
  REQUIRE(abs_area(X, c) > polygon_area * 1.01);  // the centroid lies outside: the fan overlaps itself
  const Eigen::Vector3d x = point(X, abs_area_weights(X));
  // The minimum of the sum of absolute fan areas is the polygon's area, reached at every kernel point.
  CHECK(abs_area(X, x) == Approx(polygon_area).epsilon(1e-9));
  // Random polygons: the iteration only descends.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (int trial = 0; trial < 20; ++trial) {
    PolygonPositions Y = regular(6);
    for (int k = 0; k < 6; ++k) Y.row(k) += Eigen::RowVector3d(u(rng), u(rng), trial % 2 ? u(rng) : 0.0);
    const Eigen::Vector3d y = point(Y, abs_area_weights(Y));
    CHECK(abs_area(Y, y) <= abs_area(Y, Y.colwise().mean().transpose()) * (1 + 1e-12));
    // Brute force: no point of a fine grid around the polygon does better by more than the grid's resolution.
    double best = INFINITY;
    for (int i = -40; i <= 40; ++i)
      for (int j = -40; j <= 40; ++j) best = std::min(best, abs_area(Y, Eigen::Vector3d(i * 0.04, j * 0.04, y.z())));
    CHECK(abs_area(Y, y) <= best + 1e-2);
  }
}

TEST_CASE("convex: non-negative weights, optimal over the simplex, equal to affine when those are convex",
          "[compare][virtual_vertex]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  std::exponential_distribution<double> ex(1.0);
  for (const PolygonPositions& X : {thin_l(), c_shape()}) {
    const Eigen::VectorXd w = convex_weights(X);
    CHECK(w.minCoeff() >= 0);
    CHECK(w.sum() == Approx(1.0));
    // Optimality against random points of the simplex (the objective is the squared fan area).
    const double e = squared_area(X, point(X, w));
    for (int trial = 0; trial < 2000; ++trial) {
      Eigen::VectorXd v(X.rows());
      for (int k = 0; k < v.size(); ++k) v[k] = ex(rng);
      v /= v.sum();
      CHECK(e <= squared_area(X, point(X, v)) * (1 + 1e-7));
    }
    // The affine minimizer of thin_l / c_shape has a negative weight, so convex is strictly worse
    // than affine there, and never better.
    CHECK(squared_area(X, point(X, squared_area_weights(X))) <= e * (1 + 1e-12));
  }
  // Slightly irregular convex polygons: the affine least-norm weights are positive, so the convex
  // solution is the same point (ties broken towards least norm).
  for (int trial = 0; trial < 10; ++trial) {
    PolygonPositions X = regular(5 + trial % 3);
    for (int k = 0; k < X.rows(); ++k) X.row(k) += Eigen::RowVector3d(0.3 * u(rng), 0.3 * u(rng), 0);
    const Eigen::VectorXd wa = squared_area_weights(X);
    REQUIRE(wa.minCoeff() > 0);
    CHECK((convex_weights(X) - wa).cwiseAbs().maxCoeff() < 1e-6);
  }
}

TEST_CASE("trace-min: minimizes the fan trace in the kernel, harmonic weights reproduce the point",
          "[compare][virtual_vertex]") {
  const PolygonPositions X = thin_l();  // star-shaped (kernel: the corner square)
  const Eigen::VectorXd w = trace_min_weights(X);
  const Eigen::Vector3d p = point(X, w);
  const double t = fan_trace(X, p);
  REQUIRE(std::isfinite(t));  // all fan triangles counter-clockwise
  // Brute force over a grid of the bounding box.
  for (int i = 0; i <= 80; ++i)
    for (int j = 0; j <= 80; ++j) CHECK(t <= fan_trace(X, Eigen::Vector3d(i * 0.05, j * 0.05, 0)) * (1 + 1e-9));
  // The squared-area point is a worse (or invalid) choice by the same measure.
  CHECK(t <= fan_trace(X, point(X, squared_area_weights(X))));
  // The coarsened trace criterion of the fallback prefers the result.
  CHECK(coarse_stiffness_trace(X, w) <= coarse_stiffness_trace(X, squared_area_weights(X)));
  // A polygon without kernel falls back to the squared-area weights.
  const PolygonPositions C = c_shape();
  CHECK((trace_min_weights(C) - squared_area_weights(C)).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("coarse_stiffness_trace equals the trace of P^T S^f P", "[compare][virtual_vertex]") {
  // Independent route: assemble the (n+1) x (n+1) fan cotangent matrix and coarsen it densely.
  const PolygonPositions X = thin_l();
  const int n = int(X.rows());
  const Eigen::VectorXd w = squared_area_weights(X);
  const Eigen::Vector3d xf = point(X, w);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + 1, n + 1);
  for (int k = 0; k < n; ++k) {
    const int idx[3] = {k, (k + 1) % n, n};
    const Eigen::Vector3d p[3] = {X.row(k).transpose(), X.row((k + 1) % n).transpose(), xf};
    const double A2 = (p[1] - p[0]).cross(p[2] - p[0]).norm();
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      const double cot = (p[b] - p[a]).dot(p[c] - p[a]) / A2;  // angle at a, opposite edge (b, c)
      K(idx[b], idx[c]) -= cot / 2;
      K(idx[c], idx[b]) -= cot / 2;
      K(idx[b], idx[b]) += cot / 2;
      K(idx[c], idx[c]) += cot / 2;
    }
  }
  Eigen::MatrixXd P(n + 1, n);
  P.topRows(n).setIdentity();
  P.row(n) = w.transpose();
  CHECK(coarse_stiffness_trace(X, w) == Approx((P.transpose() * K * P).trace()).epsilon(1e-12));
}

TEST_CASE("fan quality of each variant on tetris.obj (non-star-shaped polygons)", "[compare][virtual_vertex]") {
  POLYDEC_SHARED_MESH(path, "tetris.obj");
  const Mesh mesh = read_mesh(path);
  auto quality = [&](VirtualVertexRule rule) {
    RefinementOptions o;
    o.rule = rule;
    return refine(mesh, o).quality;
  };
  const FanQuality ours = quality(VirtualVertexRule::SquaredArea), centroid = quality(VirtualVertexRule::Centroid),
                   abs = quality(VirtualVertexRule::AbsArea), convex = quality(VirtualVertexRule::Convex),
                   trace = quality(VirtualVertexRule::TraceMin);
  CHECK(ours.n_inverted >= 1);  // tetris.obj's non-star-shaped faces invert a fan triangle
  // Abs-area (measured on this mesh): the L1 objective moves the point onto edge lines, trading
  // every inverted triangle for degenerate ones.
  CHECK(abs.n_inverted == 0);
  CHECK(abs.n_degenerate > ours.n_degenerate);
  // The trace minimizer sits strictly inside the kernel where there is one and falls back to
  // ours elsewhere: never more inverted or degenerate triangles than ours.
  CHECK(trace.n_inverted <= ours.n_inverted);
  CHECK(trace.n_degenerate <= ours.n_degenerate);
  // The centroid of a non-convex polygon is often outside it.
  CHECK(centroid.n_inverted > ours.n_inverted);
  CHECK(convex.n_inverted + convex.n_degenerate >= 1);  // no convex combination sees every edge either
}

}  // namespace test_virtual_vertex_variants
