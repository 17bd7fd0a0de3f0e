// tests/apps/paper/test_sphere_spectrum.cpp — the paper report's sphere-spectrum table: errors against
// l(l+1) agree with a direct computation, shrink under refinement, and the Markdown lists them.
#include <catch2/catch.hpp>

#include "polydec/apps/applications/spectrum.h"
#include "polydec/apps/paper/sphere_spectrum.h"
#include "polydec/dec/mesh/generators.h"

using namespace polydec;

namespace test_sphere_spectrum {

TEST_CASE("sphere_spectrum_errors: first 100 eigenvalues against l(l+1), every Laplacian",
          "[sphere_spectrum]") {
  const Mesh coarse = project_to_unit_sphere(cube_sphere(8)), fine = project_to_unit_sphere(cube_sphere(16));
  const nlohmann::json c = sphere_spectrum_errors(coarse, "ours"), f = sphere_spectrum_errors(fine, "ours");
  // Direct: eigenvalue 99 is the last of the band l = 9 (90).
  SpectrumOptions o;
  o.k = 100;
  const Spectrum sp = laplacian_spectrum(fine, o);
  CHECK(f["per_band"][8].get<double>() >= std::abs(sp.eigenvalues[99] / 90 - 1));
  CHECK(std::abs(f["lambda_0"].get<double>()) <= 1e-8);
  CHECK(f["max"].get<double>() >= f["mean"].get<double>());
  // Second order: a factor ~4 per halving of the edge length; required 2.5.
  CHECK(f["mean"].get<double>() < c["mean"].get<double>() / 2.5);
  CHECK(f["max"].get<double>() < 0.1);  // measured 0.077 (band l = 9)
  // Other operators run; an unknown name is reported, not thrown.
  for (const char* m : {"aw11:0.5", "refined", "intrinsic-delaunay"}) {
    INFO(m);
    const nlohmann::json e = sphere_spectrum_errors(fine, m);
    REQUIRE(e["mean"].is_number());
    CHECK(e["mean"].get<double>() < 0.05);
  }
  CHECK(sphere_spectrum_errors(fine, "no-such-laplacian").contains("error"));
  nlohmann::json r;
  r["spectrum100"]["QUAD SPHERE"]["ours"] = f;
  const std::string md = sphere_spectrum_markdown(r, {"ours", "aw11:0.5"});
  CHECK(md.find("## Spectrum") != std::string::npos);
  CHECK(md.find("| QUAD SPHERE | mean |") != std::string::npos);
}

}  // namespace test_sphere_spectrum
