// tests/apps/cli/test_cli_spectral.cpp — `polydec spectrum --form 1|2` (eigenvalues, cochains, parts,
// pictures, against the library) and `polydec spectral` (HKS, WKS, distances, filter: PLY
// properties and PNGs against the library); usage errors mapped to exit codes.
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "polydec/apps/applications/form_spectrum.h"
#include "polydec/apps/applications/spectral_tools.h"
#include "polydec/dec/surface/complex.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/surface/refinement.h"
#include "tests/apps/cli/cli_run.h"
#include "tests/support/feec_meshes.h"

using namespace polydec;

namespace test_cli_spectral {

namespace {

using Run = test::CliRun;

Run run_cli(const std::string& args, const std::string& dir) { return test::run_cli_in(dir, args); }

bool is_png(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  char sig[8] = {};
  f.read(sig, 8);
  return f && std::string(sig + 1, 3) == "PNG" && std::filesystem::file_size(path) > 1000;
}

// The dense Matrix Market files ("array real general") the spectrum command writes, read by the
// library's reader.
Eigen::MatrixXd read_dense(const std::string& path) { return Eigen::MatrixXd(read_matrix_market(path)); }

// The vertex properties of an ASCII PLY file (as write_mesh writes it), by name.
std::map<std::string, Eigen::VectorXd> read_ply_properties(const std::string& path) {
  std::ifstream f(path);
  std::string line;
  std::vector<std::string> names;
  long n = 0;
  bool in_vertex = false;
  while (std::getline(f, line) && line != "end_header") {
    std::istringstream ls(line);
    std::string a, b, c;
    ls >> a >> b >> c;
    if (a == "element") in_vertex = b == "vertex", n = in_vertex ? std::stol(c) : n;
    if (a == "property" && in_vertex) names.push_back(c);
  }
  std::map<std::string, Eigen::VectorXd> props;
  for (const auto& nm : names) props[nm].resize(n);
  for (long v = 0; v < n; ++v)
    for (const auto& nm : names) f >> props[nm][v];
  REQUIRE(f);
  return props;
}

}  // namespace

TEST_CASE("polydec spectrum --form 1 and --form 2 write eigenpairs, parts and pictures", "[cli_spectral]") {
  const test::ScratchDir scratch("spectral_form");
  const std::string dir = scratch.dir.string();
  write_mesh(dir + "/torus.obj", test::torus(10, 6, 0.1, true));
  const Mesh mesh = read_mesh(dir + "/torus.obj");
  const CoarseComplex cx(mesh);
  for (int degree : {1, 2}) {
    INFO("--form " << degree);
    const std::string out = dir + fmt::format("/out{}", degree),
                      png = dir + fmt::format("/form{}.png", degree);
    const Run r =
        run_cli(fmt::format("spectrum {}/torus.obj --form {} --k 6 --out {} --png {} --png-index 3 --json",
                            dir, degree, out, png),
                dir);
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    FormSpectrumOptions o;
    o.degree = degree;
    o.k = 6;
    const FormSpectrum sp = form_spectrum(mesh, o);
    for (int i = 0; i < 6; ++i) {
      CHECK(j["eigenvalues"][i].get<double>() == Approx(sp.eigenvalues[i]).margin(1e-9 * sp.eigenvalues[5]));
      CHECK(j["eigenpairs"][i]["kind"] == form_kind_name(sp.kinds[size_t(i)]));
    }
    // The torus: two harmonic 1-forms, one harmonic 2-form.
    CHECK(j["eigenpairs"][0]["kind"] == "harmonic");
    CHECK(j["eigenpairs"][degree == 1 ? 1 : 0]["kind"] == "harmonic");
    CHECK(j["eigenpairs"][2]["kind"] != "harmonic");
    const Eigen::MatrixXd W = read_dense(out + "/eigenvectors.mtx");
    CHECK(W.rows() == (degree == 1 ? cx.n_pairs() : cx.n_triples()));
    CHECK(W.cols() == 6);
    const Eigen::MatrixXd E = read_dense(out + "/exact.mtx"), C = read_dense(out + "/coexact.mtx"),
                          H = read_dense(out + "/harmonic.mtx");
    CHECK((E + C + H - W).norm() <= 1e-10 * W.norm());
    CHECK(std::filesystem::exists(out + (degree == 1 ? "/pairs.txt" : "/triples.txt")));
    CHECK(is_png(png));
  }
  // Usage errors.
  CHECK(run_cli("spectrum " + dir + "/torus.obj --form 3 --k 4", dir).code == 2);
  CHECK(run_cli("spectrum " + dir + "/torus.obj --form 1 --k 4 --png " + dir + "/x.png --png-index 9", dir)
            .code == 2);
}

TEST_CASE("polydec spectrum --form warns of degenerate fan triangles", "[cli_spectral]") {
  POLYDEC_SHARED_MESH(path, "tetris.obj");
  const test::ScratchDir scratch("spectral_tetris");
  const Mesh mesh = read_mesh(path);
  const Refinement ref = refine(mesh);
  const Run r = run_cli("spectrum '" + path + "' --form 2 --k 3 --json", scratch.dir.string());
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["fan_degenerate"] == ref.quality.n_degenerate);
  CHECK((r.err.find("degenerate fan triangle") != std::string::npos) == (ref.quality.n_degenerate > 0));
  // The torus has none, and no warning.
  write_mesh(scratch.path("torus.obj"), test::torus(8, 6, 0.1, true));
  const Run t =
      run_cli("spectrum " + scratch.path("torus.obj") + " --form 2 --k 3 --json", scratch.dir.string());
  REQUIRE(t.code == 0);
  CHECK(nlohmann::json::parse(t.out)["fan_degenerate"] == 0);
  CHECK(t.err.find("degenerate") == std::string::npos);
}

TEST_CASE("polydec spectral writes HKS, WKS, distances and the filtered mesh", "[cli_spectral]") {
  const test::ScratchDir scratch("spectral_tools");
  const std::string dir = scratch.dir.string();
  write_mesh(dir + "/sphere.obj", add_noise(hex_sphere(1), 0.1, 2));
  const Mesh mesh = read_mesh(dir + "/sphere.obj");
  SpectrumOptions so;
  so.k = 30;
  const Spectrum sp = laplacian_spectrum(mesh, so);
  {
    const Run r = run_cli("spectral " + dir + "/sphere.obj --hks --k 30 --samples 10 --out " + dir +
                              "/hks.ply --png " + dir + "/hks.png --json",
                          dir);
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    const Eigen::VectorXd t = hks_times(sp, 10);
    const Eigen::MatrixXd hks = heat_kernel_signature(sp, t);
    CHECK(j["times"][9].get<double>() == Approx(t[9]));
    auto props = read_ply_properties(dir + "/hks.ply");
    REQUIRE(props.count("hks_004"));
    CHECK((props["hks_004"] - hks.col(4)).norm() <= 1e-6 * hks.col(4).norm());
    CHECK(is_png(dir + "/hks.png"));
  }
  {
    const Run r =
        run_cli("spectral " + dir + "/sphere.obj --wks --k 30 --samples 10 --out " + dir + "/wks.ply", dir);
    REQUIRE(r.code == 0);
    auto props = read_ply_properties(dir + "/wks.ply");
    CHECK(props.count("wks_009") == 1);
  }
  {
    const Run r = run_cli("spectral " + dir + "/sphere.obj --biharmonic 5 --k 30 --out " + dir +
                              "/bih.ply --png " + dir + "/bih.png",
                          dir);
    REQUIRE(r.code == 0);
    auto props = read_ply_properties(dir + "/bih.ply");
    const Eigen::VectorXd d = biharmonic_distance(sp, 5);
    CHECK((props["biharmonic"] - d).norm() <= 1e-6 * d.norm());
    CHECK(is_png(dir + "/bih.png"));
  }
  {
    const Run r = run_cli("spectral " + dir + "/sphere.obj --diffusion 7 --k 30 --json", dir);
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["max_distance"].get<double>() ==
          Approx(diffusion_distance(sp, 1 / sp.eigenvalues[1], 7).maxCoeff()).epsilon(1e-6));
  }
  {
    const Run r = run_cli("spectral " + dir + "/sphere.obj --filter 4 --out " + dir + "/filtered.ply", dir);
    REQUIRE(r.code == 0);
    const Mesh f = read_mesh(dir + "/filtered.ply");
    const Eigen::VectorXd rad = f.positions().rowwise().norm();
    CHECK(rad.maxCoeff() - rad.minCoeff() < 0.5 * (mesh.positions().rowwise().norm().maxCoeff() -
                                                   mesh.positions().rowwise().norm().minCoeff()));
  }
  CHECK(run_cli("spectral " + dir + "/sphere.obj --hks --wks --json", dir).code == 2);
  CHECK(run_cli("spectral " + dir + "/sphere.obj --json", dir).code == 2);
  CHECK(run_cli("spectral " + dir + "/sphere.obj --biharmonic 100000 --json", dir).code != 0);
}

}  // namespace test_cli_spectral
