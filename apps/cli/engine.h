// apps/cli/engine.h — the `--engine petsc` runs of `polydec geodesics` and `polydec spectrum` under
// mpirun (apps/cli/petsc/engine.cpp, compiled only with -DPOLYDEC_WITH_PETSC=ON; without it the
// commands answer --engine petsc with a usage error). Every rank reads the mesh in compact form (or
// generates it: MESH = generate:torus:NU,NV, the quad torus of bench/scale_torus.sh); rank 0 writes the
// same outputs as the serial command, through the command's own output code (the `write` callback,
// run on rank 0 inside the engine's error agreement, so a failure there ends every rank alike).
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "polydec/apps/applications/geodesics.h"
#include "polydec/apps/applications/spectrum.h"
#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec::cli {

// The options the PETSc engine adds to a subcommand.
struct EngineOptions {
  std::string engine = "serial";  // serial | petsc
  std::string solver = "direct";  // direct (MUMPS Cholesky) | cg-gamg | cg-hypre
  std::string petsc_options;      // passed to PETSc's options database, e.g. "-heat_ksp_monitor -eps_view"
};

inline void add_engine_options(CLI::App& app, EngineOptions& e) {
  app.add_option("--engine", e.engine,
                 "serial (default) or petsc: distributed on PETSc/SLEPc, run as `mpirun -n N polydec ...` "
                 "(needs a build with -DPOLYDEC_WITH_PETSC=ON)");
  app.add_option("--solver", e.solver,
                 "with --engine petsc: linear solver, direct (MUMPS Cholesky, default), cg-gamg or cg-hypre "
                 "(CG with GAMG or BoomerAMG)");
  app.add_option("--petsc-options", e.petsc_options,
                 "with --engine petsc: PETSc/SLEPc options, e.g. \"-heat_ksp_type gmres -eps_view\" (prefixes heat_, "
                 "poisson_, st_, eps_); PETSC_OPTIONS in the environment works too");
}

// A mesh's counts, and the whole Mesh built only when an output needs it (files, pictures): the
// engine holds the mesh in compact form only, and rank 0 builds the Mesh on the first get().
struct LazyMesh {
  int n_vertices = 0, n_faces = 0;
  double extent = 0;  // bounding-box diagonal of the vertices
  std::function<const Mesh&()> get;
  static LazyMesh of(const Mesh& m) {
    return {m.n_vertices(), m.n_faces(), m.bounding_box_diagonal(), [&m]() -> const Mesh& { return m; }};
  }
};

// What rank 0 hands to the geodesics command's output code.
struct EngineGeodesics {
  LazyMesh mesh;
  const std::vector<int>& sources;  // mesh vertices
  const Eigen::VectorXd& distance;  // |V|, mesh order
  double time_step;
  HeatDiagnostics heat;  // how far the heat step was resolved
  FanQuality quality;
  nlohmann::json summary;  // engine, ranks, solver, iterations, per-rank timings and memory
};

// Heat geodesics from file vertices `file_sources` (mapped as the serial command maps them).
void petsc_geodesics(const std::string& mesh_path, bool repair, const std::vector<int>& file_sources, bool lumped_mass,
                     bool mass_weighted_source, double time_step_factor, const EngineOptions& engine,
                     const std::function<void(const EngineGeodesics&)>& write);

// What rank 0 hands to the spectrum command's output code.
struct EngineSpectrum {
  LazyMesh mesh;
  const Spectrum& spectrum;  // eigenvectors |V| x k in mesh order, M-orthonormal
  nlohmann::json summary;
};

// The k smallest eigenpairs of -S x = lambda M x with SLEPc.
void petsc_spectrum(const std::string& mesh_path, bool repair, int k, bool lumped_mass, bool vectors,
                    const EngineOptions& engine,
                    const std::function<void(const EngineSpectrum&)>& write);

}  // namespace polydec::cli
