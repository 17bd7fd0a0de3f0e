// apps/cli/virtual_lift.cpp — parsing of `--virtual-lift` and `--virtual-positions`.
#include "polydec/apps/cli/virtual_lift.h"

#include "polydec/apps/cli/command.h"
#include "polydec/dec/io/virtual_positions.h"

namespace polydec::cli {

void add_virtual_lift_options(CLI::App& app, VirtualLiftArgs& args) {
  app.add_option("--virtual-lift", args.lift,
                 "virtual vertices off their affine points (beyond the paper; the weights keep defining P): none "
                 "(default), sphere (closest point on the vertices' best-fit sphere), sphere:cx,cy,cz,r, quadric "
                 "(local quadric fit)");
  app.add_option("--virtual-positions", args.positions,
                 "file with one 'x y z' line per face: the virtual vertices' positions");
}

VirtualLift virtual_lift(const VirtualLiftArgs& args, const Mesh& mesh) {
  if (!args.positions.empty()) {
    if (args.lift != "none") throw UsageError("--virtual-positions and --virtual-lift exclude each other");
    VirtualLift lift;
    lift.kind = VirtualLiftKind::Positions;
    lift.positions = read_virtual_positions(args.positions, mesh.n_faces());
    return lift;
  }
  return parse_option(parse_virtual_lift, args.lift);
}

}  // namespace polydec::cli
