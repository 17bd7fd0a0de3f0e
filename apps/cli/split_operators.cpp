// apps/cli/split_operators.cpp — the files and fan diagnostics of `operators --virtual-vertex split`.
#include "polydec/apps/cli/split_operators.h"

#include <fmt/format.h>

#include <filesystem>

#include "polydec/apps/cli/command.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/operators/surface/split_laplacian.h"

namespace polydec::cli {

void write_split_operators(const Mesh& mesh, const std::string& mesh_path, const std::string& out, bool json,
                           PhaseTimer& timer) {
  const SplitLaplacian L = timer.time("operators", [&] { return split_laplacian(mesh); });
  const auto t_write = PhaseTimer::Clock::now();
  std::filesystem::create_directories(out);
  SparseMatrix Ml(mesh.n_vertices(), mesh.n_vertices());
  Ml.setIdentity();
  Ml.diagonal() = L.M_lumped;
  write_matrix_market(out + "/S.mtx", L.S);
  write_matrix_market(out + "/M.mtx", L.M);
  write_matrix_market(out + "/M_lumped.mtx", Ml);
  write_matrix_market(out + "/G.mtx", L.G);
  write_matrix_market(out + "/D.mtx", L.D);
  write_matrix_market(out + "/P.mtx", L.P);
  timer.add("write", t_write);
  const SplitRefinement& s = L.split;
  nlohmann::json j = {{"mesh", mesh_path},
                      {"out", out},
                      {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()},
                      {"virtual_vertex", "split"},
                      {"pieces", s.n_pieces()},
                      {"faces_split", s.n_faces_split},
                      {"faces_unsplittable", s.n_faces_unsplittable},
                      {"pieces_histogram", s.pieces_histogram},
                      {"S_nonzeros", L.S.nonZeros()},
                      {"fan_degenerate_before", s.before.n_degenerate},
                      {"fan_inverted_before", s.before.n_inverted},
                      {"fan_degenerate", s.after.n_degenerate},
                      {"fan_inverted", s.after.n_inverted},
                      {"fan_worst_before", s.worst_before},
                      {"fan_worst", s.worst_after},
                      {"files", {"S.mtx", "M.mtx", "M_lumped.mtx", "G.mtx", "D.mtx", "P.mtx"}},
                      {"times_ms", timer.json()}};
  if (json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; S has {} non-zeros\n", mesh_path, mesh.n_vertices(), mesh.n_faces(),
             L.S.nonZeros());
  fmt::print("split: {} faces cut, {} pieces in all, {} faces with an invalid fan and no valid split\n",
             s.n_faces_split, s.n_pieces(), s.n_faces_unsplittable);
  fmt::print("fan triangles: {} degenerate, {} inverted (single virtual vertex: {} degenerate, {} inverted)\n",
             s.after.n_degenerate, s.after.n_inverted, s.before.n_degenerate, s.before.n_inverted);
  fmt::print("worst fan triangle 2 area / longest^2: {:.4g} (single virtual vertex: {:.4g})\n", s.worst_after,
             s.worst_before);
  fmt::print("wrote S.mtx M.mtx M_lumped.mtx G.mtx D.mtx P.mtx to {} (P: (|V| + pieces) x |V|)\n", out);
}

}  // namespace polydec::cli
