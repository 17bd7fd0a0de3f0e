// tests/apps/applications/test_curvature.cpp — mean curvature (eq. 29): the paper's Table 2 on the unit-sphere
// meshes, scale covariance, orientation independence, vertex normals.
#include <cmath>

#include "polydec/apps/applications/curvature.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "tests/support/paper_spheres.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_curvature {

namespace {

Mesh unit_sphere_mesh(const std::string& path) { return project_to_unit_sphere(read_mesh(path)); }

double rmse_on(const Mesh& mesh, bool lumped) {
  CurvatureOptions o;
  o.lumped_mass = lumped;
  return curvature_rmse(mean_curvature(mesh, o), 1.0);
}

// Same vertices, every face reversed.
Mesh reversed(const Mesh& m) {
  PolygonSoup s;
  s.positions = m.positions();
  s.precision = m.precision();  // the same data
  for (int f = 0; f < m.n_faces(); ++f) {
    std::vector<int> face(m.face(f).begin(), m.face(f).end());
    std::reverse(face.begin(), face.end());
    s.add_face(face);
  }
  return Mesh(std::move(s));
}

}  // namespace

// Reference values: the authors' program (Table 2), positions in double; tolerance 1% relative.
TEST_CASE("curvature: Table 2 RMSE on REGULAR and NOISY SPHERE, lumped and unlumped", "[apps]") {
  POLYDEC_SHARED_MESH(regular_path, "quad-sphere.off");
  POLYDEC_SHARED_MESH(noisy_path, "noisy-sphere.off");
  const Mesh regular = unit_sphere_mesh(regular_path), noisy = unit_sphere_mesh(noisy_path);
  CHECK(rmse_on(regular, true) == Approx(0.016770).epsilon(0.01));
  CHECK(rmse_on(noisy, true) == Approx(0.046895).epsilon(0.01));
  CHECK(rmse_on(regular, false) == Approx(0.051469).epsilon(0.01));
  CHECK(rmse_on(noisy, false) == Approx(0.15186).epsilon(0.01));
}

TEST_CASE("curvature: H scales as 1/length and ignores the face orientation", "[apps]") {
  POLYDEC_SHARED_MESH(path, "noisy-sphere.off");
  const Mesh sphere = unit_sphere_mesh(path);
  const Eigen::VectorXd H = mean_curvature(sphere);
  CHECK(H.minCoeff() > 0);  // convex closed surface, outward normals: positive everywhere
  for (double s : {1e-6, 1e6}) {
    const Eigen::VectorXd Hs = mean_curvature(sphere.with_positions(s * sphere.positions()));
    CHECK((s * Hs - H).cwiseAbs().maxCoeff() <= 1e-9 * H.cwiseAbs().maxCoeff());
  }
  // noisy-sphere.off is oriented inwards; reversing the faces must not change H.
  const Eigen::VectorXd Hr = mean_curvature(reversed(sphere));
  CHECK((Hr - H).cwiseAbs().maxCoeff() <= 1e-12 * H.cwiseAbs().maxCoeff());
  CHECK(signed_volume(sphere) * signed_volume(reversed(sphere)) < 0);
}

TEST_CASE("curvature: vertex normals of a unit sphere point along the position", "[apps]") {
  POLYDEC_SHARED_MESH(path, "quad-sphere.off");
  const Mesh sphere = unit_sphere_mesh(path);
  const Eigen::MatrixX3d N = vertex_normals(sphere);
  const double sign = signed_volume(sphere) > 0 ? 1.0 : -1.0;
  const double h = sphere.mean_edge_length();
  for (int v = 0; v < sphere.n_vertices(); ++v) {
    CHECK(N.row(v).norm() == Approx(1.0).epsilon(1e-12));
    // angle between the normal and the radial direction is O(h) on a sphere
    CHECK(sign * N.row(v).dot(sphere.positions().row(v)) > std::cos(h));
  }
}

TEST_CASE("curvature: a flat plane has zero mean curvature at interior vertices", "[apps]") {
  POLYDEC_SHARED_MESH(path, "quad-plane.obj");
  const Mesh plane = read_mesh(path);
  const Eigen::VectorXd H = mean_curvature(plane);
  const double scale = 1.0 / plane.mean_edge_length();
  for (int v = 0; v < plane.n_vertices(); ++v)
    if (!plane.is_boundary_vertex(v)) CHECK(std::abs(H[v]) <= 1e-10 * scale);
}

namespace {

double rmse_with(const OperatorSet& ops, bool lumped) {
  CurvatureOptions o;
  o.lumped_mass = lumped;
  return curvature_rmse(mean_curvature(ops, o), 1.0);
}

}  // namespace

TEST_CASE("curvature: Table 2 RMSE on HEX and FINE SPHERE, lumped and unlumped", "[apps]") {
  POLYDEC_SHARED_MESH(path, "unit-sphere.off");
  const OperatorSet& hex = test::hex_sphere(path).ops;
  const OperatorSet& fine = test::fine_sphere(path).ops;
  CHECK(hex.domain.n_faces() == 16070);
  CHECK(fine.domain.n_faces() == 96408);
  CHECK(rmse_with(hex, true) == Approx(0.001598).epsilon(0.01));
  CHECK(rmse_with(fine, true) == Approx(0.13336).epsilon(0.01));
  CHECK(rmse_with(hex, false) == Approx(0.003915).epsilon(0.01));
  CHECK(rmse_with(fine, false) == Approx(0.36685).epsilon(0.01));
}

TEST_CASE("curvature: a vertex in no face changes nothing and gets H = 0", "[apps]") {
  POLYDEC_SHARED_MESH(path, "quad-sphere.off");
  const Mesh sphere = unit_sphere_mesh(path);
  PolygonSoup soup;
  soup.positions.resize(sphere.n_vertices() + 1, 3);
  soup.positions.topRows(sphere.n_vertices()) = sphere.positions();
  soup.positions.row(sphere.n_vertices()) = Eigen::RowVector3d(3, 0, 0);
  for (int f = 0; f < sphere.n_faces(); ++f) soup.add_face(sphere.face(f));
  const Mesh extra(std::move(soup));
  for (bool lumped : {true, false}) {
    CurvatureOptions o;
    o.lumped_mass = lumped;
    const Eigen::VectorXd H = mean_curvature(sphere, o), He = mean_curvature(extra, o);
    CHECK(He[sphere.n_vertices()] == 0.0);
    CHECK((He.head(sphere.n_vertices()) - H).cwiseAbs().maxCoeff() <= 1e-12);
  }
}

}  // namespace test_curvature
