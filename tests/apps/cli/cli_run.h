// tests/apps/cli/cli_run.h — the CLI tests' way to run the built `polydec` program: exit code,
// stdout and stderr (through files in a scratch folder: test::ScratchDir of tests/support/support.h).
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/support.h"

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

}  // namespace polydec::test
