// tests/support/paper_spheres.h — the HEX and FINE SPHERE of the paper's Tables 2 and 3 (see
// ../shared/data/README.md) with the paper's operators, built once per test binary: inline
// functions with static locals are shared by every test file that includes this header.
#pragma once

#include <string>

#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec::test {

struct PaperSphere {
  Mesh mesh;
  OperatorSet ops;  // "ours", without G and D
};

// HEX SPHERE: dual of unit-sphere.off (dual vertex at the triangle centroid), projected.
inline const PaperSphere& hex_sphere(const std::string& unit_sphere_off) {
  static const PaperSphere s = [&] {
    const Mesh m = project_to_unit_sphere(dual(read_mesh(unit_sphere_off)));
    return PaperSphere{m, build_operators(m, parse_laplacian("ours"), false)};
  }();
  return s;
}

// FINE SPHERE: one Catmull-Clark step of the HEX SPHERE, projected.
inline const PaperSphere& fine_sphere(const std::string& unit_sphere_off) {
  static const PaperSphere s = [&] {
    const Mesh m = project_to_unit_sphere(catmull_clark(hex_sphere(unit_sphere_off).mesh));
    return PaperSphere{m, build_operators(m, parse_laplacian("ours"), false)};
  }();
  return s;
}

}  // namespace polydec::test
