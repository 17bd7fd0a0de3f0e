// apps/cli/operators.cpp — `polydec operators MESH --out DIR`: writes S, M, M_lumped, G, D, P
// in Matrix Market, rows and columns in the file's vertex order.
#include "apps/cli/command.h"
#include "dec/io.h"
#include "dec/prolongation.h"
#include "operators/gradient.h"

#include <filesystem>
#include <fmt/format.h>

namespace polydec::cli {
namespace {

struct Options {
  std::string mesh, out, rule = "squared-area";
  bool json = false;
};

void run(const Options& o) {
  const Mesh mesh = read_mesh(o.mesh);
  RefinementOptions ropt;
  ropt.rule = parse_virtual_vertex_rule(o.rule);
  const Refinement r = refine(mesh, ropt);
  const Laplacian L = assemble_laplacian(mesh, r);
  std::filesystem::create_directories(o.out);
  SparseMatrix Ml(mesh.n_vertices(), mesh.n_vertices());
  Ml.setIdentity();
  Ml.diagonal() = L.M_lumped;
  write_matrix_market(o.out + "/S.mtx", L.S);
  write_matrix_market(o.out + "/M.mtx", L.M);
  write_matrix_market(o.out + "/M_lumped.mtx", Ml);
  write_matrix_market(o.out + "/G.mtx", gradient(mesh, r));
  write_matrix_market(o.out + "/D.mtx", divergence(mesh, r));
  write_matrix_market(o.out + "/P.mtx", prolongation(mesh, r));
  nlohmann::json j = {{"mesh", o.mesh},
                      {"out", o.out},
                      {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()},
                      {"S_nonzeros", L.S.nonZeros()},
                      {"fan_degenerate", r.quality.n_degenerate},
                      {"fan_inverted", r.quality.n_inverted},
                      {"files", {"S.mtx", "M.mtx", "M_lumped.mtx", "G.mtx", "D.mtx", "P.mtx"}}};
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; S has {} non-zeros\n", o.mesh, mesh.n_vertices(), mesh.n_faces(),
             L.S.nonZeros());
  fmt::print("fan triangles: {} degenerate, {} inverted\n", r.quality.n_degenerate, r.quality.n_inverted);
  fmt::print("wrote S.mtx M.mtx M_lumped.mtx G.mtx D.mtx P.mtx to {}\n", o.out);
}

const RegisterCommand reg("operators", "Assemble S, M, lumped M, G, D, P and write them in Matrix Market", [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("mesh", o->mesh, "input mesh (.obj, .off, .ply)")->required();
  app.add_option("--out", o->out, "output directory")->required();
  app.add_option("--virtual-vertex", o->rule, "virtual-vertex rule: squared-area (default), centroid");
  app.add_flag("--json", o->json, "print one JSON object instead of text");
  app.callback([o] { run(*o); });
});

}  // namespace
}  // namespace polydec::cli
