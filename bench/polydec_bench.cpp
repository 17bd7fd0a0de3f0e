// bench/polydec_bench.cpp — the benchmark behind docs/benchmarks.md. Every figure is a ratio
// against a baseline timed in the same process, interleaved run by run (the machines are shared
// and noisy): the plain surface and volume Laplacians (bench/plain_surface_reference.cpp,
// bench/plain_volume_reference.cpp), a geometry-central-like heat-geodesics path (bench/gc_like_heat.cpp),
// a first assembly, single-threaded assembly, Eigen's SimplicialLLT, or our own
// precomputation. Prints a Markdown table on stdout.
//
//   polydec_bench [--big N] [--no-big] [--quick] [--reps K] [--blas-threads N] [--no-big-geodesics]
//                 [--only spectrum|feec|geodesics|cholesky|form-spectrum|volume|dec]   (one section on FINE SPHERE;
//                 form-spectrum: a 100k-face quad sphere)
//   polydec_bench --only geodesics-big [--big N]   (the geodesics section on cube_sphere(N) alone, default 500)
//   --gc-like-simplicial   (the geometry-central-like heat path with simplicial factors on the big mesh too:
//                 CHOLMOD's simplicial factorization of the 1.5M-quad sphere takes minutes)
//   polydec_bench --only dec [--no-big]   (DEC bundles, each in a child process: HEX SPHERE on both
//                 complexes; the mesh complex on a 1M-quad sphere, a jittered 32^3 hex grid, BCC Voronoi
//                 cells and the 100^3 grid)
//   polydec_bench --only assembly [--no-big] [--big N]  (surface assembly rows: HEX SPHERE, FINE SPHERE,
//                 bunny-hexa, and cube_sphere(N), default 500, with the recorded pmp-library constant)
//   polydec_bench --only checks [--big N]   (check_mesh on cube_sphere(N), default 500)
//   polydec_bench --only volume [--volume-big N]   (volume S + M against the plain volume reference:
//                 cube_hexahedron_4, hex_grid_volume(16^3) and hex_grid_volume(N^3), default N = 100)
//   polydec_bench --only blas-load [--cli PATH]   (not part of the default run: `polydec geodesics` on
//                 a 100k-vertex quad torus with the default BLAS policy against OPENBLAS_NUM_THREADS=1,
//                 two busy processes beside it, wall time; PATH defaults to this build's CLI)
//   polydec_bench --memory-child N      (internal: peak memory of one assembly, fresh process)
//   polydec_bench --volume-first-child N T   (internal: one volume assembly on T threads, fresh process)
//   polydec_bench --volume-read N [R]   (hex_grid_volume(N^3) built, then read back from .vtu, .vtk and
//                 .msh files, R rounds: what loading a large volume mesh costs)
//   polydec_bench --surface-read N [R]  (the same for cube_sphere(N) and .off, .obj, .ply)
//   polydec_bench --volume-memory N     (the polydec side alone on hex_grid_volume(N^3): peak memory,
//                 for /usr/bin/time -v; prints the sizes of the mesh and the matrices)
#include "polydec/apps/applications/geodesics.h"
#include "polydec/apps/applications/form_spectrum.h"
#include "polydec/apps/applications/spectrum.h"
#include "bench/plain_surface_reference.h"
#include "bench/plain_volume_reference.h"
#ifdef POLYDEC_HAVE_GC_LIKE_HEAT
#include "bench/gc_like_heat.h"
#endif
#include "polydec/dec/detail/huge_pages.h"
#include "polydec/dec/surface/complex.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/mesh_checks.h"
#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/operators/solvers/cholesky.h"
#include "polydec/operators/surface/laplacian.h"
#include "polydec/operators/volume/laplacian.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <ctime>
#include <malloc.h>
#include <memory>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <set>
#include <sstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace polydec;

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// CPU time of the calling thread: single-threaded comparisons are not distorted by other
// processes on the shared machine (wall time is used for the thread-scaling rows only).
double thread_cpu_ms() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

double time_ms(const std::function<void()>& f) {
  const double t0 = thread_cpu_ms();
  f();
  return thread_cpu_ms() - t0;
}

double process_cpu_ms(const std::function<void()>& f) {
  timespec a, b;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &a);
  f();
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &b);
  return (b.tv_sec - a.tv_sec) * 1e3 + (b.tv_nsec - a.tv_nsec) * 1e-6;
}

double wall_ms(const std::function<void()>& f) {
  const auto t0 = Clock::now();
  f();
  return ms_since(t0);
}

// Minor page faults of the calling thread while f runs (each costs ~13 us on these virtual machines).
double minor_faults(const std::function<void()>& f) {
  rusage a, b;
  getrusage(RUSAGE_THREAD, &a);
  f();
  getrusage(RUSAGE_THREAD, &b);
  return double(b.ru_minflt - a.ru_minflt);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

double best(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

// Runs the two timed functions alternately `reps` times; returns the median of each.
std::pair<double, double> interleaved(int reps, const std::function<void()>& base, const std::function<void()>& ours,
                                      bool wall = false) {
  std::vector<double> tb, to;
  for (int i = 0; i < reps; ++i) {
    tb.push_back(wall ? wall_ms(base) : time_ms(base));
    to.push_back(wall ? wall_ms(ours) : time_ms(ours));
  }
  return {median(tb), median(to)};
}

struct Row {
  std::string target, mesh, baseline, ours;
  double base_ms = 0, ours_ms = 0;
  double ratio = 0;      // base_ms / ours_ms unless stated
  double required = 0;   // 0: no target, reported only
  std::string note;
};
std::vector<Row> rows;

void add(Row r) {
  if (r.ratio == 0 && r.ours_ms > 0) r.ratio = r.base_ms / r.ours_ms;
  std::fprintf(stderr, "  %-28s %-12s %10.2f ms / %10.2f ms = %6.2fx  %s\n", r.target.c_str(), r.mesh.c_str(),
               r.base_ms, r.ours_ms, r.ratio, r.note.c_str());
  rows.push_back(std::move(r));
}

std::string shared(const std::string& name) { return std::string(POLYDEC_SHARED_DATA) + "/" + name; }

// HEX SPHERE: the dual of the paper's unit-sphere.off, projected (16070 faces), or where the shared
// meshes are missing the generated hex_sphere(5) (10242 faces; the table's last lines give the counts).
Mesh hex_sphere_mesh() {
  const std::string path = shared("unit-sphere.off");
  if (std::filesystem::exists(path)) return project_to_unit_sphere(dual(read_mesh(path)));
  std::fprintf(stderr, "%s not found: HEX SPHERE is the generated hex_sphere(5)\n", path.c_str());
  return hex_sphere(5);
}

bool same_bits(const SparseMatrix& A, const SparseMatrix& B) {
  return A.nonZeros() == B.nonZeros() &&
         std::memcmp(A.valuePtr(), B.valuePtr(), sizeof(double) * A.nonZeros()) == 0 &&
         std::memcmp(A.innerIndexPtr(), B.innerIndexPtr(), sizeof(int) * A.nonZeros()) == 0;
}

double relative_difference(const SparseMatrix& A, const SparseMatrix& B) {
  return (A - B).norm() / std::max(A.norm(), B.norm());
}

// dst takes src's storage (Eigen 3.4's SparseMatrix has no move assignment: `dst = f()` would
// deep-copy S and M inside the timed region).
void take(Laplacian& dst, Laplacian&& src) {
  dst.S.swap(src.S);
  dst.M.swap(src.M);
  dst.M_lumped.swap(src.M_lumped);
}

// Assembly from a loaded mesh: virtual vertices, pattern, the parts asked for (default S, M, lumped M).
Laplacian assemble_all(const Mesh& mesh, int threads, LaplacianParts parts = {}) {
  RefinementOptions options;
  options.threads = threads;
  const Refinement r = refine(mesh, options);
  return assemble_laplacian(mesh, r, parts, nullptr, {threads});
}

struct AssemblyMs {
  double full = 0;      // S + M + lumped M
  double s_lumped = 0;  // S + lumped M
};

// Rounds of the plain reference, S+M+lumped and S+lumped (ours in alternating order); returns our
// medians (ms). Each of ours keeps its own result, so that each run frees a result of its own size.
AssemblyMs bench_assembly(const std::string& name, const Mesh& mesh, int reps) {
  const auto input = plain_surface_reference::from_mesh(mesh);
  SparseMatrix Sp, Mp;
  Laplacian L, Ls;
  std::vector<double> t_plain, t_full, t_sl;
  auto full = [&] { t_full.push_back(time_ms([&] { take(L, assemble_all(mesh, 1)); })); };
  auto s_lumped = [&] {
    t_sl.push_back(time_ms([&] { take(Ls, assemble_all(mesh, 1, {true, false, true})); }));
  };
  for (int i = 0; i < reps; ++i) {
    t_plain.push_back(time_ms([&] { plain_surface_reference::build(input, Sp, Mp); }));
    if (i % 2) {
      s_lumped();
      full();
    } else {
      full();
      s_lumped();
    }
  }
  const AssemblyMs ours{median(t_full), median(t_sl)};
  std::string rounds;
  for (int i = 0; i < reps; ++i) rounds += fmt::format(" {:.0f}/{:.0f}", t_full[size_t(i)], t_sl[size_t(i)]);
  std::fprintf(stderr, "  %s rounds, ms S+M+lumped/S+lumped:%s\n", name.c_str(), rounds.c_str());
  const std::string check = fmt::format("|S - S_plain| / |S| = {:.1e}, |M - M_plain| / |M| = {:.1e}",
                                        relative_difference(L.S, Sp), relative_difference(L.M, Mp));
  add({"assembly S+M+lumped, 1 thread", name, "plain build() (S+M)", "refine + pattern + values",
       median(t_plain), ours.full, 0, 25, check});
  const Eigen::VectorXd rows = L.M * Eigen::VectorXd::Ones(mesh.n_vertices());
  add({"assembly S+lumped, 1 thread", name, "ours, S+M+lumped (same rounds)",
       "refine + pattern + values (no M)", ours.full, ours.s_lumped, 0, 0,
       fmt::format("S bitwise as with M: {}; max |lumped - M 1| / max |M 1| = {:.1e}", same_bits(Ls.S, L.S),
                   (Ls.M_lumped - rows).cwiseAbs().maxCoeff() / rows.cwiseAbs().maxCoeff())});
  // The same with the sparsity pattern kept (virtual vertices and values recomputed).
  const FacePattern fp = face_pattern(mesh);
  const auto [plain2, kept] = interleaved(reps, [&] { plain_surface_reference::build(input, Sp, Mp); },
                                          [&] { reassemble_laplacian(mesh, refine(mesh), fp, {}, L); });
  add({"assembly, pattern kept", name, "plain build() (S+M)", "refine + values", plain2, kept, 0, 0, ""});
  return ours;
}

// pmp-library 3.0 (built from source at -O3, one thread) assembling S and the lumped mass of
// cube_sphere(500), recorded beside polydec's 1557 ms (S+M+lumped, main b1ae48f) on another
// session's 2-core machine, medians of 5 interleaved rounds. A ratio against a recorded constant
// depends on the machine; the note gives our S+M+lumped against the 1557 ms recorded with it.
constexpr double kPmpQuad1500kMs = 8392, kPolydecQuad1500kMs = 1557;

// Compares pmp's S + lumped mass with ours on the same parts.
void add_pmp_row(const std::string& name, const AssemblyMs& ours) {
  add({"assembly S+lumped vs pmp (recorded)", name, "pmp-library 3.0 -O3, S+lumped (recorded constant)",
       "refine + pattern + values (S+lumped)", kPmpQuad1500kMs, ours.s_lumped, 0, 10,
       fmt::format(
           "recorded constant: pmp-library {:.0f} ms for S and the lumped mass, beside polydec {:.0f} ms "
           "for S+M+lumped on b1ae48f (another machine; the ratio depends on the machine); ours: S+lumped, "
           "the same parts as pmp; our S+M+lumped here {:.0f} ms = {:.2f}x pmp, {:.2f} x the recorded {:.0f} "
           "ms",
           kPmpQuad1500kMs, kPolydecQuad1500kMs, ours.full, kPmpQuad1500kMs / ours.full,
           ours.full / kPolydecQuad1500kMs, kPolydecQuad1500kMs)});
}

// The machine's load average (other processes compete for the cores in wall-time rows).
std::string load_note() {
  std::ifstream in("/proc/loadavg");
  double l1 = 0;
  in >> l1;
  return fmt::format(" (load average {:.1f})", l1);
}

void bench_threads(const std::string& name, const Mesh& mesh, int reps) {
  const int T = std::max(2, int(std::thread::hardware_concurrency()));
  const Refinement r = refine(mesh);
  const FacePattern fp = face_pattern(mesh, T);  // with the threads' face patches
  Laplacian L1, LT;
  const auto [one, many] = interleaved(reps, [&] { reassemble_laplacian(mesh, r, fp, {}, L1, {1}); },
                                       [&] { reassemble_laplacian(mesh, r, fp, {}, LT, {T}); }, true);
  // Process CPU time of both: with the cores to itself, T threads would take about
  // (CPU time with T threads) / T of wall time; the ratio below is the parallel overhead.
  std::vector<double> c1, cT;
  for (int i = 0; i < reps; ++i) {
    c1.push_back(process_cpu_ms([&] { reassemble_laplacian(mesh, r, fp, {}, L1, {1}); }));
    cT.push_back(process_cpu_ms([&] { reassemble_laplacian(mesh, r, fp, {}, LT, {T}); }));
  }
  const double overhead = median(cT) / median(c1);
  const bool same = same_bits(L1.S, LT.S) && same_bits(L1.M, LT.M) &&
                    std::memcmp(L1.M_lumped.data(), LT.M_lumped.data(), sizeof(double) * L1.M_lumped.size()) == 0;
  add({fmt::format("values S+M+lumped, {} threads", T), name, "same, 1 thread", fmt::format("{} threads", T), one, many,
       0, 1.7,
       std::string(same ? "bitwise identical to 1 thread" : "RESULTS DIFFER") + "; wall time" + load_note() +
           fmt::format("; CPU time {} threads / 1 thread = {:.2f}, so {:.2f}x on {} idle cores", T, overhead,
                       T / overhead, T)});
  const auto [full1, fullT] =
      interleaved(reps, [&] { take(L1, assemble_all(mesh, 1)); }, [&] { take(LT, assemble_all(mesh, T)); }, true);
  add({fmt::format("full assembly, {} threads", T), name, "same, 1 thread", "refine and values threaded", full1,
       fullT, 0, 0, "wall time" + load_note()});
}

void bench_reassembly(const std::string& name, const Mesh& mesh, int reps) {
  // Moved vertices: a smooth radial displacement of 1% (one smoothing-like step).
  Eigen::MatrixX3d P = mesh.positions();
  for (int v = 0; v < P.rows(); ++v) P.row(v) *= 1.0 + 0.01 * std::sin(3.0 * P(v, 0) + 2.0 * P(v, 1));
  const Mesh moved = mesh.with_positions(P);
  const LaplacianParts only_M{false, true, false};
  const FacePattern fp = face_pattern(mesh);
  Laplacian first, again = assemble_laplacian(mesh, refine(mesh), only_M, &fp);
  const auto [first_ms, re_ms] = interleaved(
      reps, [&] { take(first, assemble_laplacian(moved, refine(moved), only_M)); },
      [&] { reassemble_laplacian(moved, refine(moved), fp, only_M, again); });
  add({"re-assembly of M, moved vertices", name, "first assembly of M", "pattern and storage kept", first_ms, re_ms, 0, 2,
       same_bits(first.M, again.M) ? "bitwise equal to first assembly" : "RESULTS DIFFER"});
}

long status_kb(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::stol(line.substr(std::strlen(key)));
  return -1;
}

// In a fresh process: RSS before the mesh, with the mesh, and the peak during one assembly.
int memory_child(int n) {
  malloc_trim(0);
  const long rss0 = status_kb("VmRSS:");
  const Mesh mesh = cube_sphere(n);
  malloc_trim(0);
  const long rss_mesh = status_kb("VmRSS:");
  { std::ofstream("/proc/self/clear_refs") << "5"; }  // reset the peak (VmHWM) to the current RSS
  const long hwm_reset = status_kb("VmHWM:");
  const Laplacian L = assemble_all(mesh, 1);
  const long hwm = status_kb("VmHWM:");
  const double matrices = double(L.S.nonZeros() + L.M.nonZeros()) * (sizeof(double) + sizeof(int)) +
                          2.0 * (L.S.outerSize() + 1) * sizeof(int) + double(L.M_lumped.size()) * sizeof(double);
  std::printf("%d %ld %ld %ld %ld %.0f\n", mesh.n_faces(), rss0, rss_mesh, hwm_reset, hwm, matrices / 1024.0);
  return 0;
}

void bench_memory(const std::string& self, int n) {
  const std::string cmd = self + " --memory-child " + std::to_string(n);
  FILE* p = popen(cmd.c_str(), "r");
  long faces = 0, rss0 = 0, rss_mesh = 0, hwm_reset = 0, hwm = 0;
  double matrices_kb = 0;
  const int got = p ? std::fscanf(p, "%ld %ld %ld %ld %ld %lf", &faces, &rss0, &rss_mesh, &hwm_reset, &hwm, &matrices_kb) : 0;
  if (p) pclose(p);
  if (got != 6) {
    add({"peak memory", "quad sphere", "", "", 0, 0, 0, 0, "memory child failed"});
    return;
  }
  const double mesh_kb = double(rss_mesh - rss0), peak_kb = double(hwm - rss0);
  Row r{"peak memory / (matrices + mesh)", fmt::format("{}k quads", faces / 1000), "matrices + mesh (MB)",
        "peak RSS above start (MB)", (matrices_kb + mesh_kb) / 1024, peak_kb / 1024, 0, 0,
        fmt::format("mesh {:.0f} MB, matrices {:.0f} MB, peak {:.0f} MB; target ratio <= 2.5", mesh_kb / 1024,
                    matrices_kb / 1024, peak_kb / 1024)};
  r.ratio = peak_kb / (matrices_kb + mesh_kb);  // lower is better here
  r.required = -2.5;                             // negative: upper bound
  add(r);
}

std::string blas_libraries() {
  std::ifstream in("/proc/self/maps");
  std::string line;
  std::set<std::string> libs;
  while (std::getline(in, line)) {
    const auto slash = line.find('/');
    if (slash == std::string::npos) continue;
    const std::string path = line.substr(slash);
    if (path.find("blas") != std::string::npos || path.find("lapack") != std::string::npos) libs.insert(path);
  }
  std::string s;
  for (const auto& l : libs) s += (s.empty() ? "" : ", ") + l;
  return s.empty() ? "none mapped" : s;
}

void bench_cholesky(const std::string& name, const Laplacian& L, int reps) {
  const SparseMatrix A = L.M - 0.1 * L.S;
  Eigen::SimplicialLLT<SparseMatrix> llt;
  llt.analyzePattern(A);
  std::vector<double> t_llt;
  for (int i = 0; i < reps; ++i) t_llt.push_back(time_ms([&] { llt.factorize(A); }));
  Eigen::SimplicialLDLT<SparseMatrix> ldlt;
  ldlt.analyzePattern(A);
  std::vector<double> t_ldlt;
  for (int i = 0; i < reps; ++i) t_ldlt.push_back(time_ms([&] { ldlt.factorize(A); }));
  add({"numeric Cholesky, Eigen LDLT", name, "Eigen SimplicialLLT", "Eigen SimplicialLDLT (fallback)", best(t_llt),
       best(t_ldlt), 0, 0, "best of " + std::to_string(reps) + ", thread CPU time (1 BLAS thread)"});
  if (!SparseCholesky::cholmod_available()) {
    add({"numeric Cholesky, CHOLMOD", name, "", "", 0, 0, 0, 2, "CHOLMOD not compiled in"});
    return;
  }
  // One solve with the default supernodes (as the heat method factors) per ordering, interleaved
  // with AMD's: every solve reads the whole factor, so fill is solve time.
  std::vector<std::unique_ptr<SparseCholesky>> solvers;
  for (auto ord : {CholeskyOrdering::Amd, CholeskyOrdering::Metis, CholeskyOrdering::NestedDissection}) {
    std::unique_ptr<SparseCholesky> chol;
    const double first = time_ms([&] { chol = std::make_unique<SparseCholesky>(A, "M - 0.1 S", CholeskyOptions{CholeskyBackend::Cholmod, ord}); });
    std::vector<double> t;
    for (int i = 0; i < reps; ++i) t.push_back(time_ms([&] { chol->refactor(A); }));
    // Interleave one more LLT run so that both sides see the same machine state.
    t_llt.push_back(time_ms([&] { llt.factorize(A); }));
    add({"numeric Cholesky, CHOLMOD " + chol->ordering(), name, "Eigen SimplicialLLT", "CHOLMOD supernodal refactor",
         best(t_llt), best(t), 0, ord == CholeskyOrdering::Amd ? 2.0 : 0.0,
         fmt::format("nnz(L) {:.2f}M; analysis + first factorization {:.0f} ms; thread CPU time", chol->factor_nonzeros() / 1e6, first)});
    CholeskyOptions exact{CholeskyBackend::Cholmod, ord};
    exact.relaxed_supernodes = false;
    solvers.push_back(std::make_unique<SparseCholesky>(A, "M - 0.1 S", exact));
  }
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 1.0);
  std::vector<std::vector<double>> t_solve(solvers.size());
  for (int i = 0; i < 3 * reps; ++i)
    for (size_t k = 0; k < solvers.size(); ++k) t_solve[k].push_back(time_ms([&] { (void)solvers[k]->solve(b); }));
  for (size_t k = 1; k < solvers.size(); ++k)
    add({"one solve, CHOLMOD " + solvers[k]->ordering(), name, "AMD", solvers[k]->ordering(), median(t_solve[0]),
         median(t_solve[k]), 0, 0,
         fmt::format("default supernodes; nnz(L) {:.2f}M against AMD's {:.2f}M; median of {}, interleaved; thread CPU time",
                     solvers[k]->factor_nonzeros() / 1e6, solvers[0]->factor_nonzeros() / 1e6, 3 * reps)});
}

// --gc-like-simplicial: the geometry-central-like path's factors simplicial on every mesh (default:
// supernodal from kGcLikeSupernodalVertices vertices on).
bool gc_like_always_simplicial = false;
// CHOLMOD's simplicial factorization of the 1.5M-quad sphere's two matrices took 208 s of thread CPU
// time (361 s wall; the big geodesics section 11.5 min), so meshes this large get supernodal factors.
constexpr int kGcLikeSupernodalVertices = 500000;

// polydec's HeatGeodesics against the geometry-central-like path of bench/gc_like_heat.cpp (a stand-in
// for geometry-central's PolygonMeshHeatSolver, written here), per source, timed interleaved on the
// same sources: ratio = reference / ours, target 2 (ours at most half). The note carries the
// reference's precomputation, its factors' size and, as a sanity check only (two discretizations),
// the largest difference between the two fields where ours is resolved (HeatDiagnostics), relative
// to the largest distance there.
void bench_gc_like_heat(const std::string& name, const Mesh& mesh, const HeatGeodesics& heat, int n_sources) {
  const std::string target = "heat geodesics per source vs geometry-central-like path (timed)";
#ifdef POLYDEC_HAVE_GC_LIKE_HEAT
  // Simplicial, as geometry-central factors, except on very large meshes (see above).
  const bool supernodal = !gc_like_always_simplicial && mesh.n_vertices() >= kGcLikeSupernodalVertices;
  std::unique_ptr<gc_like_heat::GcLikeHeat> ref;
  double pre_wall = 0;
  const double pre = time_ms([&] {
    pre_wall = wall_ms([&] { ref = std::make_unique<gc_like_heat::GcLikeHeat>(mesh, supernodal); });
  });
  std::vector<double> tref, tours;
  double diff = 0, dmax = 0;
  int unresolved = 0;
  for (int i = 0; i < n_sources; ++i) {
    const int s = int((long(i) * 7919 * 104729) % mesh.n_vertices());
    Eigen::VectorXd a, b;
    tref.push_back(time_ms([&] { b = ref->distance(s); }));
    tours.push_back(time_ms([&] { a = heat.distance(s); }));
    // Compared where ours resolves the heat step (beyond ~650 edge lengths both fields are noise).
    HeatDiagnostics diagnostics;
    (void)heat.distance(std::span<const int>(&s, 1), &diagnostics);
    unresolved = std::max(unresolved, diagnostics.unresolved_vertices);
    for (Eigen::Index v = 0; v < a.size(); ++v)
      if (a[v] <= diagnostics.resolved_radius) {
        diff = std::max(diff, std::abs(a[v] - b[v]));
        dmax = std::max(dmax, a[v]);
      }
  }
  std::string note = fmt::format(
      "ratio = reference / ours, median of {} sources each, interleaved, thread CPU time; reference: de Goes et al. "
      "operators (lambda 1), CHOLMOD {} of M + tL and L (one vertex pinned; long interface, default orderings), "
      "dense solves; its precomputation {:.0f} ms thread CPU ({:.0f} ms wall), factors {:.1f}M non-zeros together; "
      "max |difference| of the fields {:.1f}% of the max distance {:.3g} (two discretizations: a sanity check only)",
      n_sources, ref->supernodal() ? "supernodal LL^T (simplicial LDL^T too slow here)" : "simplicial LDL^T", pre,
      pre_wall, ref->factor_nonzeros() / 1e6, 100 * diff / dmax, dmax);
  if (unresolved > 0)
    note += fmt::format(" over the vertices ours resolves (up to {} unresolved per source)", unresolved);
  if (name == "FINE SPHERE") {
    // Recorded, see the rows "per source vs geometry-central" and "precomputation vs geometry-central".
    constexpr double kGeometryCentralMs = 23.5, kGeometryCentralTotalMs = 2570;
    note += fmt::format("; calibration: the reference's {:.1f} ms per source against geometry-central's recorded "
                        "23.5 ms ({:.2f}x), its precomputation + first source {:.0f} ms wall against the recorded "
                        "2570 ms ({:.2f}x)",
                        median(tref), median(tref) / kGeometryCentralMs, pre_wall + tref[0],
                        (pre_wall + tref[0]) / kGeometryCentralTotalMs);
  }
  add({target, name, "geometry-central-like (timed)", "HeatGeodesics::distance", median(tref), median(tours), 0, 2,
       note});
#else
  (void)mesh, (void)heat, (void)n_sources;
  add({target, name, "", "", 0, 0, 0, 0, "skipped: built without CHOLMOD"});
#endif
}

void bench_geodesics(const std::string& name, const Mesh& mesh, int n_sources) {
  // The operator set alone (S, M, lumped M, G, D), to split the precomputation.
  std::unique_ptr<OperatorSet> ops;
  const double ops_ms = time_ms([&] { ops.reset(new OperatorSet(build_operators(mesh, parse_laplacian("ours")))); });
  ops.reset();
  // The precomputation three times, wall time (what a user waits for; CHOLMOD's own threads
  // included): the first in this process is reported apart, the median of the three is the row.
  std::unique_ptr<HeatGeodesics> heat;
  // The last one's thread CPU time is the per-source row's precomputation.
  std::vector<double> pre_wall;
  double pre = 0;
  for (int i = 0; i < 3; ++i) {
    heat.reset();
    pre = time_ms([&] { pre_wall.push_back(wall_ms([&] { heat.reset(new HeatGeodesics(mesh)); })); });
  }
  std::vector<double> t;
  for (int i = 0; i < n_sources; ++i) {
    const int s = int((long(i) * 7919 * 104729) % mesh.n_vertices());
    t.push_back(time_ms([&] { heat->distance(s); }));
  }
  Row r{"heat geodesics per source", name, "precomputation", "one source", pre, median(t), 0, 0,
        fmt::format("{:.1f} ms per source (median of {}); ratio = precomputation / per source; precomputation = operator "
                    "set {:.0f} ms (measured separately) + two CHOLMOD factorizations and the rest; thread CPU time; "
                    "{:.0f} minor page faults per source",
                    median(t), n_sources, ops_ms, minor_faults([&] { heat->distance(0); }))};
  add(r);
  if (name == "FINE SPHERE") {
    // geometry-central's PolygonMeshHeatSolver on FINE SPHERE in all (operators, factorizations and
    // the first solve: 2.57 s, issue 33), a recorded constant; ours without the first solve.
    constexpr double kGeometryCentralTotalMs = 2570;
    add({"heat geodesics precomputation vs geometry-central", name, "geometry-central in all (recorded)",
         "HeatGeodesics(mesh)", kGeometryCentralTotalMs, median(pre_wall), 0, 2,
         fmt::format("operators + both factorizations, wall time, median of 3 in one process (runs {:.0f}, {:.0f}, "
                     "{:.0f} ms; the first is the process's first); geometry-central's 2570 ms is a constant recorded "
                     "in issue 33 (operators, factorizations and first solve, beside polydec's 2310 ms then on main "
                     "b1ae48f), not timed here: the ratio depends on the machine and its load",
                     pre_wall[0], pre_wall[1], pre_wall[2])});
    // geometry-central's PolygonMeshHeatSolver per further source on FINE SPHERE, a recorded constant
    // (not timed here): so the ratio depends on this machine's speed and load against that run's.
    constexpr double kGeometryCentralMs = 23.5;
    add({"heat geodesics per source vs geometry-central", name, "geometry-central (recorded)", "one source",
         kGeometryCentralMs, median(t), 0, 2,
         "geometry-central's 23.5 ms is a constant recorded in issue 33 (measured 2026-11 on main b1ae48f, one thread, "
         "beside polydec's 38.5 ms then), not timed in this run: the ratio depends on the machine and its load; "
         "ours: the median above, thread CPU time"});
  }
  bench_gc_like_heat(name, mesh, *heat, n_sources);
  // The face-wise gradient-normalization-divergence pass against the route through G and D, with
  // the same factors (an operator set without its refinement keeps the matrices), interleaved.
  {
    OperatorSet named = build_operators(mesh, parse_laplacian("ours"));
    named.refinement.reset();
    const HeatGeodesics by_matrices(std::move(named), mesh.mean_edge_length());
    std::vector<double> tm, tf;
    double diff = 0, dmax = 0;
    for (int i = 0; i < n_sources; ++i) {
      const int s = int((long(i) * 7919 * 104729) % mesh.n_vertices());
      Eigen::VectorXd a, b;
      tm.push_back(time_ms([&] { b = by_matrices.distance(s); }));
      tf.push_back(time_ms([&] { a = heat->distance(s); }));
      diff = std::max(diff, (a - b).cwiseAbs().maxCoeff());
      dmax = std::max(dmax, b.maxCoeff());
    }
    add({"heat geodesics per source, face-wise pass", name, "through G and D", "face by face", median(tm), median(tf), 0,
         0,
         fmt::format("median of {}, interleaved, same factors; max |difference| {:.1e} (distances up to {:.3g}); "
                     "thread CPU time",
                     n_sources, diff, dmax)});
  }
  // The heat step's solve for one source: the dense right-hand side against the sparse one (the
  // forward solve over the source's reach only), on the heat matrix factored as HeatGeodesics does.
  {
    const OperatorSet o = build_operators(mesh, parse_laplacian("ours"), false);
    const double h = mesh.mean_edge_length();
    SparseMatrix Ml(o.M_lumped.size(), o.M_lumped.size());
    Ml.setIdentity();
    Ml.diagonal() = o.M_lumped;
    CholeskyOptions copt;
    copt.relaxed_supernodes = false;
    copt.ordering = CholeskyOrdering::BestFill;
    const SparseCholesky chol(SparseMatrix(Ml - h * h * o.S), "M - t S", copt);
    std::vector<double> td, ts, tdist, rest;
    double diff = 0, xmax = 0;
    for (int i = 0; i < n_sources; ++i) {
      const int s = int((long(i) * 7919 * 104729) % mesh.n_vertices());
      Eigen::VectorXd b = Eigen::VectorXd::Zero(o.M_lumped.size()), xd, xs;
      b[s] = o.M_lumped[s];
      const std::vector<int> rows{s};
      const std::vector<double> values{o.M_lumped[s]};
      if (i == 0) (void)chol.solve_sparse(rows, values);  // its workspace, made once
      td.push_back(time_ms([&] { xd = chol.solve(b); }));
      ts.push_back(time_ms([&] { xs = chol.solve_sparse(rows, values); }));
      tdist.push_back(time_ms([&] { heat->distance(s); }));
      rest.push_back(tdist.back() - td.back() - ts.back());
      diff = std::max(diff, (xs - xd).cwiseAbs().maxCoeff());
      xmax = std::max(xmax, xd.cwiseAbs().maxCoeff());
    }
    add({"heat step, one source: sparse right-hand side", name, "dense solve", "solve_sparse", median(td), median(ts),
         0, 0,
         fmt::format("median of {}, interleaved, one factor (nnz(L) {:.2f}M); forward solve over the source's reach, "
                     "backward solve over the whole factor; max |difference| {:.1e} (solution up to {:.3g}); "
                     "thread CPU time",
                     n_sources, chol.factor_nonzeros() / 1e6, diff, xmax)});
    // Where one source's time goes: distance() against its two solves (the heat step's sparse one and
    // a dense one for the Poisson step, which has the same pattern and analysis), timed in the same
    // iterations; the rest (right-hand sides, the face-wise pass, the shift) by subtraction per
    // iteration.
    add({"heat geodesics per source: the rest", name, "distance()", "all but the two solves", median(tdist),
         median(rest), 0, 0,
         fmt::format("by subtraction per iteration: distance() - heat step (solve_sparse) - one dense solve (the "
                     "Poisson step's), median of {} ({:.2f} ms; medians of the three: {:.2f}, {:.2f}, {:.2f} ms); "
                     "thread CPU time",
                     n_sources, median(rest), median(tdist), median(ts), median(td))});
    // What the solves cannot go below on this machine: one source streams the heat factor once (its
    // backward solve; the forward one covers the source's reach only) and the Poisson factor twice,
    // each at least nnz(L) doubles. Two arrays of nnz(L) doubles (together beyond the L3 cache, as
    // the two factors are), read as one source reads its factors (vectorized sums, huge pages),
    // median of 9; the row indices and CHOLMOD's explicit zeros come on top.
    const size_t lnz = size_t(chol.factor_nonzeros());
    const auto heat_values = uninitialized_on_huge_pages<double>(lnz);
    const auto poisson_values = uninitialized_on_huge_pages<double>(lnz);
    for (size_t k = 0; k < lnz; ++k) heat_values[k] = poisson_values[k] = 1.0 / double(k + 1);
    auto read = [&](const std::unique_ptr<double[]>& a) {
      return Eigen::Map<const Eigen::VectorXd>(a.get(), Eigen::Index(lnz)).sum();
    };
    std::vector<double> tread;
    double sink = 0;
    for (int i = 0; i < 9; ++i)
      tread.push_back(time_ms([&] { sink += read(heat_values) + read(poisson_values) + read(poisson_values); }));
    const double floor_ms = median(tread);
    add({"heat geodesics per source: memory floor", name, "target (half of geometry-central's 23.5 ms)",
         "heat factor once, Poisson factor twice", 11.75, floor_ms, 0, 0,
         fmt::format("three reads of {:.2f}M doubles, two arrays: {:.2f} ms ({:.1f} GB/s; median of 9, thread CPU time; "
                     "sum {:.3f}); against the two solves timed above ({:.2f} + {:.2f} ms): what the solves take beyond "
                     "streaming their values is not bandwidth",
                     lnz / 1e6, floor_ms, 24e-6 * double(lnz) / floor_ms, sink / 27, median(ts), median(td))});
  }
  // One field per source for 64 sources at once (blocks of right-hand sides), against the single
  // source median above, re-timed interleaved with it. Target: at most a quarter per source.
  std::vector<int> many;
  for (int i = 0; i < 64; ++i) many.push_back(int((long(i) * 104729 + 17) % mesh.n_vertices()));
  // Also into a caller's matrix, reused from call to call (HeatGeodesics::distances(sources, out)):
  // a new |V| x 64 result is fresh memory at every call (768 MB on 1.5M quads).
  Eigen::MatrixXd D, into(heat->operators().n_input_vertices, 64);
  std::vector<double> single, block, block_into;
  for (int round = 0; round < 3; ++round) {
    single.push_back(time_ms([&] { heat->distance(many[size_t(round)]); }));
    block.push_back(time_ms([&] { D = heat->distances(many); }) / 64);
    block_into.push_back(time_ms([&] { heat->distances(many, into); }) / 64);
  }
  double diff = 0;
  for (int c = 0; c < 64; c += 21) diff = std::max(diff, (D.col(c) - heat->distance(many[size_t(c)])).cwiseAbs().maxCoeff());
  Row m{"heat geodesics, 64 sources at once", name, "one source", "per source of 64 (distances)", median(single),
        median(block), 0, 4,
        fmt::format("median of 3 rounds each; max |difference| to one-by-one {:.1e} (distances up to {:.3g}); thread "
                    "CPU time; {:.0f} minor page faults per call of distances(64)",
                    diff, D.col(0).maxCoeff(), minor_faults([&] { D = heat->distances(many); }))};
  add(m);
  add({"heat geodesics, 64 sources at once, into a caller's matrix", name, "one source",
       "per source of 64 (distances into a reused matrix)", median(single), median(block_into), 0, 4,
       fmt::format("median of 3 rounds each, interleaved with the row above; the same bits as it: {}; thread CPU "
                   "time; {:.0f} minor page faults per call",
                   into == D ? "yes" : "no", minor_faults([&] { heat->distances(many, into); }))});
}

// FEEC: the coarse Hodge star star1 (dec/surface/hodge_star.h) against the stiffness S, both from the
// same refinement, each including its own sparsity structure (the cell complex, like the
// refinement, is built once outside the timing).
void bench_feec(const std::string& name, const Mesh& mesh, int reps) {
  const Refinement r = refine(mesh);
  const CoarseComplex complex(mesh);
  SparseMatrix st1;
  Laplacian L;
  const auto [s_ms, star_ms] = interleaved(
      reps, [&] { take(L, assemble_laplacian(mesh, r, {true, false, false})); },
      [&] {
        SparseMatrix fresh = star1(mesh, r, complex);
        st1.swap(fresh);  // not `st1 = star1(...)`: a deep copy (no move assignment in Eigen 3.4)
      });
  Row row{"FEEC star1 vs S", name, "S (pattern + values)", "star1", s_ms, star_ms, 0, 0,
          fmt::format("ratio = star1 time / S time (lower is better); star1 {} x {}, {} non-zeros = {:.2f}x those of S "
                      "({}); time per non-zero: star1 {:.1f} ns, S {:.1f} ns",
                      st1.rows(), st1.cols(), st1.nonZeros(), double(st1.nonZeros()) / L.S.nonZeros(),
                      L.S.nonZeros(), 1e6 * star_ms / st1.nonZeros(), 1e6 * s_ms / L.S.nonZeros())};
  row.ratio = star_ms / s_ms;
  row.required = -3;
  add(row);
}

// The mesh complex's star1 (dec/surface/mesh_complex.h, on the mesh edges) against the complete
// complex's (all vertex pairs of a face), from the same refinement, each with its own structure.
// Target (HEX SPHERE, with_target): less time with at most a third of the non-zeros.
void bench_mesh_star1(const std::string& name, const Mesh& mesh, int reps, bool with_target) {
  const Refinement r = refine(mesh);
  SparseMatrix complete, native;
  const auto [complete_ms, native_ms] = interleaved(
      reps,
      [&] {
        SparseMatrix fresh = star1(mesh, r, CoarseComplex(mesh));
        complete.swap(fresh);
      },
      [&] {
        SparseMatrix fresh = mesh_star1(mesh, r);
        native.swap(fresh);
      });
  Row row{"mesh-complex star1 vs complete", name, "complete complex star1 (with its complex)", "mesh complex star1",
          complete_ms, native_ms, 0, with_target ? 1.0 : 0.0,
          fmt::format("non-zeros: mesh {} ({} x {}) = {:.3f}x the complete complex's {} ({} x {}){}",
                      native.nonZeros(), native.rows(), native.cols(), double(native.nonZeros()) / complete.nonZeros(),
                      complete.nonZeros(), complete.rows(), complete.cols(),
                      with_target ? "; target: faster and <= 1/3 of the non-zeros" : "")};
  if (with_target && 3 * native.nonZeros() > complete.nonZeros()) row.required = 0, row.note += " (non-zero target MISSED)";
  add(row);
}

void bench_spectrum(const std::string& name, const Mesh& mesh, int reps) {
  const OperatorSet ops = build_operators(mesh, parse_laplacian("ours"), false);
  SpectrumOptions o;
  o.k = 50;
  Spectrum ours;
  Eigen::VectorXd base;
  long base_solves = 0;
  const int ncv = spectrum_krylov_size(o.k, int(ops.S.rows()));
  std::fprintf(stderr, "  spectrum: Krylov size %d\n", ncv);
  const auto [base_ms, ours_ms] = interleaved(
      reps,
      [&] {
        // The baseline: Spectra's generalized shift-invert Lanczos driven by Eigen's SimplicialLDLT
        // of (-S - sigma M), same problem, shift, Krylov size and tolerance.
        SpectrumOptions ref = o;
        ref.reference = true;
        const Spectrum sp = laplacian_spectrum(ops, ref);
        base = sp.eigenvalues;
        base_solves = sp.n_solves;
      },
      [&] { ours = laplacian_spectrum(ops, o); });
  // Largest relative eigenvalue difference; the zero eigenvalue is compared relative to lambda_1.
  double diff = 0;
  for (int i = 0; i < o.k; ++i)
    diff = std::max(diff, std::abs(ours.eigenvalues[i] - base[i]) / std::max(std::abs(base[i]), base[1]));
  add({"spectrum, 50 eigenpairs", name, "Spectra + Eigen SimplicialLDLT shift-invert", "laplacian_spectrum",
       base_ms, ours_ms, 0, 1.5,
       fmt::format("tolerance {:g}, shift -{:g}/area; baseline ncv {} ({} solves); ours: {}; max relative eigenvalue "
                   "difference {:.1e}; thread CPU time (1 BLAS thread)",
                   o.tolerance, o.shift_factor, ncv, base_solves,
                   fmt::format("{}, {} solves", ours.method, ours.n_solves), diff)});
}

// 50 eigenpairs of the 1-form Hodge Laplacian (apps/applications/form_spectrum.h) against 50 of
// the 0-form spectrum, same mesh, one run each (ratio = 1-form time / 0-form time).
void bench_form_spectrum(const std::string& name, const Mesh& mesh) {
  SpectrumOptions o0;
  o0.k = 50;
  FormSpectrumOptions o1;
  o1.k = 50;
  o1.decompose = false;
  Spectrum zero;
  FormSpectrum one;
  const double t0 = time_ms([&] { zero = laplacian_spectrum(mesh, o0); });
  const double t1 = time_ms([&] { one = form_spectrum(mesh, o1); });
  // The exact 1-form eigenvalues are the 0-form ones: the largest distance of a nonzero 0-form
  // eigenvalue below the 1-form range to the nearest 1-form eigenvalue.
  double diff = 0;
  for (int i = 1; i < o0.k; ++i) {
    if (zero.eigenvalues[i] > one.eigenvalues[o1.k - 1]) break;
    diff = std::max(diff,
                    (one.eigenvalues.array() - zero.eigenvalues[i]).abs().minCoeff() / zero.eigenvalues[i]);
  }
  Row r{
      "1-form spectrum, 50 eigenpairs",
      name,
      "0-form spectrum (laplacian_spectrum)",
      "form_spectrum",
      t0,
      t1,
      0,
      0,
      fmt::format("ratio = 1-form time / 0-form time; {} faces, 1-form rank {}, {} solves (0-form: {}, {}); "
                  "nearest 1-form eigenvalue to each 0-form one within {:.1e} (relative); includes assembly; "
                  "thread CPU time (1 BLAS thread)",
                  mesh.n_faces(), one.rank, one.n_solves, zero.n_solves, zero.method, diff)};
  r.ratio = t1 / t0;
  add(r);
}

// Volume S + M + lumped M (refinement, pattern, values; one thread) against the plain volume
// reference (bench/plain_volume_reference.cpp, its own mesh copy built outside the timing).
// The two must agree: a relative difference above 1e-10 marks the row "RESULTS DIFFER".
void bench_volume(const std::string& name, const VolumeMesh& mesh, int reps) {
  const auto input = plain_volume_reference::from_volume_mesh(mesh);
  SparseMatrix Sp, Mp;
  VolumeLaplacian L;
  const auto [plain_ms, ours_ms] = interleaved(
      reps, [&] { plain_volume_reference::build(input, Sp, Mp); },
      [&] {
        VolumeLaplacian fresh = assemble_volume_laplacian(mesh, refine_volume(mesh));
        L.S.swap(fresh.S);
        L.M.swap(fresh.M);
        L.M_lumped.swap(fresh.M_lumped);
      });
  const double dS = relative_difference(L.S, Sp), dM = relative_difference(L.M, Mp);
  const bool agree = dS < 1e-10 && dM < 1e-10;
  add({"volume S+M+lumped, 1 thread", name, "plain volume build() (S+M)", "refine_volume + assemble_volume_laplacian",
       plain_ms, ours_ms, 0, 10,
       fmt::format("{}{} cells, {} vertices, nnz(S) {}; |S - S_plain| / |S| = {:.1e}, |M - M_plain| / |M| = {:.1e}; "
                   "median of {}, thread CPU time",
                   agree ? "" : "RESULTS DIFFER; ", mesh.n_cells(), mesh.n_vertices(), L.S.nonZeros(), dS, dM, reps)});
}

// Volume refinement + assembly with T threads against one thread (wall time), bitwise compared.
void bench_volume_threads(const std::string& name, const VolumeMesh& mesh, int reps) {
  const int T = std::max(2, int(std::thread::hardware_concurrency()));
  VolumeLaplacian L1, LT;
  auto run = [&](int threads, VolumeLaplacian& out) {
    VolumeRefinementOptions o;
    o.threads = threads;
    VolumeLaplacian fresh = assemble_volume_laplacian(mesh, refine_volume(mesh, o), nullptr, threads);
    out.S.swap(fresh.S);
    out.M.swap(fresh.M);
    out.M_lumped.swap(fresh.M_lumped);
  };
  // Alternating which goes first (1, T, T, 1, ...): the run after another one reuses the pages that
  // one just freed, which are cheaper to fault in than pages freed long ago on a virtual machine.
  // One untimed pair first, reported apart: within a process, whether a run gets memory just freed
  // (cheap) or memory the kernel has meanwhile handed back to the hypervisor (free page reporting:
  // ~12x dearer to touch again, bench/fresh_memory.cpp) depends on the kernel's timing; the first
  // pair is the most exposed (measured 0.87-1.08x, later pairs 1.3-2.9x). The row "fresh process"
  // times the first call of fresh processes instead (docs/benchmarks.md).
  std::vector<double> w1, wT, c1, cT;
  const std::string load_before = load_note();
  const double cold1 = wall_ms([&] { run(1, L1); }), coldT = wall_ms([&] { run(T, LT); });
  for (int i = 0; i < std::max(2, reps); ++i)
    for (int k = 0; k < 2; ++k) {
      const bool first_one = (k == 0) == (i % 2 == 0);
      std::vector<double>& w = first_one ? w1 : wT;
      std::vector<double>& c = first_one ? c1 : cT;
      timespec a, b;
      clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &a);
      w.push_back(wall_ms([&] { run(first_one ? 1 : T, first_one ? L1 : LT); }));
      clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &b);
      c.push_back((b.tv_sec - a.tv_sec) * 1e3 + (b.tv_nsec - a.tv_nsec) * 1e-6);
    }
  const bool same = same_bits(L1.S, LT.S) && same_bits(L1.M, LT.M) && L1.M_lumped == LT.M_lumped;
  add({fmt::format("volume S+M+lumped, {} threads", T), name, "same, 1 thread", fmt::format("{} threads", T),
       median(w1), median(wT), 0, mesh.n_cells() >= 1000000 ? 1.6 : 0,
       std::string(same ? "bitwise identical to 1 thread" : "RESULTS DIFFER") +
           fmt::format("; wall time, medians of {} in the order 1,T,T,1,...;{} at the start,{} at the end; process "
                       "CPU time {} threads / 1 thread = {:.2f}; untimed first pair {:.0f} / {:.0f} ms = {:.2f}x",
                       w1.size(), load_before, load_note(), T, median(cT) / median(c1), cold1, coldT,
                       cold1 / coldT)});
}

// The polydec side alone on hex_grid_volume(n^3), for `/usr/bin/time -v polydec_bench --volume-memory N`:
// prints RSS at start, with the mesh, and the peak (VmHWM) during refinement + assembly, and the
// bytes of S and M (nnz (8 + 4) + 4 (cols + 1) each) and of the lumped mass.
int volume_memory(int n) {
  malloc_trim(0);
  const long rss0 = status_kb("VmRSS:");
  const VolumeMesh mesh = hex_grid_volume(n, n, n);
  malloc_trim(0);
  const long rss_mesh = status_kb("VmRSS:");
  { std::ofstream("/proc/self/clear_refs") << "5"; }
  const long hwm_reset = status_kb("VmHWM:");
  const VolumeLaplacian L = assemble_volume_laplacian(mesh, refine_volume(mesh));
  const long hwm = status_kb("VmHWM:");
  const double matrices = double(L.S.nonZeros() + L.M.nonZeros()) * (sizeof(double) + sizeof(int)) +
                          2.0 * (L.S.outerSize() + 1) * sizeof(int) + double(L.M_lumped.size()) * sizeof(double);
  const double mesh_kb = double(rss_mesh - rss0), peak_kb = double(hwm - rss0);
  std::printf("hex_grid_volume(%d^3): %d cells, %d vertices, nnz(S) = nnz(M) = %ld\n", n, mesh.n_cells(),
              mesh.n_vertices(), long(L.S.nonZeros()));
  std::printf("RSS at start %.0f MB, mesh %.0f MB (RSS growth while generating), matrices %.0f MB\n", rss0 / 1024.0,
              mesh_kb / 1024, matrices / 1024 / 1024);
  std::printf("peak RSS %.0f MB (%.0f MB when the peak was reset, after the mesh); peak above start / (matrices + "
              "mesh) = %.2f\n",
              hwm / 1024.0, hwm_reset / 1024.0, peak_kb / (matrices / 1024 + mesh_kb));
  return 0;
}

// Writes `mesh` in each format of `extensions` to a scratch folder and reads it back `reps` times
// with `read` (wall time), printing the medians; the files are removed afterwards.
template <class MeshType, class Write, class Read>
void time_reads(const MeshType& mesh, std::initializer_list<const char*> extensions, int reps, Write&& write,
                Read&& read) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("polydec_bench_read_{}", getpid());
  std::filesystem::create_directories(dir);
  for (const char* ext : extensions) {
    const std::string path = (dir / (std::string("mesh") + ext)).string();
    write(mesh, path);
    std::vector<double> t;
    long elements = 0;
    for (int r = 0; r < reps; ++r) t.push_back(wall_ms([&] { elements = read(path); }));
    std::printf("read %s (%.0f MB): median %.0f ms of %d, %ld elements\n", ext,
                double(std::filesystem::file_size(path)) / 1e6, median(t), reps, elements);
  }
  std::filesystem::remove_all(dir);
}

// Wall time of the next 64 MB allocation: what glibc's consolidation of the small blocks a mesh
// build left behind costs the call after it.
double next_allocation_ms() {
  const auto t = Clock::now();
  std::unique_ptr<char[]> large(new char[size_t(64) << 20]);
  char* volatile escaped = large.get();  // a real allocation, not one the compiler may elide
  (void)escaped;
  return ms_since(t);
}

// `--volume-read N [R]` and `--surface-read N [R]`: building a large mesh, as a user waits for it.
// Wall time of hex_grid_volume(N^3) or cube_sphere(N) (the first call of the process) and of the
// next large allocation, then R rounds (default 3) of reading the mesh back from each format
// (medians). With LD_LIBRARY_PATH pointing at another build's libraries, the same binary times that
// build (docs/benchmarks.md).
int volume_read(int n, int reps) {
  const auto t0 = Clock::now();
  const VolumeMesh grid = hex_grid_volume(n, n, n);
  const double generate = ms_since(t0);
  std::printf("hex_grid_volume(%d^3): %d cells, %d faces; %.0f ms; the next 64 MB allocation %.1f ms\n", n,
              grid.n_cells(), grid.n_faces(), generate, next_allocation_ms());
  time_reads(
      grid, {".vtu", ".vtk", ".msh"}, reps, [](const VolumeMesh& m, const std::string& p) { write_volume_mesh(m, p); },
      [](const std::string& p) { return long(read_volume_mesh(p).n_cells()); });
  return 0;
}

int surface_read(int n, int reps) {
  const auto t0 = Clock::now();
  const Mesh sphere = cube_sphere(n);
  const double generate = ms_since(t0);
  std::printf("cube_sphere(%d): %d faces; %.0f ms; the next 64 MB allocation %.1f ms\n", n, sphere.n_faces(),
              generate, next_allocation_ms());
  time_reads(
      sphere, {".off", ".obj", ".ply"}, reps, [](const Mesh& m, const std::string& p) { write_mesh(p, m); },
      [](const std::string& p) { return long(read_mesh(p).n_faces()); });
  return 0;
}

// `--volume-phases N [R]`: R (default 2) repetitions of refine_volume, cell_pattern alone and
// assemble_volume_laplacian (pattern included) on hex_grid_volume(N^3), each with its wall, user
// and system time and page faults (getrusage), to see what first-touch page faults cost
// (POLYDEC_NO_HUGE_PAGES=1 for the comparison without huge pages).
int volume_phases(int n, int reps) {
  struct Stamp {
    double wall, user, sys;
    long faults;
  };
  auto now = [] {
    rusage r{};
    getrusage(RUSAGE_SELF, &r);
    return Stamp{std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(),
                 double(r.ru_utime.tv_sec) + 1e-6 * double(r.ru_utime.tv_usec),
                 double(r.ru_stime.tv_sec) + 1e-6 * double(r.ru_stime.tv_usec), r.ru_minflt};
  };
  auto print = [](const char* what, const Stamp& a, const Stamp& b) {
    std::printf("  %-40s wall %8.1f ms  user %8.1f ms  system %7.1f ms  page faults %ld\n", what,
                1e3 * (b.wall - a.wall), 1e3 * (b.user - a.user), 1e3 * (b.sys - a.sys), b.faults - a.faults);
  };
  const VolumeMesh mesh = hex_grid_volume(n, n, n);
  std::printf("hex_grid_volume(%d^3): %d cells; huge pages %s\n", n, mesh.n_cells(),
              std::getenv("POLYDEC_NO_HUGE_PAGES") ? "off (POLYDEC_NO_HUGE_PAGES)" : "advised");
  for (int r = 0; r < reps; ++r) {
    std::printf("repetition %d\n", r + 1);
    const Stamp a = now();
    const VolumeRefinement R = refine_volume(mesh);
    const Stamp b = now();
    const SparseMatrix pattern = cell_pattern(mesh);
    const Stamp c = now();
    const VolumeLaplacian L = assemble_volume_laplacian(mesh, R);
    const Stamp d = now();
    print("refine_volume", a, b);
    print("cell_pattern (alone)", b, c);
    print("assemble_volume_laplacian (pattern included)", c, d);
    if (L.S.nonZeros() != pattern.nonZeros()) return 1;
  }
  return 0;
}

// In a fresh process: hex_grid_volume(n^3), then one refine_volume + assemble_volume_laplacian on
// `threads` threads; prints its wall time (ms) and the bytes of S.
int volume_first_child(int n, int threads) {
  const VolumeMesh grid = hex_grid_volume(n, n, n);
  VolumeRefinementOptions o;
  o.threads = threads;
  long nnz = 0;
  const double ms =
      wall_ms([&] { nnz = assemble_volume_laplacian(grid, refine_volume(grid, o), nullptr, threads).S.nonZeros(); });
  std::printf("%.3f %ld\n", ms, nnz);
  return 0;
}

// A user's one-off volume assembly: each in a fresh process, as `polydec` runs it. One thread and T
// threads alternate, `rounds` processes each. Within one process, which run of a pair gets memory
// that the kernel has just handed back to the hypervisor (free page reporting) is decided by the
// kernel, not the thread count: in fresh processes every run starts from the same state.
void bench_volume_fresh_processes(const std::string& self, int n, int rounds) {
  const int T = std::max(2, int(std::thread::hardware_concurrency()));
  std::vector<double> w[2];
  bool ok = true;
  for (int r = 0; r < rounds; ++r)
    for (int k = 0; k < 2; ++k) {
      const int threads = (k == 0) == (r % 2 == 0) ? 1 : T;
      FILE* p = popen(fmt::format("{} --volume-first-child {} {}", self, n, threads).c_str(), "r");
      double ms = 0;
      long nnz = 0;
      ok = ok && p && std::fscanf(p, "%lf %ld", &ms, &nnz) == 2 && nnz > 0;
      if (p) ok = pclose(p) == 0 && ok;
      w[threads == 1 ? 0 : 1].push_back(ms);
    }
  const std::string name = fmt::format("hex grid {}^3", n);
  const std::string label = fmt::format("volume S+M+lumped, {} threads, fresh process", T);
  if (!ok) {
    add({label, name, "", "", 0, 0, 0, 0, "a child process failed"});
    return;
  }
  std::string each;
  for (int i = 0; i < rounds; ++i) each += fmt::format(" {:.0f}/{:.0f}", w[0][size_t(i)], w[1][size_t(i)]);
  add({label, name, "same, 1 thread, fresh process", fmt::format("{} threads", T), median(w[0]), median(w[1]), 0,
       n * n * n >= 1000000 ? 1.6 : 0,
       fmt::format("wall time of refine_volume + assemble_volume_laplacian, the first call of a process after "
                   "hex_grid_volume; medians of {} processes each, alternating; ms 1 thread / {} threads:{}",
                   rounds, T, each)});
}

// check_mesh (dec/mesh/mesh_checks.h) on a large mesh: the wall time of the process's first call,
// as the figure recorded for its previous version (a map of face cycles and dynamic-size SVDs) was
// taken, in alternating processes that generated the same mesh first; then the median of `reps`
// further calls.
void bench_mesh_checks(const std::string& name, const Mesh& mesh, int reps, double recorded_ms) {
  bool clean = false;
  const double first = wall_ms([&] { clean = check_mesh(mesh).clean(); });
  std::vector<double> t;
  for (int k = 0; k < reps; ++k) t.push_back(wall_ms([&] { check_mesh(mesh); }));
  add({"check_mesh, 1 thread", name, "previous check_mesh (recorded)", "check_mesh", recorded_ms, first, 0, 0,
       fmt::format("{} faces, clean {}; wall time of the first call of the process; recorded on 74efbfb: "
                   "2129 / 2145 / 2203 ms in three processes, 2026-12-07 00:50 UTC; later calls median {:.0f} ms of {}",
                   mesh.n_faces(), clean, median(t), reps)});
}

void bench_volumes(const std::string& self, int big, int reps) {
  std::fprintf(stderr, "volume assembly vs plain volume reference...\n");
  try {
    bench_volume("cube_hexahedron_4", read_volume_mesh(shared("volume/cube_hexahedron_4.ovm")), reps);
  } catch (const std::exception& e) {
    add({"volume S+M+lumped, 1 thread", "cube_hexahedron_4", "", "", 0, 0, 0, 0, std::string("skipped: ") + e.what()});
  }
  const VolumeMesh grid16 = hex_grid_volume(16, 16, 16);
  bench_volume("hex grid 16^3", grid16, reps);
  bench_volume_threads("hex grid 16^3", grid16, reps);
  if (big > 0) {
    std::fprintf(stderr, "generating hex_grid_volume(%d^3)...\n", big);
    const VolumeMesh grid = hex_grid_volume(big, big, big);
    bench_volume(fmt::format("hex grid {}^3", big), grid, 1);
    bench_volume_threads(fmt::format("hex grid {}^3", big), grid, 3);
    bench_volume_fresh_processes(self, big, 5);
  }
}

// Building a whole DEC bundle (d, P, stars) in a child process: wall ms of the build (the mesh
// generated before the clock starts) and the child's peak RSS above what it had after generating
// the mesh, so that each row's memory is its own. `build` returns a short description.
struct ChildRun {
  double ms = -1, peak_mb = -1;
  std::string what;
};
ChildRun in_child(const std::function<std::string()>& build) {
  int fd[2];
  if (pipe(fd) != 0) return {};
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    rusage before{};
    getrusage(RUSAGE_SELF, &before);
    std::string what;
    const double ms = wall_ms([&] { what = build(); });
    rusage after{};
    getrusage(RUSAGE_SELF, &after);
    const std::string msg = fmt::format("{} {} {}", ms, (after.ru_maxrss - before.ru_maxrss) / 1024.0, what);
    if (write(fd[1], msg.data(), msg.size()) < 0) _exit(1);
    _exit(0);
  }
  close(fd[1]);
  std::string text;
  char buf[512];
  for (ssize_t n; (n = read(fd[0], buf, sizeof buf)) > 0;) text.append(buf, size_t(n));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  ChildRun r;
  std::istringstream in(text);
  in >> r.ms >> r.peak_mb;
  std::getline(in, r.what);
  return r;
}

// d, P and the stars of the mesh complex (up to degree 2 on surfaces, 3 on volumes) against the
// complete complex where it runs: time and peak memory, each in its own process.
void bench_dec(bool with_big) {
  auto surface_row = [&](const std::string& name, const std::function<Mesh()>& make) {
    for (DecComplex complex : {DecComplex::Complete, DecComplex::Mesh}) {
      if (complex == DecComplex::Complete && name.rfind("QUAD", 0) == 0) continue;  // minutes and GBs
      const ChildRun r = in_child([&] {
        const Mesh mesh = make();
        const Refinement R = refine(mesh);
        const SurfaceDec D = surface_dec(mesh, R, {.max_degree = 2, .complex = complex});
        return fmt::format("{} faces; star1 {} x {} ({} nz), star2 {} nz", mesh.n_faces(), D.star[1].rows(),
                           D.star[1].cols(), D.star[1].nonZeros(), D.star[2].nonZeros());
      });
      add({"DEC bundle to degree 2, " + to_string(complex) + " complex", name, "", "surface_dec (refine included)", 0,
           r.ms, 0, 0, fmt::format("peak {:.0f} MB above the mesh;{}", r.peak_mb, r.what)});
    }
  };
  surface_row("HEX SPHERE", [] { return hex_sphere_mesh(); });
  if (with_big) surface_row("QUAD 1000k", [] { return cube_sphere(409); });
  auto volume_row = [&](const std::string& name, const std::function<VolumeMesh()>& make) {
    const ChildRun r = in_child([&] {
      const VolumeMesh mesh = make();
      const VolumeRefinement R = refine_volume(mesh);
      const VolumeDec D = volume_dec(mesh, R, VolumeDecOptions{.max_degree = 3, .complex = DecComplex::Mesh});
      return fmt::format("{} cells; star1 {} nz, star2 {} nz, star3 diagonal {}", mesh.n_cells(), D.star[1].nonZeros(),
                         D.star[2].nonZeros(), D.star[3].rows());
    });
    add({"DEC bundle to degree 3, mesh complex", name, "", "volume_dec (refine included)", 0, r.ms, 0, 0,
         fmt::format("peak {:.0f} MB above the mesh;{}", r.peak_mb, r.what)});
  };
  volume_row("hex grid 32^3", [] { return hex_grid_volume(32, 32, 32, {.amplitude = 0.2, .seed = 1}); });
  volume_row("Voronoi BCC n=17", [] { return truncated_octahedra_volume(17, {.amplitude = 0.15, .seed = 2}); });
  if (with_big) volume_row("hex grid 100^3", [] { return hex_grid_volume(100, 100, 100); });
}

// A process spinning on the CPU until killed (its pid; the caller kills exactly it).
pid_t spin() {
  const pid_t pid = fork();
  if (pid == 0) {
    volatile unsigned long x = 0;
    for (;;) x = x + 1;
  }
  return pid;
}

// One run of the CLI with a clean thread environment plus `env`: wall ms, or -1 with the exit
// status in `failure` when it does not succeed.
double cli_wall_ms(const std::string& cli, const std::string& env, const std::string& args, const std::string& dir,
                   std::string& failure) {
  const std::string cmd = "env -u OPENBLAS_NUM_THREADS -u OMP_NUM_THREADS -u POLYDEC_BLAS_THREADS " + env + " '" +
                          cli + "' " + args + " > '" + dir + "/stdout.txt' 2> '" + dir + "/stderr.txt'";
  int status = 0;
  const double ms = wall_ms([&] { status = std::system(cmd.c_str()); });
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return ms;
  failure = fmt::format("`{}` failed (status {})", cmd, status);
  return -1;
}

// The CLI's default BLAS policy (operators/solvers/cholesky.h: one thread) against a run forced to one
// BLAS thread, with two busy processes beside it: `polydec geodesics` on a 100k-vertex quad torus
// (CHOLMOD's supernodes large enough for BLAS-3 work), three runs each, interleaved, medians of
// wall time; one more run with OpenBLAS's own default (one thread per core) is reported.
void bench_blas_load(const std::string& cli) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("polydec_bench_blas_load_{}", getpid());
  std::filesystem::create_directories(dir);
  const Mesh mesh = torus(400, 250);
  write_mesh((dir / "torus.ply").string(), mesh);
  const std::string geo = "geodesics '" + (dir / "torus.ply").string() + "' --source 0 --json";
  const std::string load_before = load_note();
  std::string failure;
  std::vector<double> policy, one;
  const pid_t a = spin(), b = spin();
  for (int k = 0; k < 3 && failure.empty(); ++k) {
    policy.push_back(cli_wall_ms(cli, "", geo, dir.string(), failure));
    one.push_back(cli_wall_ms(cli, "OPENBLAS_NUM_THREADS=1", geo, dir.string(), failure));
  }
  const double all_cores = failure.empty() ? cli_wall_ms(cli, "POLYDEC_BLAS_THREADS=0", geo, dir.string(), failure) : -1;
  kill(a, SIGKILL);
  kill(b, SIGKILL);
  waitpid(a, nullptr, 0);
  waitpid(b, nullptr, 0);
  std::filesystem::remove_all(dir);
  const std::string name = fmt::format("TORUS {}k", mesh.n_vertices() / 1000);
  if (!failure.empty()) {
    add({"CLI geodesics under load", name, "", "", 0, 0, 0, -1.5, "skipped: " + failure});
    return;
  }
  Row r{"CLI geodesics under load, default BLAS policy", name, "OPENBLAS_NUM_THREADS=1", "default policy",
        median(one), median(policy), 0, -1.5,
        fmt::format("ratio = default / one thread (lower is better); wall time of `polydec geodesics --source 0 "
                    "--json`, medians of 3 interleaved runs (default {:.0f}, {:.0f}, {:.0f} ms; one thread {:.0f}, "
                    "{:.0f}, {:.0f} ms) with two busy processes beside them; OpenBLAS's own default "
                    "(POLYDEC_BLAS_THREADS=0, one thread per core, one run) {:.0f} ms; before the spinners{}, at the "
                    "end{}",
                    policy[0], policy[1], policy[2], one[0], one[1], one[2], all_cores, load_before, load_note())};
  r.ratio = median(policy) / median(one);
  add(r);
}

std::string status(const Row& r) {
  if (r.required == 0) return "(reported)";
  if (r.required < 0) return r.ratio <= -r.required ? "met" : fmt::format("MISSED by {:.2f}x", r.ratio / -r.required);
  return r.ratio >= r.required ? "met" : fmt::format("MISSED ({:.0f}% of target)", 100 * r.ratio / r.required);
}

// The rows so far as a Markdown table on stdout.
void print_table() {
  std::printf("| target | mesh | baseline | ours | baseline ms | ours ms | ratio | required | status | notes |\n");
  std::printf("|---|---|---|---|---:|---:|---:|---:|---|---|\n");
  for (const Row& r : rows) {
    const std::string req = r.required > 0 ? fmt::format(">= {:g}x", r.required)
                            : r.required < 0 ? fmt::format("<= {:g}x", -r.required)
                                             : "";
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", r.target.c_str(), r.mesh.c_str(),
                r.baseline.c_str(), r.ours.c_str(), r.base_ms > 0 ? fmt::format("{:.2f}", r.base_ms).c_str() : "",
                r.ours_ms > 0 ? fmt::format("{:.2f}", r.ours_ms).c_str() : "",
                r.ratio > 0 ? fmt::format("{:.2f}x", r.ratio).c_str() : "", req.c_str(),
                r.ratio > 0 || r.ours_ms > 0 ? status(r).c_str() : "skipped", r.note.c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  int big = 500, reps = 5, blas_threads = 1, volume_big = 100;
  bool with_big = true, quick = false, big_geodesics = true;  // --quick: assembly rows on HEX and FINE only
  std::string cli = POLYDEC_CLI;  // --cli PATH: the polydec CLI timed by --only blas-load
  std::string only;  // --only spectrum|feec|geodesics|cholesky: that section alone, on FINE SPHERE;
                     // form-spectrum: on a 100k-face quad sphere; geodesics-big: on cube_sphere(big)
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--memory-child" && i + 1 < argc) return memory_child(std::stoi(argv[i + 1]));
    if (a == "--volume-memory" && i + 1 < argc) return volume_memory(std::stoi(argv[i + 1]));
    if (a == "--volume-first-child" && i + 2 < argc)
      return volume_first_child(std::stoi(argv[i + 1]), std::stoi(argv[i + 2]));
    if (a == "--surface-read" && i + 1 < argc)
      return surface_read(std::stoi(argv[i + 1]), i + 2 < argc ? std::stoi(argv[i + 2]) : 3);
    if (a == "--volume-read" && i + 1 < argc)
      return volume_read(std::stoi(argv[i + 1]), i + 2 < argc ? std::stoi(argv[i + 2]) : 3);
    if (a == "--volume-phases" && i + 1 < argc)
      return volume_phases(std::stoi(argv[i + 1]), i + 2 < argc ? std::stoi(argv[i + 2]) : 2);
    if (a == "--profile" && i + 1 < argc && std::string(argv[i + 1]) == "volume") {
      // one volume assembly of hex_grid_volume(16^3), or with `cube` of cube_hexahedron_4 (with
      // `plain`: also the plain volume reference)
      const bool cube = i + 2 < argc && std::string(argv[i + 2]) == "cube";
      const VolumeMesh grid =
          cube ? read_volume_mesh(shared("volume/cube_hexahedron_4.ovm")) : hex_grid_volume(16, 16, 16);
      SparseMatrix Sp, Mp;
      if (i + 2 + int(cube) < argc && std::string(argv[i + 2 + int(cube)]) == "plain")
        plain_volume_reference::build(plain_volume_reference::from_volume_mesh(grid), Sp, Mp);
      const VolumeLaplacian L = assemble_volume_laplacian(grid, refine_volume(grid));
      return L.S.nonZeros() + Sp.nonZeros() > 0 ? 0 : 1;
    }
    if (a == "--profile") {  // one assembly of FINE SPHERE (or `plain`, or `star1`), for valgrind --tool=callgrind
      const Mesh fine = project_to_unit_sphere(catmull_clark(hex_sphere_mesh()));
      const auto input = plain_surface_reference::from_mesh(fine);
      SparseMatrix Sp, Mp;
      if (i + 1 < argc && std::string(argv[i + 1]) == "star1") {  // --toggle-collect='polydec::star1*'
        const Refinement r = refine(fine);
        const SparseMatrix st1 = star1(fine, r, CoarseComplex(fine));
        return st1.nonZeros() > 0 ? 0 : 1;
      }
      if (i + 1 < argc && std::string(argv[i + 1]) == "plain") plain_surface_reference::build(input, Sp, Mp);
      const Laplacian L = assemble_all(fine, 1);
      return L.S.nonZeros() + Sp.nonZeros() > 0 ? 0 : 1;
    }
    if (a == "--big" && i + 1 < argc) big = std::stoi(argv[++i]);
    else if (a == "--no-big") with_big = false;
    else if (a == "--volume-big" && i + 1 < argc) volume_big = std::stoi(argv[++i]);
    else if (a == "--quick") quick = true;
    else if (a == "--no-big-geodesics") big_geodesics = false;
    else if (a == "--gc-like-simplicial") gc_like_always_simplicial = true;
    else if (a == "--only" && i + 1 < argc) only = argv[++i];
    else if (a == "--blas-threads" && i + 1 < argc) blas_threads = std::stoi(argv[++i]);
    else if (a == "--cli" && i + 1 < argc) cli = argv[++i];
    else if (a == "--reps" && i + 1 < argc) reps = std::stoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: polydec_bench [--big N] [--no-big] [--quick] [--reps K] [--blas-threads N] [--no-big-geodesics] [--only SECTION] [--volume-big N] [--cli PATH]\n"
                           "  [--gc-like-simplicial]\n"
                           "  SECTION: spectrum|form-spectrum|feec|geodesics|geodesics-big|cholesky|assembly|volume|\n"
                           "  checks|dec|blas-load (blas-load runs only when asked for)\n");
      return 2;
    }
  }
  const auto t_start = Clock::now();
  // One BLAS thread by default: Eigen's factorization it is compared with is single-threaded,
  // and on a shared 2-core machine OpenBLAS's spinning worker threads lose to other processes.
  const int blas_in_effect = polydec::set_blas_threads(blas_threads).threads;  // the library's policy (operators/solvers/cholesky.h)
  if (only == "blas-load") {
    std::fprintf(stderr, "CLI geodesics under load (%s)...\n", cli.c_str());
    bench_blas_load(cli);
    print_table();
    return 0;
  }
  std::fprintf(stderr, "loading and generating meshes...\n");
  const Mesh hex = hex_sphere_mesh();
  const Mesh fine = project_to_unit_sphere(catmull_clark(hex));
  Mesh bunny;
  std::string bunny_error;
  try {
    bunny = read_mesh(shared("bunny-hexa.off"));
  } catch (const std::exception& e) {
    bunny_error = e.what();
  }
  if (quick) {
    with_big = false;
    bench_assembly("HEX SPHERE", hex, reps);
    bench_assembly("FINE SPHERE", fine, reps);
    bench_reassembly("FINE SPHERE", fine, reps);
    bench_threads("FINE SPHERE", fine, reps);
    return 0;
  }
  if (!only.empty()) {
    if (only == "spectrum") bench_spectrum("FINE SPHERE", fine, reps);
    else if (only == "form-spectrum")
      bench_form_spectrum("QUAD SPHERE 100K", project_to_unit_sphere(cube_sphere(129)));
    else if (only == "feec") {
      bench_feec("FINE SPHERE", fine, reps);
      bench_mesh_star1("HEX SPHERE", hex, reps, true);
      bench_mesh_star1("FINE SPHERE", fine, reps, false);
      print_table();
    }
    else if (only == "geodesics") {
      bench_geodesics("FINE SPHERE", fine, 9);
      print_table();
    }
    else if (only == "geodesics-big") {
      std::fprintf(stderr, "generating cube_sphere(%d)...\n", big);
      const Mesh quad = cube_sphere(big);
      bench_geodesics(fmt::format("QUAD {}k", quad.n_faces() / 1000), quad, 5);  // 5 sources, as the full run
      print_table();
    }
    else if (only == "dec") {
      bench_dec(with_big);
      print_table();
    }
    else if (only == "cholesky") bench_cholesky("FINE SPHERE", assemble_all(fine, 1), 3);
    else if (only == "assembly") {
      bench_assembly("HEX SPHERE", hex, reps);
      bench_assembly("FINE SPHERE", fine, reps);
      if (bunny_error.empty()) bench_assembly("bunny-hexa", bunny, reps);
      if (with_big) {
        std::fprintf(stderr, "generating cube_sphere(%d)...\n", big);
        const Mesh quad = cube_sphere(big);
        const std::string quad_name = fmt::format("QUAD {}k", quad.n_faces() / 1000);
        // Five interleaved rounds, as the recorded pmp-library figure was taken (medians of 5).
        const AssemblyMs ours = bench_assembly(quad_name, quad, 5);
        if (big == 500) add_pmp_row(quad_name, ours);
      }
      print_table();
      std::printf("\nload average at the end: %s\n", load_note().c_str());
    }
    else if (only == "checks") {
      std::fprintf(stderr, "generating cube_sphere(%d)...\n", big);
      const Mesh quad = cube_sphere(big);
      bench_mesh_checks(fmt::format("QUAD {}k", quad.n_faces() / 1000), quad, reps, big == 500 ? 2145.0 : 0.0);
      print_table();
    }
    else if (only == "volume") {
      bench_volumes(std::filesystem::read_symlink("/proc/self/exe").string(), volume_big, reps);
      print_table();
      std::printf("\nload average at the end: %s\n", load_note().c_str());
    }
    else std::fprintf(stderr, "unknown section '%s'\n", only.c_str());
    return 0;
  }
  Mesh quad_big;
  if (with_big) {
    std::fprintf(stderr, "generating the big mesh cube_sphere(%d) (%.1fM quads; the big rows take minutes, each row is printed when done)...\n",
                 big, 6.0 * big * big / 1e6);
    quad_big = cube_sphere(big);
  }
  const std::string big_name = fmt::format("QUAD {}k", quad_big.n_faces() / 1000);

  std::fprintf(stderr, "assembly vs plain reference...\n");
  bench_assembly("HEX SPHERE", hex, reps);
  bench_assembly("FINE SPHERE", fine, reps);
  if (bunny_error.empty())
    bench_assembly("bunny-hexa", bunny, reps);
  else
    add({"assembly S+M+lumped, 1 thread", "bunny-hexa", "", "", 0, 0, 0, 0, "skipped: " + bunny_error});
  if (with_big) {
    const AssemblyMs ours = bench_assembly(big_name, quad_big, 5);  // medians of 5, as the pmp figure
    if (big == 500) add_pmp_row(big_name, ours);
  }

  std::fprintf(stderr, "threads...\n");
  bench_threads("FINE SPHERE", fine, reps);
  if (with_big) bench_threads(big_name, quad_big, 3);

  std::fprintf(stderr, "re-assembly...\n");
  bench_reassembly("FINE SPHERE", fine, reps);
  if (with_big) bench_reassembly(big_name, quad_big, 3);

  if (with_big) {
    std::fprintf(stderr, "memory...\n");
    bench_memory(std::filesystem::read_symlink("/proc/self/exe").string(), big);
  }

  std::fprintf(stderr, "Cholesky...\n");
  const Laplacian Lf = assemble_all(fine, 1);
  bench_cholesky("FINE SPHERE", Lf, 3);

  std::fprintf(stderr, "heat geodesics...\n");
  bench_geodesics("FINE SPHERE", fine, 9);
  if (with_big && big_geodesics)
    bench_geodesics(big_name, quad_big, 5);
  else if (with_big)
    add({"heat geodesics per source", big_name, "", "", 0, 0, 0, 0, "skipped (--no-big-geodesics)"});

  std::fprintf(stderr, "FEEC...\n");
  bench_feec("FINE SPHERE", fine, reps);
  bench_mesh_star1("HEX SPHERE", hex, reps, true);
  bench_mesh_star1("FINE SPHERE", fine, reps, false);
  if (with_big) bench_mesh_star1(big_name, quad_big, 1, false);
  std::fprintf(stderr, "spectrum...\n");
  bench_spectrum("FINE SPHERE", fine, 3);

  bench_volumes(std::filesystem::read_symlink("/proc/self/exe").string(), with_big ? volume_big : 0, reps);

  print_table();
  std::printf("\nmeshes: HEX SPHERE %d faces, FINE SPHERE %d faces%s%s\n", hex.n_faces(), fine.n_faces(),
              bunny_error.empty() ? fmt::format(", bunny-hexa {} faces", bunny.n_faces()).c_str() : "",
              with_big ? fmt::format(", {} = cube_sphere({}) {} faces", big_name, big, quad_big.n_faces()).c_str() : "");
  std::printf("hardware threads: %u; BLAS/LAPACK mapped: %s; OpenBLAS threads: %d\n",
              std::thread::hardware_concurrency(), blas_libraries().c_str(), blas_in_effect);
  std::printf("total benchmark time: %.0f s\n", ms_since(t_start) / 1000);
  return 0;
}
