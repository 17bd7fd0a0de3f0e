// apps/cli/virtual_lift.h — the `--virtual-lift` and `--virtual-positions` options of the commands
// that build the paper's operator (dec/surface/virtual_lift.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/virtual_lift.h"

namespace polydec::cli {

struct VirtualLiftArgs {
  std::string lift = "none";  // --virtual-lift: none, sphere, sphere:cx,cy,cz,r, quadric
  std::string positions;      // --virtual-positions FILE: one "x y z" line per face
};

// Adds both options to a subcommand.
void add_virtual_lift_options(CLI::App& app, VirtualLiftArgs& args);

// The lift the options ask for on `mesh`: UsageError for a malformed --virtual-lift or both options at
// once, FileError (exit 3) for an unreadable or malformed positions file.
VirtualLift virtual_lift(const VirtualLiftArgs& args, const Mesh& mesh);

}  // namespace polydec::cli
