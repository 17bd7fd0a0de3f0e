// apps/cli/main.cpp — the polydec command-line program: subcommand dispatch and the mapping
// of failures to exit codes (0 ok, 1 internal error, 2 usage, 3 bad input, 4 solver failure).
#include "polydec/apps/cli/command.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/operators/solvers/cholesky.h"

#include <algorithm>
#include <fmt/format.h>
#include <iostream>

namespace polydec::cli {

std::vector<Command>& registry() {
  static std::vector<Command> commands;
  return commands;
}

void print_json(const nlohmann::json& j) {
  if (!j.is_object() || j.contains("blas_threads")) {
    std::cout << j.dump(2) << std::endl;
    return;
  }
  nlohmann::json out = j;
  const polydec::BlasThreads b = polydec::blas_threads();
  out["blas_threads"] = {
      {"threads", b.threads}, {"requested", b.requested}, {"source", b.source}, {"applied", b.applied}};
  std::cout << out.dump(2) << std::endl;
}

}  // namespace polydec::cli

int main(int argc, char** argv) {
  using namespace polydec::cli;
  CLI::App app{"polydec: discrete exterior calculus on polygon meshes (Polygon Laplacian Made Simple)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "polydec 0.1");
  app.fallthrough();
  app.add_option("--planarity-tolerance", global_options().planarity_tolerance,
                 "faces whose out-of-plane extent is at most this fraction of their size count as planar for "
                 "the virtual-vertex weights (default 0: decided from the precision the file's coordinates "
                 "carry; 1e-5 reproduces polydec <= 0.1)")
      ->check(CLI::Range(0.0, 0.999));
  app.add_option_function<int>(
         "--blas-threads", [](int n) { polydec::set_blas_threads(n); },
         "BLAS threads of the sparse Cholesky solvers (default 1, or POLYDEC_BLAS_THREADS, or OpenBLAS's "
         "OPENBLAS_NUM_THREADS when set; 0: one per core); reported as blas_threads in every --json")
      ->check(CLI::Range(0, 1024));
  auto& cmds = registry();
  std::sort(cmds.begin(), cmds.end(), [](const Command& a, const Command& b) { return a.name < b.name; });
  for (auto& c : cmds) c.setup(*app.add_subcommand(c.name, c.description));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::cerr << "polydec: usage error: " << e.what() << " (see polydec --help)\n";
    return kUsageError;
  } catch (const UsageError& e) {
    std::cerr << "polydec: usage error: " << e.what() << "\n";
    return kUsageError;
  } catch (const polydec::FileError& e) {
    std::cerr << "polydec: bad input: " << e.what() << "\n";
    return kBadInput;
  } catch (const polydec::InvalidMeshError& e) {
    const std::string& input = polydec::cli::global_options().last_input;
    const std::string what = e.what();
    const bool named = input.empty() || what.find(input) != std::string::npos;
    std::cerr << "polydec: bad input: " << (named ? "" : input + ": ") << what << "\n";
    return kBadInput;
  } catch (const polydec::SolverError& e) {
    std::cerr << "polydec: solver failure: " << e.what() << "\n";
    return kSolverFailure;
  } catch (const std::out_of_range& e) {
    std::cerr << "polydec: bad input: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "polydec: usage error: " << e.what() << "\n";
    return kUsageError;
  } catch (const std::exception& e) {
    std::cerr << "polydec: error: " << e.what() << "\n";
    return kInternalError;
  }
  return kOk;
}
