// tests/apps/applications/test_parametrization.cpp — spectral conformal parametrization: a planar disk maps
// conformally onto itself, suzanne-half has low distortion and no flipped fan triangles.
#include <filesystem>
#include <fstream>

#include "polydec/apps/applications/parametrization.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_parametrization {

TEST_CASE("parametrization: a planar mesh is mapped by a similarity (zero distortion)", "[apps]") {
  // For a flat mesh the identity is conformal: E_C = 0 up to translation, so the first
  // non-trivial eigenvector must be a similarity of the input (angles kept exactly).
  for (const Mesh& plane : {quad_grid(6, 4), hex_grid(5, 5), triangle_grid(4, 7)}) {
    const ConformalParametrization p = spectral_conformal_parametrization(plane);
    CHECK(std::abs(p.eigenvalue) <= 1e-9);
    CHECK(conformal_distortion(plane, p.uv) <= 1e-7);
    CHECK(vertex_conformal_distortion(plane, p.uv).maxCoeff() <= 1e-7);
    CHECK(count_flipped_fan_triangles(plane, refine(plane), p.uv) == 0);
    CHECK(p.uv.minCoeff() >= -1e-12);
    CHECK(p.uv.maxCoeff() == Approx(1.0));
  }
}

TEST_CASE("parametrization: suzanne-half (Figure 6, Table 1)", "[apps]") {
  POLYDEC_SHARED_MESH(path, "suzanne-half.obj");
  const Mesh mesh = read_mesh(path);
  const ConformalParametrization p = spectral_conformal_parametrization(mesh);
  const double d = conformal_distortion(mesh, p.uv);
  INFO("conformal distortion " << d);
  CHECK(d > 0);
  // Measured 0.11567 rad (area-weighted RMS corner-angle difference); bound 0.125. Table 1's
  // 1.157e-3 uses a normalization the paper does not state (see docs/applications.md).
  CHECK(d <= 0.125);
  CHECK(count_flipped_fan_triangles(mesh, refine(mesh), p.uv) == 0);
  // Distortion is invariant under scaling of the input (the parametrization is normalized).
  const ConformalParametrization q =
      spectral_conformal_parametrization(mesh.with_positions(1e3 * mesh.positions()));
  CHECK(conformal_distortion(mesh, q.uv) == Approx(d).epsilon(1e-6));
}

TEST_CASE("parametrization: OBJ with vt round-trips and closed meshes are rejected", "[apps]") {
  const Mesh plane = quad_grid(3, 2);
  const ConformalParametrization p = spectral_conformal_parametrization(plane);
  const test::ScratchDir scratch("test_uv");
  const std::string file = scratch.path("uv.obj");
  write_obj_with_uv(file, plane, p.uv);
  const Mesh back = read_mesh(file);
  CHECK(back.n_faces() == plane.n_faces());
  CHECK((back.positions() - plane.positions()).cwiseAbs().maxCoeff() <= 1e-15);
  std::ifstream in(file);
  int vt = 0;
  for (std::string line; std::getline(in, line);) vt += line.rfind("vt ", 0) == 0;
  CHECK(vt == plane.n_vertices());
  CHECK_THROWS_AS(spectral_conformal_parametrization(cube_sphere(3)), std::invalid_argument);
}

}  // namespace test_parametrization
