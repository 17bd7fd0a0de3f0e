// tests/apps/applications/volume/test_geodesics.cpp — heat-method geodesics in volumes
// ([volume-geodesics]): HeatGeodesics on the operator sets of operators/registry/volume_laplacians.h.
// Distances in a box (convex, so geodesic = Euclidean) from a corner and from a centre vertex
// converge under refinement; the shared cubes; symmetry d(a, b) ~ d(b, a); several sources.
#include <catch2/catch.hpp>
#include <cmath>

#include "polydec/apps/applications/geodesics.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/operators/registry/volume_laplacians.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_geodesics {

namespace {

// The vertex closest to p.
int nearest_vertex(const VolumeMesh& mesh, const Eigen::Vector3d& p) {
  Eigen::Index v;
  (mesh.positions().rowwise() - p.transpose()).rowwise().squaredNorm().minCoeff(&v);
  return int(v);
}

// hex_grid_volume(2n, n, n) stretched to the box [0, 2] x [0, 1] x [0, 1] (cubic cells of side 1/n).
VolumeMesh box(int n, double jitter = 0) {
  const VolumeMesh m = hex_grid_volume(2 * n, n, n, {jitter, 5});
  Eigen::MatrixX3d X = m.positions();
  X.col(0) *= 2;
  return m.with_positions(X);
}

HeatGeodesics heat(const VolumeMesh& mesh, const std::string& method = "ours") {
  return HeatGeodesics(build_volume_operators(mesh, parse_volume_laplacian(method)), mesh.mean_edge_length());
}

// RMS of (heat distance - Euclidean distance from the source), relative to the largest Euclidean distance.
double relative_rms_error(const VolumeMesh& mesh, const Eigen::VectorXd& d, int source) {
  const Eigen::VectorXd e = (mesh.positions().rowwise() - mesh.position(source).transpose()).rowwise().norm();
  return rmse(d, e) / e.maxCoeff();
}

}  // namespace

TEST_CASE("volume heat geodesics in a box converge to the Euclidean distance", "[volume-geodesics]") {
  for (const std::string method : {"ours", "polylaplace"})
    for (const bool centre : {false, true}) {
      std::vector<double> h, err;
      for (int n : {4, 8, 16}) {
        const VolumeMesh mesh = box(n, 0.2);
        const int s = nearest_vertex(mesh, centre ? Eigen::Vector3d(1, 0.5, 0.5) : Eigen::Vector3d(0, 0, 0));
        const Eigen::VectorXd d = heat(mesh, method).distance(s);
        CHECK(d[s] == 0.0);
        CHECK(d.allFinite());
        h.push_back(mesh.mean_edge_length());
        err.push_back(relative_rms_error(mesh, d, s));
      }
      const double rate = std::log(err[2] / err[1]) / std::log(h[2] / h[1]);
      INFO(method << (centre ? ", centre" : ", corner") << ": errors " << err[0] << " " << err[1] << " "
                  << err[2] << ", last rate " << rate);
      CHECK(err[1] < err[0]);
      CHECK(err[2] < err[1]);
      CHECK(rate > 0.7);
      CHECK(err[2] < 0.02);
    }
}

TEST_CASE("volume heat geodesics: symmetry d(a, b) ~ d(b, a) relative to the diameter",
          "[volume-geodesics]") {
  const VolumeMesh mesh = box(8, 0.25);
  const HeatGeodesics g = heat(mesh);
  const int pts[4] = {nearest_vertex(mesh, {0, 0, 0}), nearest_vertex(mesh, {2, 1, 1}),
                      nearest_vertex(mesh, {0.7, 0.3, 0.6}), nearest_vertex(mesh, {1.6, 0.9, 0.1})};
  const double diameter = std::sqrt(6.0);
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const double ab = g.distance(pts[i])[pts[j]], ba = g.distance(pts[j])[pts[i]];
      INFO(i << " " << j << ": " << ab << " vs " << ba);
      // The heat method is not symmetric; its asymmetry is a discretization error of the size of the
      // distance error (measured here up to 2.1% of the diameter, h = 1/8).
      CHECK(std::abs(ab - ba) < 0.03 * diameter);
    }
}

TEST_CASE("volume heat geodesics with several sources", "[volume-geodesics]") {
  const VolumeMesh mesh = box(8);
  const HeatGeodesics g = heat(mesh);
  const int a = nearest_vertex(mesh, {0, 0, 0}), b = nearest_vertex(mesh, {2, 1, 1});
  const std::vector<int> both = {a, b};
  const Eigen::VectorXd d = g.distance(both);
  const Eigen::VectorXd da = g.distance(a), db = g.distance(b);
  // The distance to the nearer source: Euclidean min, and close to min(d_a, d_b).
  const Eigen::VectorXd ea = (mesh.positions().rowwise() - mesh.position(a).transpose()).rowwise().norm();
  const Eigen::VectorXd eb = (mesh.positions().rowwise() - mesh.position(b).transpose()).rowwise().norm();
  const Eigen::VectorXd e = ea.cwiseMin(eb);
  const double diameter = std::sqrt(6.0);
  CHECK(rmse(d, e) < 0.03 * diameter);
  CHECK(rmse(d, da.cwiseMin(db)) < 0.03 * diameter);
  CHECK(d[a] < 0.02 * diameter);
  CHECK(d[b] < 0.02 * diameter);
  // Far from the midplane each vertex sees its own source's distance.
  CHECK(d.maxCoeff() < 0.7 * da.maxCoeff());
  CHECK_THROWS_AS(g.distance(mesh.n_vertices()), std::out_of_range);
}

TEST_CASE("volume heat geodesics on the shared cubes", "[volume-geodesics]") {
  for (const std::string family : {"hexahedron", "pyramids", "truncated"}) {
    std::vector<double> err;
    for (int level : {2, 3}) {
      const std::string name = "volume/cube_" + family + "_" + std::to_string(level) + ".ovm";
      POLYDEC_SHARED_MESH(path, name);
      const VolumeMesh mesh = read_volume_mesh(path);
      const int s = nearest_vertex(mesh, {0, 0, 0});
      for (const std::string method : {"ours", "polylaplace"}) {
        const Eigen::VectorXd d = heat(mesh, method).distance(s);
        REQUIRE(d.allFinite());
        if (method == "ours") err.push_back(relative_rms_error(mesh, d, s));
      }
    }
    INFO(family << ": " << err[0] << " -> " << err[1]);
    CHECK(err[1] < err[0]);
    CHECK(err[1] < 0.05);
  }
}

}  // namespace test_volume_geodesics
