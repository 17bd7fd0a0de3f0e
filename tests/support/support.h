// tests/support/support.h — helpers shared by the tests: paths of the paper's meshes in ../shared/data
// (skipped with a message where a clone has no such folder, mandatory when the environment
// sets POLYDEC_REQUIRE_SHARED_DATA=1, as .ci/run does), scratch folders that remove themselves, and
// small matrix comparisons.
#pragma once

#include <unistd.h>

#include <Eigen/Sparse>
#include <cmath>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

namespace polydec::test {

// Paths fixed at configure time (tests/support/support.cpp, the one file compiled with them, so that the
// other test files' compile commands do not depend on the build folder): ../shared/data, tests/data
// and the built `polydec` program.
const char* shared_data_dir();
const char* test_data_dir();
const char* cli_path();
#define POLYDEC_SHARED_DATA (::polydec::test::shared_data_dir())
#define POLYDEC_TEST_DATA (::polydec::test::test_data_dir())
#define POLYDEC_CLI_PATH (::polydec::test::cli_path())

// Path of ../shared/data/NAME, or "" when the folder is missing (then FAILs if the
// environment requires the shared data).
inline std::string shared_path(const std::string& name) {
  const std::string p = std::string(POLYDEC_SHARED_DATA) + "/" + name;
  if (std::filesystem::exists(p)) return p;
  const char* req = std::getenv("POLYDEC_REQUIRE_SHARED_DATA");
  if (req && std::string(req) == "1") FAIL("required test mesh missing: " << p);
  return "";
}

// A folder polydec_TAG_PID under the system's temporary folder (the process id keeps parallel ctest
// runs apart), emptied and created now and removed with everything in it when the object dies, passed
// or failed (a failed REQUIRE unwinds): at the end of its scope, or at exit for a static one (by the
// process that made it only, not by a forked child that exits).
struct ScratchDir {
  pid_t owner = ::getpid();  // before dir, which is named after it
  std::filesystem::path dir;
  explicit ScratchDir(const std::string& tag)
      : dir(std::filesystem::temp_directory_path() / ("polydec_" + tag + "_" + std::to_string(owner))) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~ScratchDir() {
    std::error_code ec;
    if (::getpid() == owner) std::filesystem::remove_all(dir, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string path(const std::string& name) const { return (dir / name).string(); }
};

// Relative Frobenius difference |A - B| / max(|A|, |B|, tiny).
inline double relative_difference(const Eigen::SparseMatrix<double>& A, const Eigen::SparseMatrix<double>& B) {
  const double scale = std::max({A.norm(), B.norm(), 1e-300});
  return (A - B).norm() / scale;
}

// A star-shaped n-gon around the origin (n x 3 corner positions): corner k at angle 2 pi k / n
// and radius uniform in [r_min, r_max], at height uniform in [-height, height] (0: planar).
inline Eigen::Matrix<double, Eigen::Dynamic, 3> star_polygon(int n, std::mt19937& rng, double r_min, double r_max,
                                                             double height) {
  std::uniform_real_distribution<double> r(r_min, r_max), z(-height, height);
  Eigen::Matrix<double, Eigen::Dynamic, 3> X(n, 3);
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n, rad = r(rng);
    X.row(k) << rad * std::cos(a), rad * std::sin(a), height > 0 ? z(rng) : 0.0;
  }
  return X;
}

}  // namespace polydec::test

// Declares std::string VAR = path of ../shared/data/NAME, or skips the test case (returns)
// with a warning when the folder is absent.
#define POLYDEC_SHARED_MESH(VAR, NAME)                                                     \
  const std::string VAR = polydec::test::shared_path(NAME);                                \
  if (VAR.empty()) {                                                                       \
    WARN("skipped: ../shared/data/" << NAME << " not found (clone without shared data)"); \
    return;                                                                                \
  }
