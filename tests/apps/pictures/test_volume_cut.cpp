// tests/apps/pictures/test_volume_cut.cpp — planar cuts of volume meshes ([volume-render]): the section
// of a unit cube's hex grid through its centre has area 1 (also tilted: the analytic polygon area),
// a linear field is reproduced exactly at the section's vertices, a plane missing the mesh gives an
// empty section and a clear error for the solid, the clipped solid is a valid closed surface.
#include <catch2/catch.hpp>
#include <cmath>

#include "polydec/apps/pictures/volume_cut.h"
#include "polydec/dec/io_volume.h"
#include "polydec/dec/volume_generators.h"
#include "tests/support.h"

using namespace polydec;

namespace test_volume_cut {

TEST_CASE("volume cut: area of the centre section of a unit cube is 1", "[volume-render]") {
  for (const auto& mesh :
       {hex_grid_volume(4, 4, 4), hex_grid_volume(5, 3, 2, {0.25, 3}), pyramid_grid_volume(3, 3, 3),
        truncated_octahedra_volume(2), tet_grid_volume(3, 3, 3, {0.2, 9})}) {
    const VolumeRefinement r = refine_volume(mesh);
    for (int axis = 0; axis < 3; ++axis) {
      // Through the centre (on a layer of faces for even counts) and off the layers.
      for (double c : {0.5, 0.37}) {
        CutPlane p;
        p.point = Eigen::Vector3d::Constant(c);
        p.normal = Eigen::Vector3d::Unit(axis);
        const VolumeCut cut = cut_volume(mesh, r, {}, p);
        INFO("axis " << axis << ", c " << c);
        CHECK(cut.area() == Approx(1.0).epsilon(1e-12));
        // Every section vertex lies in the plane.
        CHECK(((cut.positions.rowwise() - p.point.transpose()) * p.normal).cwiseAbs().maxCoeff() < 1e-12);
      }
    }
    // A tilted plane through the centre, normal (1, 1, 0): a 1 x sqrt(2) rectangle.
    CutPlane tilt;
    tilt.point = Eigen::Vector3d::Constant(0.5);
    tilt.normal = Eigen::Vector3d(1, 1, 0);
    CHECK(cut_volume(mesh, r, {}, tilt).area() == Approx(std::sqrt(2.0)).epsilon(1e-12));
  }
}

TEST_CASE("volume cut: a linear field is reproduced on the section", "[volume-render]") {
  const VolumeMesh mesh = hex_grid_volume(3, 4, 2, {0.3, 17});
  const VolumeRefinement r = refine_volume(mesh);
  const Eigen::Vector3d a(1.5, -0.4, 2.2);
  const Eigen::VectorXd u = mesh.positions() * a + Eigen::VectorXd::Constant(mesh.n_vertices(), 0.7);
  CutPlane p;
  p.point = Eigen::Vector3d(0.41, 0.52, 0.47);
  p.normal = Eigen::Vector3d(0.3, -1.0, 0.6);
  const VolumeCut cut = cut_volume(mesh, r, u, p);
  REQUIRE(!cut.empty());
  REQUIRE(cut.values.size() == cut.positions.rows());
  const Eigen::VectorXd exact = cut.positions * a + Eigen::VectorXd::Constant(cut.positions.rows(), 0.7);
  CHECK((cut.values - exact).cwiseAbs().maxCoeff() < 1e-12 * u.cwiseAbs().maxCoeff());
  // The clipped solid carries the same field at all its vertices (boundary ones included).
  Eigen::VectorXd values;
  const Mesh solid = cut_solid(mesh, r, u, p, &values);
  const Eigen::VectorXd exact_solid =
      solid.positions() * a + Eigen::VectorXd::Constant(solid.n_vertices(), 0.7);
  CHECK((values - exact_solid).cwiseAbs().maxCoeff() < 1e-12 * u.cwiseAbs().maxCoeff());
  // Nothing of the solid lies in front of the plane.
  const Eigen::VectorXd s = (solid.positions().rowwise() - p.point.transpose()) * p.normal.normalized();
  CHECK(s.maxCoeff() < 1e-12);
}

TEST_CASE("volume cut: the solid behind the plane is closed with the section's area", "[volume-render]") {
  const VolumeMesh mesh = truncated_octahedra_volume(2);
  const VolumeRefinement r = refine_volume(mesh);
  const CutPlane p = centre_plane(mesh, Eigen::Vector3d(0, 0, 1));
  const Mesh solid = cut_solid(mesh, r, {}, p);
  // Surface area of the half cube [0,1]^2 x [0, 1/2]: 1 + 1 + 4 / 2 = 4 (the section included).
  double area = 0;
  for (int f = 0; f < solid.n_faces(); ++f) {
    const auto face = solid.face(f);
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < face.size(); ++i)
      a += solid.position(face[i]).cross(solid.position(face[(i + 1) % face.size()]));
    area += 0.5 * a.norm();
  }
  CHECK(area == Approx(4.0).epsilon(1e-12));
}

TEST_CASE("volume cut: a plane missing the mesh", "[volume-render]") {
  const VolumeMesh mesh = hex_grid_volume(2, 2, 2);
  const VolumeRefinement r = refine_volume(mesh);
  CutPlane p;
  p.point = Eigen::Vector3d(0, 0, 3);
  p.normal = Eigen::Vector3d::UnitZ();  // the whole mesh is behind: kept, nothing cut
  CHECK(cut_volume(mesh, r, {}, p).empty());
  CHECK_THROWS_WITH(cut_solid(mesh, r, {}, p), Catch::Contains("misses the volume mesh"));
  p.normal = -p.normal;  // the whole mesh in front: removed
  CHECK(cut_volume(mesh, r, {}, p).empty());
  CHECK_THROWS_WITH(cut_solid(mesh, r, {}, p), Catch::Contains("keeps nothing"));
  p.normal.setZero();
  CHECK_THROWS_AS(cut_volume(mesh, r, {}, p), std::invalid_argument);
  p.normal = Eigen::Vector3d::UnitX();
  CHECK_THROWS_AS(cut_volume(mesh, r, Eigen::VectorXd::Zero(3), p), std::invalid_argument);
}

TEST_CASE("volume cut on a shared cube: area 1", "[volume-render]") {
  for (const std::string name : {"cube_truncated_2.ovm", "cube_pyramids_2.ovm", "cube_hexahedron_2.ovm"}) {
    POLYDEC_SHARED_MESH(path, "volume/" + name);
    const VolumeMesh mesh = read_volume_mesh(path);
    const CutPlane p = centre_plane(mesh, Eigen::Vector3d(0, 1, 0));
    INFO(name);
    CHECK(cut_volume(mesh, refine_volume(mesh), {}, p).area() == Approx(1.0).epsilon(1e-9));
  }
}

}  // namespace test_volume_cut
