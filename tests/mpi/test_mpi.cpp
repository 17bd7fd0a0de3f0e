// tests/mpi/test_mpi.cpp — the distributed engine (operators/petsc/) against the serial library, run by
// ctest under mpirun at 1, 2 and 3 ranks: operators equal, geodesics, eigenpairs and eigenspaces,
// the partition, and the agreement of errors across ranks. Every rank runs every test case in the
// same order; compared quantities are computed on rank 0 and broadcast, so every rank checks the
// same numbers (CHECK, never REQUIRE: a rank leaving a test case early would leave the others
// waiting in a collective call).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <Eigen/SVD>
#include <fmt/format.h>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "polydec/apps/applications/geodesics.h"
#include "polydec/apps/applications/spectrum.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/registry/laplacians.h"
#include "polydec/operators/petsc/petsc.h"
#include "polydec/operators/petsc/petsc_check.h"

namespace test_mpi {

using polydec::Mesh;
namespace pp = polydec::petsc;

MPI_Comm world() { return PETSC_COMM_WORLD; }
int rank() {
  int r = 0;
  MPI_Comm_rank(world(), &r);
  return r;
}
int size() {
  int s = 1;
  MPI_Comm_size(world(), &s);
  return s;
}
// Rank 0's value, on every rank.
double from_root(double x) {
  MPI_Bcast(&x, 1, MPI_DOUBLE, 0, world());
  return x;
}

struct NamedMesh {
  std::string name;
  Mesh mesh;
};

// quad_grid(16, 12) bent into the saddle z = (x - 1/2)^2 - (y - 1/2)^2: an open curved mesh whose
// quads are not planar.
Mesh saddle() {
  const Mesh grid = polydec::quad_grid(16, 12);
  polydec::PolygonSoup soup;
  soup.positions = grid.positions();
  for (Eigen::Index v = 0; v < soup.positions.rows(); ++v) {
    const double x = soup.positions(v, 0) - 0.5, y = soup.positions(v, 1) - 0.5;
    soup.positions(v, 2) = x * x - y * y;
  }
  soup.face_offsets = grid.face_offsets();
  soup.face_indices = grid.face_indices();
  return Mesh(std::move(soup));
}

// A curved mesh with boundary: the scanned ../shared/data/suzanne-half.obj, or where a clone has no
// such folder the generated saddle; a missing file fails when POLYDEC_REQUIRE_SHARED_DATA=1.
NamedMesh open_mesh() {
  const std::string suzanne = std::string(POLYDEC_SHARED_DATA) + "/suzanne-half.obj";
  if (std::filesystem::exists(suzanne)) return {"suzanne-half.obj (boundary)", polydec::read_mesh(suzanne)};
  const char* required = std::getenv("POLYDEC_REQUIRE_SHARED_DATA");
  if (required && std::string(required) == "1") FAIL("required test mesh missing: " << suzanne);
  return {"saddle quad_grid(16, 12) (boundary; " + suzanne + " not found)", saddle()};
}

// The distributed engine's test meshes: a sphere with degenerate eigenvalues (icosahedral
// symmetry: multiplicities 1, 3, 5 exactly), a torus (pairs), a curved mesh with boundary, a noisy hexagon grid.
std::vector<NamedMesh> meshes() {
  std::vector<NamedMesh> out;
  out.push_back({"hex_sphere(3)", polydec::hex_sphere(3)});
  out.push_back({"torus(24, 12)", polydec::torus(24, 12)});
  out.push_back({"noisy hex_grid(10, 10)", polydec::add_noise(polydec::hex_grid(10, 10), 0.01, 7)});
  out.push_back(open_mesh());
  return out;
}

// Largest extent of the mesh's bounding box.
double extent(const Mesh& mesh) {
  return (mesh.positions().colwise().maxCoeff() - mesh.positions().colwise().minCoeff()).maxCoeff();
}

TEST_CASE("the partition is the same on every rank, covers every face once and numbers the vertices in blocks",
          "[mpi][partition]") {
  for (const auto& [name, mesh] : meshes()) {
    INFO(name);
    const pp::Partition p = pp::partition_mesh(mesh, size());
    // Identical on every rank: a hash of the face order and the numbering.
    double h[2] = {0, 0};
    for (size_t i = 0; i < p.face_order.size(); ++i) h[0] += double(p.face_order[i]) * double(i % 9973 + 1);
    for (size_t i = 0; i < p.mesh_vertex.size(); ++i) h[1] += double(p.mesh_vertex[i]) * double(i % 9967 + 1);
    double lo[2], hi[2];
    MPI_Allreduce(h, lo, 2, MPI_DOUBLE, MPI_MIN, world());
    MPI_Allreduce(h, hi, 2, MPI_DOUBLE, MPI_MAX, world());
    CHECK(lo[0] == hi[0]);
    CHECK(lo[1] == hi[1]);
    std::vector<int> seen(size_t(mesh.n_faces()), 0);
    for (int f : p.face_order) ++seen[size_t(f)];
    CHECK(std::count(seen.begin(), seen.end(), 1) == mesh.n_faces());
    CHECK(p.n_global() == mesh.n_vertices());  // these meshes have no unreferenced vertex
    CHECK(p.vertex_begin.back() == p.n_global());
    for (int v = 0; v < mesh.n_vertices(); ++v) CHECK(p.mesh_vertex[size_t(p.global_index[size_t(v)])] == v);
    // A vertex is owned by the rank of the first face (in curve order) that holds it.
    for (int r = 0; r < size(); ++r)
      for (int i = p.face_begin[size_t(r)]; i < p.face_begin[size_t(r) + 1]; ++i)
        for (int v : mesh.face(p.face_order[size_t(i)])) CHECK(p.global_index[size_t(v)] < p.vertex_begin[size_t(r) + 1]);
  }
}

TEST_CASE("distributed S, M and lumped M equal the serial operators to 1e-14", "[mpi][operators]") {
  for (const auto& [name, mesh] : meshes()) {
    INFO(name << " on " << size() << " ranks");
    const pp::Partition p = pp::partition_mesh(mesh, size());
    const pp::DistributedOperators ops = pp::assemble_operators(world(), mesh, p);
    const Eigen::SparseMatrix<double> S = pp::gather_to_root(ops.S.get(), p);
    const Eigen::SparseMatrix<double> M = pp::gather_to_root(ops.M.get(), p);
    const Eigen::VectorXd ml = pp::gather_to_root(ops.M_lumped.get(), p);
    double dS = 1, dM = 1, dl = 1, dSD = 1;
    if (rank() == 0) {
      const polydec::OperatorSet ref = polydec::build_operators(mesh, polydec::parse_laplacian("ours"));
      dS = (S - ref.S).norm() / ref.S.norm();
      dM = (M - ref.M).norm() / ref.M.norm();
      dl = (ml - ref.M_lumped).norm() / ref.M_lumped.norm();
    }
    // D G u = S u: the face-by-face gradient and divergence on the ranks' faces (local G, D and one
    // ghost scatter) against the assembled S, for u = the vertices' x coordinate plus y^2.
    {
      pp::Handle<Vec> u, a, b;
      pp::check(VecDuplicate(ops.M_lumped.get(), u.out()), "VecDuplicate");
      pp::check(VecDuplicate(ops.M_lumped.get(), a.out()), "VecDuplicate");
      pp::check(VecDuplicate(ops.M_lumped.get(), b.out()), "VecDuplicate");
      PetscInt lo = 0, hi = 0;
      pp::check(VecGetOwnershipRange(u.get(), &lo, &hi), "VecGetOwnershipRange");
      for (PetscInt r = lo; r < hi; ++r) {
        const Eigen::Vector3d x = mesh.position(p.mesh_vertex[size_t(r)]);
        pp::check(VecSetValue(u.get(), r, x[0] + x[1] * x[1], INSERT_VALUES), "VecSetValue");
      }
      pp::check(VecAssemblyBegin(u.get()), "VecAssemblyBegin");
      pp::check(VecAssemblyEnd(u.get()), "VecAssemblyEnd");
      pp::divergence_of_gradient(ops, u.get(), a.get(), false);
      pp::check(MatMult(ops.S.get(), u.get(), b.get()), "MatMult");
      PetscReal nb = 0, nd = 0;
      pp::check(VecNorm(b.get(), NORM_2, &nb), "VecNorm");
      pp::check(VecAXPY(a.get(), -1.0, b.get()), "VecAXPY");
      pp::check(VecNorm(a.get(), NORM_2, &nd), "VecNorm");
      dSD = nd / nb;
    }
    // The whole mesh's mean edge length, every edge counted once across the ranks.
    CHECK(std::abs(ops.mean_edge_length - mesh.mean_edge_length()) <= 1e-14 * mesh.mean_edge_length());
    CHECK(from_root(dS) <= 1e-14);
    CHECK(from_root(dM) <= 1e-14);
    CHECK(from_root(dl) <= 1e-14);
    CHECK(dSD <= 1e-12);
  }
}

// A soup from OBJ-style text: "v x y z" and 1-based "f a b c" lines.
polydec::PolygonSoup soup_of(const std::string& obj) { return polydec::read_polygon_soup_from_memory(obj, "obj", "test.obj"); }

TEST_CASE("the compact mesh is validated across ranks as the serial Mesh validates it", "[mpi][validation]") {
  // Edge (0, 1) in three triangles; at 2 and 3 ranks the triangles lie on different ranks, whose
  // own sub-meshes are valid: only the check of the edges between ranks can see it.
  const polydec::PolygonSoup nonmanifold =
      soup_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  // Triangles 0 and 1 traverse edge (0, 1) in the same direction; triangle 2 is apart.
  const polydec::PolygonSoup flipped =
      soup_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf 1 2 3\nf 1 2 4\nf 5 6 7\n");
  for (const auto* s : {&nonmanifold, &flipped}) {
    const pp::Partition p = pp::partition_mesh(*s, size());
    std::string message;
    try {
      pp::assemble_operators(world(), *s, p);
    } catch (const polydec::InvalidMeshError& e) {
      message = e.what();
    }
    std::string serial;
    try {
      Mesh m{polydec::PolygonSoup(*s)};
    } catch (const polydec::InvalidMeshError& e) {
      serial = e.what();
    }
    INFO(message << " | serial: " << serial << " on " << size() << " ranks");
    CHECK(!message.empty());
    CHECK(message.substr(0, 12) == serial.substr(0, 12));  // the same kind of error: "edge (0, 1) i" / "faces 0 and "
  }
}

TEST_CASE("distributed heat geodesics equal the serial ones (direct 1e-8, CG 1e-6 of the diameter)",
          "[mpi][geodesics]") {
  for (const auto& [name, mesh] : meshes()) {
    const pp::Partition p = pp::partition_mesh(mesh, size());
    const pp::DistributedOperators ops = pp::assemble_operators(world(), mesh, p);
    const int sources[2] = {0, mesh.n_vertices() / 2};
    Eigen::VectorXd ref;
    if (rank() == 0) ref = polydec::HeatGeodesics(mesh).distance(std::span<const int>(sources, 2));
    for (auto solver : {pp::LinearSolver::MumpsCholesky, pp::LinearSolver::CgGamg, pp::LinearSolver::CgBoomerAmg}) {
      INFO(name << ", " << pp::linear_solver_name(solver) << " on " << size() << " ranks");
      pp::GeodesicsOptions o;
      o.solver = solver;
      const pp::HeatGeodesics heat(world(), p, ops, mesh.mean_edge_length(), o);
      const Eigen::VectorXd d = heat.distance(std::span<const int>(sources, 2));
      double err = 1, diameter = 0;
      if (rank() == 0) {
        diameter = ref.maxCoeff();
        err = (d - ref).cwiseAbs().maxCoeff() / diameter;
      }
      const double tol = solver == pp::LinearSolver::MumpsCholesky ? 1e-8 : 1e-6;
      CHECK(from_root(diameter) > 0.5 * extent(mesh));
      CHECK(from_root(err) <= tol);
      if (solver == pp::LinearSolver::MumpsCholesky) CHECK(heat.heat_unresolved() == 0);
    }
  }
}

TEST_CASE("heat geodesics report how far the heat step is resolved, and the suggested time factor resolves it",
          "[mpi][geodesics]") {
  // On a 30k-quad torus (300 x 100) at the paper's t = h^2 the heat solution falls below CG's
  // resolution (10 rtol max u) ~30 edges from the source: CG must count most vertices; MUMPS
  // (double precision's range, 1e-280 max u, reached ~650 edges out) none, as the serial class. At
  // the factor suggested from the CG run, both solvers resolve every vertex and agree to 1e-6 of
  // the diameter.
  const std::string name = "torus(300, 100)";
  const Mesh mesh = polydec::torus(300, 100);
  const pp::Partition p = pp::partition_mesh(mesh, size());
  const pp::DistributedOperators ops = pp::assemble_operators(world(), mesh, p);
  const int source = 0;
  const double paper_factor = 1.0;
  polydec::HeatDiagnostics serial;
  if (rank() == 0) polydec::HeatGeodesics(mesh).distance(std::span<const int>(&source, 1), &serial);
  double factor = 0;
  for (auto solver : {pp::LinearSolver::CgGamg, pp::LinearSolver::MumpsCholesky}) {
    INFO(name << ", " << pp::linear_solver_name(solver) << " on " << size() << " ranks");
    pp::GeodesicsOptions o;
    o.solver = solver;
    o.time_step_factor = paper_factor;
    const pp::HeatGeodesics heat(world(), p, ops, mesh.mean_edge_length(), o);
    heat.distance(std::span<const int>(&source, 1));
    CHECK(heat.heat_unresolved() <= mesh.n_vertices());
    if (solver == pp::LinearSolver::CgGamg) {
      CHECK(heat.heat_unresolved() > mesh.n_vertices() / 2);
      CHECK(heat.heat_resolved_radius() < 0.5 * extent(mesh));
      factor = polydec::suggested_time_factor(
          paper_factor, {int(heat.heat_unresolved()), heat.heat_resolved_radius()}, mesh.bounding_box_diagonal());
    } else {
      CHECK(from_root(double(serial.unresolved_vertices)) == double(heat.heat_unresolved()));
    }
  }
  CHECK(factor > paper_factor);
  Eigen::VectorXd by_solver[2];
  int i = 0;
  for (auto solver : {pp::LinearSolver::CgGamg, pp::LinearSolver::MumpsCholesky}) {
    INFO(name << ", " << pp::linear_solver_name(solver) << " at factor " << factor << " on " << size() << " ranks");
    pp::GeodesicsOptions o;
    o.solver = solver;
    o.time_step_factor = factor;
    const pp::HeatGeodesics heat(world(), p, ops, mesh.mean_edge_length(), o);
    by_solver[i++] = heat.distance(std::span<const int>(&source, 1));
    CHECK(heat.heat_unresolved() == 0);
  }
  double err = 1;
  if (rank() == 0) err = (by_solver[0] - by_solver[1]).cwiseAbs().maxCoeff() / by_solver[1].maxCoeff();
  CHECK(from_root(err) <= 1e-6);
}

// Groups of (numerically) equal eigenvalues: [begin, end) index ranges of `lambda` (ascending)
// whose neighbours differ by less than `gap` relative to the largest.
std::vector<std::pair<int, int>> clusters(const Eigen::VectorXd& lambda, double gap) {
  std::vector<std::pair<int, int>> out;
  const double scale = lambda.cwiseAbs().maxCoeff();
  int b = 0;
  for (int i = 1; i <= lambda.size(); ++i)
    if (i == lambda.size() || lambda[i] - lambda[i - 1] > gap * scale) {
      out.emplace_back(b, i);
      b = i;
    }
  return out;
}

TEST_CASE("SLEPc eigenpairs equal the serial ones: eigenvalues 1e-8, eigenspaces by principal angles",
          "[mpi][spectrum]") {
  const int k = 10;
  for (bool lumped : {true, false}) {
    for (const auto& [name, mesh] : meshes()) {
      if (!lumped && name.rfind("hex_sphere", 0) != 0) continue;  // Galerkin mass: once
      INFO(name << (lumped ? ", lumped" : ", Galerkin") << " mass on " << size() << " ranks");
      const pp::Partition p = pp::partition_mesh(mesh, size());
      const pp::DistributedOperators ops = pp::assemble_operators(world(), mesh, p, false);
      pp::SpectrumOptions o;
      o.k = k;
      o.lumped_mass = lumped;
      const pp::Spectrum sp = pp::spectrum(world(), p, ops, o);
      double value_err = 1, orth_err = 1, max_sine = 1, n_clusters = 0;
      std::string values;  // both lists, for the report of a failure
      if (rank() == 0) {
        // The serial spectrum with 4 more pairs, to know which clusters end inside the first k.
        polydec::SpectrumOptions so;
        so.k = k + 4;
        so.lumped_mass = lumped;
        const polydec::OperatorSet set = polydec::build_operators(mesh, polydec::parse_laplacian("ours"), false);
        const polydec::Spectrum ref = polydec::laplacian_spectrum(set, so);
        const Eigen::VectorXd& ls = ref.eigenvalues;
        for (int i = 0; i < k; ++i) values += fmt::format("{:.12g} / {:.12g}\n", ls[i], sp.eigenvalues[i]);
        const double first_nonzero = ls[1];  // these meshes are connected: one zero eigenvalue
        value_err = 0;
        for (int i = 0; i < k; ++i)
          value_err = std::max(value_err, std::abs(sp.eigenvalues[i] - ls[i]) / std::max(std::abs(ls[i]), first_nonzero));
        const Eigen::SparseMatrix<double> Mm =
            lumped ? Eigen::SparseMatrix<double>(set.M_lumped.asDiagonal()) : set.M;
        const Eigen::MatrixXd& V = sp.eigenvectors;
        orth_err = (V.transpose() * (Mm * V) - Eigen::MatrixXd::Identity(k, k)).cwiseAbs().maxCoeff();
        max_sine = 0;
        for (auto [b, e] : clusters(ls, 1e-6)) {
          if (e > k) break;  // a cluster cut by k
          const Eigen::MatrixXd C =
              ref.eigenvectors.middleCols(b, e - b).transpose() * (Mm * V.middleCols(b, e - b));
          const double smin = Eigen::JacobiSVD<Eigen::MatrixXd>(C).singularValues().minCoeff();
          max_sine = std::max(max_sine, std::sqrt(std::max(0.0, 1 - smin * smin)));
          n_clusters += 1;
        }
      }
      INFO("serial / SLEPc eigenvalues (rank 0):\n" << values);
      CHECK(from_root(value_err) <= 1e-8);
      CHECK(from_root(orth_err) <= 1e-8);
      CHECK(from_root(max_sine) <= 1e-6);
      CHECK(from_root(n_clusters) >= 3);
      // The engine's own backward error of the returned pairs (not SLEPc's test).
      CHECK(sp.max_residual <= 1e-8);
      if (lumped && name.rfind("hex_sphere", 0) == 0) {
        // Without gathering the vectors: the same values, nothing gathered.
        o.vectors = false;
        const pp::Spectrum values_only = pp::spectrum(world(), p, ops, o);
        CHECK(values_only.eigenvectors.size() == 0);
        CHECK((values_only.eigenvalues - sp.eigenvalues).cwiseAbs().maxCoeff() <=
              1e-12 * sp.eigenvalues.cwiseAbs().maxCoeff());
        CHECK(values_only.max_residual <= 1e-8);
      }
    }
  }
}

TEST_CASE("an error on one rank ends every rank with the same error", "[mpi][errors]") {
  const int last = size() - 1;
  auto run = [&](auto thrower) -> std::string {
    try {
      pp::agree(world(), [&] {
        if (rank() == last) thrower();
      });
    } catch (const polydec::FileError& e) {
      return std::string("FileError: ") + e.what() + " line " + std::to_string(e.line);
    } catch (const polydec::InvalidMeshError& e) {
      return std::string("InvalidMeshError: ") + e.what() + " index " + std::to_string(e.index);
    } catch (const polydec::SolverError& e) {
      return std::string("SolverError: ") + e.what();
    }
    return "no error";
  };
  const std::string file = run([] { throw polydec::FileError("missing.obj", 3, 17, "cannot open file"); });
  CHECK(file == std::string("FileError: ") + polydec::FileError("missing.obj", 3, 17, "cannot open file").what() +
                    " line 3");
  const std::string mesh = run([] { throw polydec::InvalidMeshError("edge", 5, "edge (1, 2) is non-manifold"); });
  CHECK(mesh == "InvalidMeshError: edge (1, 2) is non-manifold index 5");
  CHECK(run([] { throw polydec::SolverError("no convergence"); }) == "SolverError: no convergence");
  CHECK(run([] {}) == "no error");
  // A real one: a file that only the last rank tries to read.
  const std::string missing = run([] { polydec::read_mesh("/nonexistent/polydec-mpi-test.obj"); });
  CHECK(missing.rfind("FileError: ", 0) == 0);
  CHECK(missing.find("polydec-mpi-test.obj") != std::string::npos);
}

}  // namespace test_mpi

int main(int argc, char** argv) {
  const polydec::petsc::Session session;
  Catch::Session catch_session;
  if (int rc = catch_session.applyCommandLine(argc, argv)) return rc;
  // Only rank 0 reports (every rank checks the same broadcast numbers).
  if (session.rank() != 0) catch_session.configData().outputFilename = "/dev/null";
  int failed = catch_session.run();
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, session.comm());
  return failed > 0 ? 1 : 0;
}
