// tests/apps/cli/test_cli_threads.cpp — the BLAS thread policy of the CLI: the choice and its
// source reported in --json (default one thread, POLYDEC_BLAS_THREADS, --blas-threads), bad
// counts rejected, --planarity-tolerance applied. (Its speed under load is measured by
// `polydec_bench --only blas-load`, docs/benchmarks.md, not here.)
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_cli_threads {

namespace {

struct Run {
  int code;
  std::string out;
};

// Runs the CLI with a clean thread environment plus `env` (e.g. "POLYDEC_BLAS_THREADS=2").
Run run_cli(const std::string& env, const std::string& args, const std::string& dir) {
  const std::string out = dir + "/stdout.txt";
  const std::string cmd = "env -u OPENBLAS_NUM_THREADS -u OMP_NUM_THREADS -u POLYDEC_BLAS_THREADS " + env +
                          " '" + std::string(POLYDEC_CLI_PATH) + "' " + args + " > '" + out + "' 2> '" + dir +
                          "/stderr.txt'";
  const int status = std::system(cmd.c_str());
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

nlohmann::json blas_of(const Run& r) {
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  REQUIRE(!j.is_discarded());
  REQUIRE(j.contains("blas_threads"));
  return j["blas_threads"];
}

}  // namespace

TEST_CASE("the CLI reports its BLAS thread policy in --json", "[threads][cli]") {
  const test::ScratchDir scratch("threads_report");
  const std::string dir = scratch.dir.string();
  write_mesh(dir + "/grid.obj", quad_grid(20, 20));
  const std::string geo = "geodesics '" + dir + "/grid.obj' --source 0 --json";
  const nlohmann::json def = blas_of(run_cli("", geo, dir));
  CHECK(def["source"] == "default");
  CHECK(def["requested"] == 1);
  if (def["applied"].get<bool>()) CHECK(def["threads"] == 1);  // OpenBLAS mapped: the count is in effect
  const nlohmann::json env = blas_of(run_cli("POLYDEC_BLAS_THREADS=2", geo, dir));
  CHECK(env["source"] == "POLYDEC_BLAS_THREADS");
  CHECK(env["requested"] == 2);
  if (env["applied"].get<bool>()) CHECK(env["threads"] == 2);
  const nlohmann::json flag = blas_of(run_cli("POLYDEC_BLAS_THREADS=2", "--blas-threads 1 " + geo, dir));
  CHECK(flag["source"] == "set_blas_threads");
  CHECK(flag["requested"] == 1);
  const nlohmann::json openblas = blas_of(run_cli("OPENBLAS_NUM_THREADS=1", geo, dir));
  CHECK(openblas["source"] == "OPENBLAS_NUM_THREADS");
  // Bad counts: a usage error (2) for the flag, an error naming the variable for the environment.
  CHECK(run_cli("", "--blas-threads -1 " + geo, dir).code == 2);
  CHECK(run_cli("POLYDEC_BLAS_THREADS=many", geo, dir).code != 0);
  std::ifstream err(dir + "/stderr.txt");
  std::stringstream es;
  es << err.rdbuf();
  CHECK(es.str().find("POLYDEC_BLAS_THREADS") != std::string::npos);
  // The planarity tolerance is a global option too (after the subcommand as well).
  CHECK(run_cli("", geo + " --planarity-tolerance 1e-5", dir).code == 0);
  CHECK(run_cli("", geo + " --planarity-tolerance 2", dir).code == 2);
}

}  // namespace test_cli_threads
