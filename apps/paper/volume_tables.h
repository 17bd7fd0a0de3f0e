// apps/paper/volume_tables.h — the "Volumes" section of `polydec paper`: the 3D Franke
// Poisson convergence on the shared polyLaplace cube families (apps/applications/volume/poisson.h)
// with the mass-weighted L2 and polyLaplace's RMS error and their slopes per refinement step, and
// the unit ball's eigenvalue errors, Dirichlet and Neumann, against the zeros of the spherical
// Bessel functions (apps/applications/volume/spectrum.h).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace polydec {

// Runs both studies. Poisson: DATA_DIR/volume/cube_{hexahedron,pyramids,truncated}_L.ovm for
// L = 1..4 (quick: 1..3) and cube_tetrahedron_L.ovm for L = 1..2, methods ours and diamond, Galerkin
// and lumped mass. Ball: the 10 smallest eigenvalues on hex_ball_volume(n), n = 8, 16, 24 (quick: 4,
// 8), Galerkin mass, ours.
// Shape: {"poisson": {method: {mass: {family: [{level, vertices, cells, h, l2_error, rms_error[, l2_slope,
// rms_slope]}]}}, "ball": {"dirichlet"|"neumann": [{n, vertices, cells, h, eigenvalues, analytic,
// relative_error, max_error, method}]}, "setup": {...}}. Throws FileError when a cube file is missing.
nlohmann::json volume_tables(const std::string& data_dir, bool quick);

// The report section (Markdown) for results["volumes"] (what volume_tables returned); "(not run)"
// when absent.
std::string volume_tables_markdown(const nlohmann::json& results);

}  // namespace polydec
