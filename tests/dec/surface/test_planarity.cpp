// tests/dec/surface/test_planarity.cpp — the planarity decision of the virtual-vertex weights (eq. 16, 38):
// readers record the precision the file's digits carry, the weights of nearly planar polygons
// agree with a quadruple-precision evaluation of the paper's definition, and the file's digits
// or the user's tolerance decide which polygons count as planar.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <random>
#include <string>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/surface/refinement.h"
#include "polydec/dec/surface/virtual_vertex.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_planarity {

__extension__ typedef __float128 Quad;

// Solves the 3x3 system M z = r by Gaussian elimination with partial pivoting in Quad.
void solve3(Quad M[3][3], Quad r[3], Quad z[3]) {
  for (int c = 0; c < 3; ++c) {
    int p = c;
    for (int i = c + 1; i < 3; ++i)
      if ((M[i][c] < 0 ? -M[i][c] : M[i][c]) > (M[p][c] < 0 ? -M[p][c] : M[p][c])) p = i;
    for (int j = 0; j < 3; ++j) std::swap(M[c][j], M[p][j]);
    std::swap(r[c], r[p]);
    for (int i = c + 1; i < 3; ++i) {
      const Quad f = M[i][c] / M[c][c];
      for (int j = c; j < 3; ++j) M[i][j] -= f * M[c][j];
      r[i] -= f * r[c];
    }
  }
  for (int i = 2; i >= 0; --i) {
    Quad s = r[i];
    for (int j = i + 1; j < 3; ++j) s -= M[i][j] * z[j];
    z[i] = s / M[i][i];
  }
}

// The paper's weights of a non-planar polygon in quadruple precision, an independent route: the
// squared-area point y from the normal equations of eq. (38) (A y = b), then the unique affine
// weights w = 1/n + Y (Y^T Y)^-1 y of the centred corners Y (full rank: no least-norm choice).
// With Quad's 113-bit significand, the normal equations' condition (out-of-plane extent)^-2
// costs at most 1e-20 of 1e-34 for the polygons below.
Eigen::VectorXd quad_weights(const PolygonPositions& X) {
  const int n = int(X.rows());
  std::vector<Quad> Y(3 * n);
  Quad c[3] = {0, 0, 0};
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) c[d] += Quad(X(k, d));
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) Y[3 * k + d] = Quad(X(k, d)) - c[d] / n;
  Quad A[3][3] = {}, b[3] = {}, y[3];
  for (int k = 0; k < n; ++k) {
    const Quad* p = &Y[3 * k];
    const Quad* q = &Y[3 * ((k + 1) % n)];
    const Quad e[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const Quad ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2], ep = e[0] * p[0] + e[1] * p[1] + e[2] * p[2];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) A[i][j] += (i == j ? ee : Quad(0)) - e[i] * e[j];
      b[i] += ee * p[i] - e[i] * ep;
    }
  }
  solve3(A, b, y);
  Quad G[3][3] = {}, z[3];
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) G[i][j] += Y[3 * k + i] * Y[3 * k + j];
  solve3(G, y, z);
  Eigen::VectorXd w(n);
  for (int k = 0; k < n; ++k)
    w[k] = double(Quad(1) / n + Y[3 * k] * z[0] + Y[3 * k + 1] * z[1] + Y[3 * k + 2] * z[2]);
  return w;
}

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

// A convex n-gon of size ~1 in the plane z = 0 with its corners lifted alternately by +-h
// (out-of-plane extent ~h), rotated and moved by `offset`.
PolygonPositions nearly_planar(std::mt19937& rng, int n, double h, double offset) {
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  PolygonPositions X(n, 3);
  for (int k = 0; k < n; ++k) {
    const double t = 2 * M_PI * (k + u(rng)) / n;
    X.row(k) << std::cos(t) * (1 + u(rng)), std::sin(t) * (1 + u(rng)), (k % 2 ? h : -h) * (1 + u(rng));
  }
  const Eigen::Matrix3d R = random_rotation(rng);
  return ((X * R.transpose()).rowwise() + Eigen::RowVector3d::Constant(offset)).eval();
}

std::string off_text(const PolygonPositions& X, const char* number_format) {
  std::string s = fmt::format("OFF\n{} 1 0\n", X.rows());
  for (int k = 0; k < X.rows(); ++k)
    for (int d = 0; d < 3; ++d) {
      s += fmt::format(fmt::runtime(number_format), X(k, d));
      s.push_back(d == 2 ? '\n' : ' ');
    }
  s += std::to_string(X.rows());
  for (int k = 0; k < X.rows(); ++k) {
    s += ' ';
    s += std::to_string(k);
  }
  return s + "\n";
}

TEST_CASE("readers record the precision the coordinates' digits carry", "[planarity][io]") {
  const std::string faces = "3 0 1 2\n";
  auto off = [&](const std::string& v) {
    return read_mesh_from_memory("OFF\n3 1 0\n" + v + faces, "off", "t.off");
  };
  // Six decimals (0.5e-6), up to 7 significant digits (half a unit of the 7th digit of 2.5: 0.5e-6).
  const Mesh fixed = off("1.250000 0.000001 0.5\n-1.000000 2.500000 0.000000\n0.125000 0.250000 1.000000\n");
  CHECK(fixed.coordinate_noise() == Approx(0.5e-6));
  // Five significant digits with exponents (%g): half a unit of the 5th digit of 3.0000, 0.5e-4.
  const Mesh sig = off("1.2346e-05 0.5 1.5\n-1.2346 2.5 3\n0.12346 0.25 1\n");
  CHECK(sig.coordinate_noise() == Approx(0.5e-4));
  // 17 significant digits or integers only: the doubles themselves (noise 0, round-off only).
  const Mesh full = off("0.19509001691134054 -6.974846764313593e-8 -0.9807853410922113\n1 0 0\n0 1 0\n");
  CHECK(full.precision() == CoordinatePrecision{});
  CHECK(off("0 0 0\n1 0 0\n0 1 1\n").precision() == CoordinatePrecision{});
  // OBJ and PLY read the same way.
  const Mesh obj = read_mesh_from_memory("v 0.100 0 0\nv 1.000 0 0\nv 0 1.000 0\nf 1 2 3\n", "obj", "t.obj");
  CHECK(obj.coordinate_noise() == Approx(0.5e-3));  // 3 decimals; 4 digits of 1.000
  const std::string ply_header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const Mesh ply =
      read_mesh_from_memory(ply_header + "0.25 0 0\n1.75 0 0\n0 1.5 0\n3 0 1 2\n", "ply", "t.ply");
  CHECK(ply.coordinate_noise() == Approx(0.5e-2));  // 2 decimals; 3 digits of 1.75
  // The precision is relative to the mesh's size: it moves and scales with the positions.
  const Mesh doubled = fixed.with_positions(fixed.positions() * 2);
  CHECK(doubled.precision() == fixed.precision());
  CHECK(doubled.coordinate_noise() == Approx(2 * fixed.coordinate_noise()));
}

TEST_CASE("weights of nearly planar polygons agree with quadruple precision", "[planarity][numerics]") {
  std::mt19937 rng(14);
  double worst = 0;
  int n_tested = 0;
  for (double h : {1e-2, 1e-4, 1e-6, 1e-7, 4.5e-9, 1e-9, 1e-10})
    for (double offset : {0.0, 3.0})
      for (int trial = 0; trial < 20; ++trial) {
        const int n = 4 + trial % 4;
        const PolygonPositions X = nearly_planar(rng, n, h, offset);
        const Eigen::VectorXd w = squared_area_weights(X), exact = quad_weights(X);
        const double e = (w - exact).cwiseAbs().maxCoeff();
        INFO("h " << h << " offset " << offset << " n " << n << " error " << e);
        CHECK(e <= 1e-6);
        // The same face inside a mesh read from 17-digit text (bit-exact doubles).
        if (trial == 0) {
          const Mesh m = read_mesh_from_memory(off_text(X, "{:.17g}"), "off", "q.off");
          const Refinement r = refine(m);
          for (int k = 0; k < n; ++k) CHECK(std::abs(r.weights[k] - exact[k]) <= 1e-6);
        }
        worst = std::max(worst, e);
        ++n_tested;
      }
  CHECK(n_tested == 280);
  INFO("worst weight error " << worst);
  CHECK(worst <= 1e-6);
}

TEST_CASE("the file's digits and the user's tolerance decide planarity", "[planarity]") {
  std::mt19937 rng(15);
  const PolygonPositions X = nearly_planar(rng, 4, 1e-8, 0.0);
  // Written with 17 digits the quad is resolved as non-planar: the paper's unique weights.
  const Mesh exact_file = read_mesh_from_memory(off_text(X, "{:.17g}"), "off", "q17.off");
  const Eigen::VectorXd exact = quad_weights(X);
  const Refinement r17 = refine(exact_file);
  // Written with 6 decimals the digits cannot tell a 1e-8 lift from rounding: planar, least-norm
  // weights, the same as with the user's tolerance (or the fixed 1e-5 of earlier versions).
  const Mesh six = read_mesh_from_memory(off_text(X, "{:.6f}"), "off", "q6.off");
  const Refinement r6 = refine(six);
  RefinementOptions old;
  old.planarity_tolerance = 1e-5;
  const Refinement r6_old = refine(six, old);
  const Refinement r17_old = refine(exact_file, old);
  CoordinatePrecision user = exact_file.precision();
  user.planarity_tolerance = 1e-5;
  const Refinement r17_user = refine(exact_file.with_precision(user));
  double d_exact = 0, d_six = 0, d_user = 0, jump = 0;
  for (int k = 0; k < 4; ++k) {
    d_exact = std::max(d_exact, std::abs(r17.weights[k] - exact[k]));
    d_six = std::max(d_six, std::abs(r6.weights[k] - r6_old.weights[k]));
    d_user = std::max(d_user, std::abs(r17_user.weights[k] - r17_old.weights[k]));
    jump = std::max(jump, std::abs(r17.weights[k] - r17_old.weights[k]));
  }
  CHECK(d_exact <= 1e-6);
  CHECK(d_six == 0.0);
  CHECK(d_user == 0.0);
  // The planar and the non-planar weights differ by far more than the data's noise: the decision matters.
  CHECK(jump >= 1e-3);
  // Virtual points agree either way (the jump is in the weights only).
  CHECK((r17.virtual_points - r17_old.virtual_points).norm() <= 1e-6);
  RefinementOptions bad;
  bad.planarity_tolerance = -1;
  CHECK_THROWS_AS(refine(six, bad), std::invalid_argument);
  CoordinatePrecision nan_precision;
  nan_precision.noise = std::nan("");
  CHECK_THROWS_AS(six.with_precision(nan_precision), InvalidMeshError);
}

}  // namespace test_planarity
