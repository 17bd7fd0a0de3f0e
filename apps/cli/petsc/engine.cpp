// apps/cli/petsc/engine.cpp — `polydec geodesics|spectrum MESH --engine petsc` under mpirun: every rank
// reads (or generates) the mesh in compact form (errors and the mesh itself agreed across ranks), the distributed operators and
// solvers of operators/petsc/, and a JSON summary with every rank's timings and peak memory; rank 0
// writes the outputs through the command's own code.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <numeric>
#include <optional>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/cli/engine.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/operators/petsc/petsc.h"

namespace polydec::cli {
namespace engine_petsc {
namespace {

// Seconds since the previous lap.
struct Laps {
  std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last).count();
    last = now;
    return s;
  }
};

// "generate:torus:NU,NV": the quad torus of bench/scale_torus.sh (NU x NV quads, radii 1 and 0.4)
// generated on every rank instead of read; an empty optional for other paths.
std::optional<PolygonSoup> generated(const std::string& path) {
  const std::string prefix = "generate:torus:";
  if (path.rfind(prefix, 0) != 0) return std::nullopt;
  int nu = 0, nv = 0;
  char tail = 0;
  if (std::sscanf(path.c_str() + prefix.size(), "%d,%d%c", &nu, &nv, &tail) != 2 || nu < 3 || nv < 3 ||
      long(nu) * long(nv) > long(std::numeric_limits<int>::max() / 4))
    throw std::invalid_argument(fmt::format("{}: expected generate:torus:NU,NV with 3 <= NU, NV", path));
  return torus_soup(nu, nv);
}

// The mesh in compact form (positions and face index lists, no topology), read or generated on
// every rank; a rank that cannot read it, or that reads another mesh than the others (the ranks
// must see the same file), ends every rank with the same error. Validation follows per rank's
// faces in assemble_operators. With --repair, each rank repairs through the serial load_mesh (the
// whole Mesh for a while) and keeps the compact arrays.
PolygonSoup read_everywhere(MPI_Comm comm, const std::string& path, bool repair, std::vector<int>* vertex_map) {
  PolygonSoup soup;
  petsc::agree(comm, [&] {
    if (std::optional<PolygonSoup> g = generated(path)) {
      soup = std::move(*g);
    } else if (!repair) {
      soup = read_polygon_soup(path);
    } else {
      const Mesh mesh = load_mesh(path, true, vertex_map);
      soup.positions = mesh.positions();
      soup.face_offsets = mesh.face_offsets();
      soup.face_indices = mesh.face_indices();
      soup.precision = mesh.precision();
      return;
    }
    if (global_options().planarity_tolerance > 0) soup.precision.planarity_tolerance = global_options().planarity_tolerance;
    if (vertex_map) {
      vertex_map->resize(size_t(soup.n_vertices()));
      std::iota(vertex_map->begin(), vertex_map->end(), 0);
    }
  });
  double fp[3] = {double(soup.n_vertices()), double(soup.n_faces()), 0.0};
  const Eigen::MatrixX3d& X = soup.positions;
  for (Eigen::Index v = 0; v < X.rows(); ++v) fp[2] += (X(v, 0) + 2 * X(v, 1) + 3 * X(v, 2)) * double(v % 101 + 1);
  const std::vector<int>& idx = soup.face_indices;
  for (size_t h = 0; h < idx.size(); ++h) fp[2] += double(idx[h]) * double(h % 97 + 1);
  double lo[3], hi[3];
  MPI_Allreduce(fp, lo, 3, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(fp, hi, 3, MPI_DOUBLE, MPI_MAX, comm);
  petsc::agree(comm, [&] {
    for (int i = 0; i < 3; ++i)
      if (lo[i] != hi[i])
        throw InvalidMeshError("mesh", 0,
                               fmt::format("{}: the ranks read different meshes ({} to {} vertices, {} to {} faces); "
                                           "every rank must read the same file",
                                           path, lo[0], hi[0], lo[1], hi[1]));
  });
  return soup;
}

// The whole Mesh of the compact arrays, built on the first call (rank 0's file and picture outputs).
LazyMesh lazy_mesh(const PolygonSoup& soup, std::optional<Mesh>& cache) {
  const double extent =
      soup.n_vertices() ? (soup.positions.colwise().maxCoeff() - soup.positions.colwise().minCoeff()).norm() : 0.0;
  return {soup.n_vertices(), soup.n_faces(), extent, [&soup, &cache]() -> const Mesh& {
            if (!cache) cache.emplace(PolygonSoup(soup));
            return *cache;
          }};
}

// Per-rank figures: [faces, local vertices, owned vertices, COO entries, read, partition, assembly,
// set-up, solve seconds, peak RSS MB] gathered on rank 0 as JSON.
nlohmann::json per_rank(MPI_Comm comm, const std::vector<double>& v) {
  nlohmann::json out = nlohmann::json::array();
  const auto rows = petsc::gather_per_rank(comm, v);
  for (size_t r = 0; r < rows.size(); ++r) {
    const auto& x = rows[r];
    out.push_back({{"rank", r},
                   {"faces", long(x[0])},
                   {"local_vertices", long(x[1])},
                   {"owned_vertices", long(x[2])},
                   {"coo_entries", long(x[3])},
                   {"seconds", {{"read", x[4]}, {"partition", x[5]}, {"assembly", x[6]}, {"setup", x[7]}, {"solve", x[8]}}},
                   {"peak_rss_mb", x[9]}});
  }
  return out;
}

}  // namespace
}  // namespace engine_petsc

void petsc_geodesics(const std::string& mesh_path, bool repair, const std::vector<int>& file_sources, bool lumped_mass,
                     bool mass_weighted_source, double time_step_factor, const EngineOptions& engine,
                     const std::function<void(const EngineGeodesics&)>& write) {
  using namespace engine_petsc;
  petsc::GeodesicsOptions go;
  go.time_step_factor = time_step_factor;
  go.solver = petsc::parse_linear_solver(engine.solver);
  go.lumped_mass = lumped_mass;
  go.mass_weighted_source = mass_weighted_source;
  const petsc::Session session(engine.petsc_options);
  const MPI_Comm comm = session.comm();
  Laps laps;
  std::vector<int> vertex_map;
  const PolygonSoup mesh = read_everywhere(comm, mesh_path, repair, &vertex_map);
  std::vector<int> sources = file_sources;
  petsc::agree(comm, [&] {
    for (int& s : sources) {
      if (s < 0 || s >= int(vertex_map.size()))
        throw std::out_of_range(fmt::format("source vertex {} is out of range (the mesh has {} vertices)", s,
                                            vertex_map.size()));
      if (vertex_map[size_t(s)] < 0) throw std::out_of_range(fmt::format("source vertex {} was removed by --repair", s));
      s = vertex_map[size_t(s)];
    }
  });
  const double t_read = laps.lap();
  petsc::Partition part;
  petsc::agree(comm, [&] { part = petsc::partition_mesh(mesh, session.size()); });
  const double t_partition = laps.lap();
  const petsc::DistributedOperators ops = petsc::assemble_operators(comm, mesh, part, true, !lumped_mass);
  const double t_assembly = laps.lap();
  const petsc::HeatGeodesics heat(comm, part, ops, ops.mean_edge_length, go);
  const double t_setup = laps.lap();
  const Eigen::VectorXd d = heat.distance(sources);
  const double t_solve = laps.lap();
  const int r = session.rank();
  nlohmann::json summary = {
      {"engine", "petsc"},
      {"ranks", session.size()},
      {"solver", petsc::linear_solver_name(go.solver)},
      {"heat_iterations", heat.heat_iterations()},
      {"poisson_iterations", heat.poisson_iterations()},
      {"per_rank", per_rank(comm, {double(ops.n_local_faces), double(ops.n_local_vertices),
                                   double(part.vertex_begin[size_t(r) + 1] - part.vertex_begin[size_t(r)]),
                                   double(ops.n_coo_entries), t_read, t_partition, t_assembly, t_setup, t_solve,
                                   petsc::peak_rss_mb()})}};
  petsc::agree(comm, [&] {
    std::optional<Mesh> whole;
    if (r == 0) write({lazy_mesh(mesh, whole), sources, d, heat.time_step(), HeatDiagnostics{int(heat.heat_unresolved()), heat.heat_resolved_radius()}, ops.quality, summary});
  });
}

void petsc_spectrum(const std::string& mesh_path, bool repair, int k, bool lumped_mass, bool vectors,
                    const EngineOptions& engine,
                    const std::function<void(const EngineSpectrum&)>& write) {
  using namespace engine_petsc;
  petsc::SpectrumOptions so;
  so.solver = petsc::parse_linear_solver(engine.solver);
  so.k = k;
  so.lumped_mass = lumped_mass;
  so.vectors = vectors;
  const petsc::Session session(engine.petsc_options);
  const MPI_Comm comm = session.comm();
  Laps laps;
  const PolygonSoup mesh = read_everywhere(comm, mesh_path, repair, nullptr);
  const double t_read = laps.lap();
  petsc::Partition part;
  petsc::agree(comm, [&] {
    part = petsc::partition_mesh(mesh, session.size());
    if (part.n_global() != mesh.n_vertices())
      throw InvalidMeshError("vertex", 0,
                             fmt::format("{}: {} unreferenced vertices; the PETSc spectrum needs every vertex in a face "
                                         "(polydec repair removes them)",
                                         mesh_path, mesh.n_vertices() - part.n_global()));
  });
  const double t_partition = laps.lap();
  const petsc::DistributedOperators ops = petsc::assemble_operators(comm, mesh, part, false, !lumped_mass);
  const double t_assembly = laps.lap();
  petsc::Spectrum ps = petsc::spectrum(comm, part, ops, so);
  const double t_solve = laps.lap();
  const int r = session.rank();
  Spectrum sp;
  sp.eigenvalues = ps.eigenvalues;
  sp.eigenvectors = std::move(ps.eigenvectors);
  sp.shift = ps.shift;
  sp.n_converged = ps.n_converged;
  sp.method = "SLEPc Krylov-Schur, shift-and-invert (" + petsc::linear_solver_name(so.solver) + ")";
  nlohmann::json summary = {
      {"engine", "petsc"},
      {"ranks", session.size()},
      {"solver", petsc::linear_solver_name(so.solver)},
      {"method", sp.method},
      {"restarts", ps.n_iterations},
      {"converged", ps.n_converged},
      {"max_residual", ps.max_residual},
      {"per_rank", per_rank(comm, {double(ops.n_local_faces), double(ops.n_local_vertices),
                                   double(part.vertex_begin[size_t(r) + 1] - part.vertex_begin[size_t(r)]),
                                   double(ops.n_coo_entries), t_read, t_partition, t_assembly, 0.0, t_solve,
                                   petsc::peak_rss_mb()})}};
  petsc::agree(comm, [&] {
    std::optional<Mesh> whole;
    if (r == 0) write({lazy_mesh(mesh, whole), sp, summary});
  });
}

}  // namespace polydec::cli
