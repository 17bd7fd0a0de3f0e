// tests/apps/pictures/test_volume_cut.cpp — planar cuts of volume meshes ([volume-render]): the section
// of a unit cube's hex grid through its centre has area 1 (also tilted: the analytic polygon area),
// a linear field is reproduced exactly at the section's vertices, a plane missing the mesh gives an
// empty section and a clear error for the solid, the clipped solid is a valid closed surface; the
// operators' refinement passed in gives the default refinement's cut and picture (polyLaplace's its
// own values), a refinement of another mesh is refused; points within round-off of the plane lie on it.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "polydec/apps/pictures/volume_cut.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/operators/registry/volume_laplacians.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_volume_cut {

// Sum of the faces' areas (each face's vector area).
double surface_area(const Mesh& m) {
  double area = 0;
  for (int f = 0; f < m.n_faces(); ++f) {
    const auto face = m.face(f);
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < face.size(); ++i)
      a += m.position(face[i]).cross(m.position(face[(i + 1) % face.size()]));
    area += 0.5 * a.norm();
  }
  return area;
}

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
  CHECK(surface_area(solid) == Approx(4.0).epsilon(1e-12));
}

TEST_CASE("volume cut: refined vertices within round-off of the plane lie on it", "[volume-render]") {
  // Face and cell points of faces and cells in the plane, moved off it by a few ulps each way (what
  // a weighted sum of corners in the plane may give): the section and the solid are those of the
  // exact points, not slivers of arbitrary orientation.
  const VolumeMesh mesh = truncated_octahedra_volume(2);
  for (int axis = 0; axis < 3; ++axis) {
    VolumeRefinement r = refine_volume(mesh);
    const CutPlane p = centre_plane(mesh, Eigen::Vector3d::Unit(axis));
    int moved = 0;
    for (Eigen::MatrixX3d* points : {&r.face_points, &r.cell_points})
      for (Eigen::Index k = 0; k < points->rows(); ++k)
        if ((*points)(k, axis) == p.point[axis]) {
          (*points)(k, axis) *= 1 + (k % 2 ? 3 : -2) * std::numeric_limits<double>::epsilon();
          ++moved;
        }
    INFO("axis " << axis);
    REQUIRE(moved > 0);
    CHECK(cut_volume(mesh, r, {}, p).area() == Approx(1.0).epsilon(1e-12));
    const Mesh solid = cut_solid(mesh, r, {}, p);
    CHECK(surface_area(solid) == Approx(4.0).epsilon(1e-12));
  }
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

TEST_CASE("volume cut: the operators' refinement passed in, and a refinement of another mesh",
          "[volume-render]") {
  const auto slurp = [](const std::string& path) {
    std::stringstream ss;
    ss << std::ifstream(path, std::ios::binary).rdbuf();
    return ss.str();
  };
  const test::ScratchDir scratch("test_volume_cut");
  for (const VolumeMesh& mesh :
       {hex_grid_volume(3, 4, 2, {0.3, 17}), truncated_octahedra_volume(2, {0.2, 5})}) {
    INFO(mesh.n_cells() << " cells");
    // Not linear on the sub-tetrahedra: the face and cell points' weights show in the values.
    const Eigen::ArrayXd x = mesh.positions().col(0), y = mesh.positions().col(1),
                         z = mesh.positions().col(2);
    const Eigen::VectorXd u = (3 * x).sin() + y * z.square();
    CutPlane p;
    p.point = Eigen::Vector3d(0.41, 0.52, 0.47);
    p.normal = Eigen::Vector3d(0.3, -1.0, 0.6);
    const VolumeRefinement fresh = refine_volume(mesh);
    const OperatorSet ours_ops =
        build_volume_operators(mesh, parse_volume_laplacian("ours"), {.threads = 2, .keep_refinement = true});
    const OperatorSet poly_ops = build_volume_operators(mesh, parse_volume_laplacian("polylaplace"),
                                                        {.with_gradient = false, .keep_refinement = true});
    REQUIRE(ours_ops.volume_refinement.has_value());
    REQUIRE(poly_ops.volume_refinement.has_value());
    const VolumeRefinement& ours = *ours_ops.volume_refinement;
    const VolumeRefinement& poly = *poly_ops.volume_refinement;
    // The refinement "ours" was built on (two threads) cuts exactly as a fresh default one.
    Eigen::VectorXd v_fresh, v_ours, v_poly;
    const Mesh s_fresh = cut_solid(mesh, fresh, u, p, &v_fresh),
               s_ours = cut_solid(mesh, ours, u, p, &v_ours);
    REQUIRE(s_fresh.n_faces() > 0);
    CHECK(s_ours.positions() == s_fresh.positions());
    CHECK(s_ours.face_offsets() == s_fresh.face_offsets());
    CHECK(s_ours.face_indices() == s_fresh.face_indices());
    CHECK(v_ours == v_fresh);
    const VolumeCut c_fresh = cut_volume(mesh, fresh, u, p), c_ours = cut_volume(mesh, ours, u, p);
    CHECK(c_ours.positions == c_fresh.positions);
    CHECK(c_ours.values == c_fresh.values);
    CHECK(c_ours.indices == c_fresh.indices);
    // The picture: the same bytes through both overloads.
    RenderOptions o;
    o.width = 200;
    o.height = 150;
    o.isolines = 8;
    render_volume_cut_png(scratch.path("passed.png"), mesh, ours, u, p, o);
    render_volume_cut_png(scratch.path("default.png"), mesh, u, p, o);
    CHECK(slurp(scratch.path("passed.png")).size() > 1000);
    CHECK(slurp(scratch.path("passed.png")) == slurp(scratch.path("default.png")));
    // polyLaplace's refinement has the same points (the cell rule changes the cell weights only), so
    // the same solid, with its own cell values: the refinement passed in is the one used.
    REQUIRE(poly.cell_points == fresh.cell_points);
    const Mesh s_poly = cut_solid(mesh, poly, u, p, &v_poly);
    CHECK(s_poly.positions() == s_fresh.positions());
    REQUIRE(v_poly.size() == v_fresh.size());
    CHECK((v_poly - v_fresh).cwiseAbs().maxCoeff() > 1e-6 * u.cwiseAbs().maxCoeff());
    // A refinement of another mesh, or with sizes that do not match the cells, is refused before
    // anything is read (and no picture written).
    const VolumeRefinement other = refine_volume(hex_grid_volume(2, 2, 2));
    CHECK_THROWS_AS(cut_volume(mesh, other, u, p), std::invalid_argument);
    CHECK_THROWS_WITH(cut_solid(mesh, other, u, p),
                      Catch::Contains("the refinement does not belong to this mesh"));
    CHECK_THROWS_AS(render_volume_cut_png(scratch.path("other.png"), mesh, other, u, p, o),
                    std::invalid_argument);
    CHECK_FALSE(std::filesystem::exists(scratch.path("other.png")));
    VolumeRefinement bad = fresh;
    bad.face_weights.pop_back();
    CHECK_THROWS_WITH(cut_volume(mesh, bad, u, p), Catch::Contains("face weights"));
    bad = fresh;
    bad.cell_weight_offsets[1] -= 1;  // cell 0 one weight short, cell 1 one too many
    CHECK_THROWS_WITH(cut_volume(mesh, bad, u, p), Catch::Contains("cell 0 has"));
    bad = fresh;
    bad.tets.pop_back();
    CHECK_THROWS_WITH(cut_volume(mesh, bad, u, p), Catch::Contains("sub-tetrahedra for offsets"));
    bad = fresh;
    bad.cell_points.conservativeResize(mesh.n_cells() - 1, 3);
    CHECK_THROWS_WITH(cut_volume(mesh, bad, u, p), Catch::Contains("cell points"));
  }
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
