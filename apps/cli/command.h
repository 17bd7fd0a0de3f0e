// apps/cli/command.h — the polydec subcommand registry and shared CLI helpers. Each
// subcommand lives in its own file apps/cli/<name>.cpp and registers itself with a static
// RegisterCommand object.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace polydec::cli {

// Exit codes of the polydec program.
enum ExitCode : int { kOk = 0, kInternalError = 1, kUsageError = 2, kBadInput = 3, kSolverFailure = 4 };

// A subcommand: `setup` adds its options to `app` and sets a callback that does the work.
// The callback returns normally on success and throws on failure (mapped to exit codes in main).
struct Command {
  std::string name;
  std::string description;
  std::function<void(CLI::App& app)> setup;
};

std::vector<Command>& registry();

struct RegisterCommand {
  RegisterCommand(std::string name, std::string description, std::function<void(CLI::App&)> setup) {
    registry().push_back({std::move(name), std::move(description), std::move(setup)});
  }
};

// Prints a JSON object on stdout (one line per object, pretty with 2 spaces).
void print_json(const nlohmann::json& j);

// Thrown for wrong command-line usage detected after parsing (exit code 2).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace polydec::cli
