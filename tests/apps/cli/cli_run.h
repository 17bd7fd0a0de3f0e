// tests/apps/cli/cli_run.h — the CLI tests' way to run the built `polydec` program: exit code,
// stdout and stderr (through files in a scratch folder), and the scratch folder itself.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support.h"

namespace polydec::test {

struct CliRun {
  int code = -1;  // exit code, -1 when the program did not exit normally
  std::string out, err;
};

// Runs `polydec ARGS` (ARGS as on a shell command line), its stdout and stderr captured in
// dir/stdout.txt and dir/stderr.txt.
inline CliRun run_cli_in(const std::filesystem::path& dir, const std::string& args) {
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd =
      std::string("'") + POLYDEC_CLI_PATH + "' " + args + " >'" + out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::stringstream o, e;
  o << std::ifstream(out).rdbuf();
  e << std::ifstream(err).rdbuf();
  r.out = o.str();
  r.err = e.str();
  return r;
}

// The lines of `text` (stderr, say), without their line ends.
inline std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A folder polydec_TAG_PID under the system's temporary folder, created now and removed with
// everything in it at the end of the scope.
struct ScratchDir {
  std::filesystem::path dir;
  explicit ScratchDir(const std::string& tag) {
    dir = std::filesystem::temp_directory_path() / ("polydec_" + tag + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string path(const std::string& name) const { return (dir / name).string(); }
};

}  // namespace polydec::test
