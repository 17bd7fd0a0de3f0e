// tests/apps/applications/test_geodesics.cpp — heat-method geodesics (paper section 5.5, eq. 31-33):
// accuracy on generated meshes, the paper's Table 4 values (authors' program, lumped mass),
// several sources, reuse of the factorizations, unreachable vertices, the heat step's reach and the
// suggested time factor from any starting factor.
#include "polydec/apps/applications/geodesics.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/surface/virtual_lift.h"
#include "polydec/operators/surface/gradient.h"
#include "tests/support/support.h"

#include <catch2/catch.hpp>
#include <cmath>
#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif
#include <limits>
#include <string>
#include <utility>

using namespace polydec;

namespace test_geodesics {

namespace {

// The paper's operator set on the given refinement, under `name`.
OperatorSet operators_on(const Mesh& mesh, const Refinement& r, const std::string& name) {
  OperatorSet ops;
  ops.name = name;
  ops.domain = mesh;
  ops.n_input_vertices = mesh.n_vertices();
  Laplacian L = assemble_laplacian(mesh, r);
  ops.S = L.S;
  ops.M = L.M;
  ops.M_lumped = L.M_lumped;
  ops.G = gradient(mesh, r);
  ops.D = divergence(mesh, r);
  return ops;
}

// RMSE of the heat distance from vertex 0 against the Euclidean distance (planar meshes),
// both shifted to minimum 0, as the authors' program measures it.
double euclidean_rmse(const Mesh& mesh, bool lumped = true, double degenerate_tolerance = -1) {
  HeatGeodesicsOptions o;
  o.lumped_mass = lumped;
  Eigen::VectorXd d;
  if (degenerate_tolerance < 0) {
    d = HeatGeodesics(mesh, o).distance(0);
  } else {
    // Ours with another degenerate-fan tolerance.
    RefinementOptions ro;
    ro.degenerate_tolerance = degenerate_tolerance;
    d = HeatGeodesics(operators_on(mesh, refine(mesh, ro), "ours"), mesh.mean_edge_length(), o).distance(0);
  }
  Eigen::VectorXd e(mesh.n_vertices());
  for (int v = 0; v < mesh.n_vertices(); ++v) e[v] = (mesh.position(v) - mesh.position(0)).norm();
  return rmse(d, e.array() - e.minCoeff());
}

}  // namespace

TEST_CASE("geodesics converge to the great-circle distance on spheres", "[geodesics]") {
  double previous = 1e9;
  for (int level : {2, 3, 4}) {
    const Mesh mesh = hex_sphere(level);
    const Eigen::VectorXd d = HeatGeodesics(mesh).distance(0);
    Eigen::VectorXd exact(mesh.n_vertices());
    for (int v = 0; v < mesh.n_vertices(); ++v)
      exact[v] = std::acos(std::clamp(mesh.position(0).dot(mesh.position(v)), -1.0, 1.0));
    const double err = rmse(d, exact);
    CHECK(err < 0.05);
    CHECK(err < previous);
    previous = err;
    CHECK(d.minCoeff() == 0.0);
    CHECK(d.allFinite());
  }
}

TEST_CASE("several sources: distance is the minimum over sources, solver reused", "[geodesics]") {
  const Mesh mesh = quad_grid(24, 24);
  const HeatGeodesics heat(mesh);
  const int a = 0, b = mesh.n_vertices() - 1;
  const int both[2] = {a, b};
  const Eigen::VectorXd da = heat.distance(a), db = heat.distance(b), dab = heat.distance(both);
  // Near each source the two-source distance follows that source's distance.
  CHECK(dab[a] < 0.02);
  CHECK(dab[b] < 0.02);
  // Everywhere it is close to the minimum of the single-source distances (smoothing at the cut locus).
  Eigen::VectorXd mn = da.cwiseMin(db);
  CHECK(rmse(dab, mn) < 0.03);
  // Repeated queries on one instance give identical answers (factorizations are reused, not mutated).
  CHECK((heat.distance(a) - da).cwiseAbs().maxCoeff() == 0.0);
  CHECK_THROWS_AS(heat.distance(mesh.n_vertices()), std::out_of_range);
  CHECK_THROWS_AS(heat.distance(std::span<const int>()), std::out_of_range);
}

TEST_CASE("unreachable vertices get +infinity, reachable ones finite", "[geodesics]") {
  PolygonSoup s;
  const Mesh g = quad_grid(3, 3);
  s.positions.resize(g.n_vertices() * 2 + 1, 3);
  s.positions.topRows(g.n_vertices()) = g.positions();
  s.positions.middleRows(g.n_vertices(), g.n_vertices()) = g.positions().rowwise() + Eigen::RowVector3d(5, 0, 0);
  s.positions.row(2 * g.n_vertices()) << 9, 9, 9;  // unreferenced
  for (int copy = 0; copy < 2; ++copy)
    for (int f = 0; f < g.n_faces(); ++f) {
      std::vector<int> face;
      for (int v : g.face(f)) face.push_back(v + copy * g.n_vertices());
      s.add_face(face);
    }
  const Mesh mesh(std::move(s));
  const Eigen::VectorXd d = HeatGeodesics(mesh).distance(0);
  for (int v = 0; v < g.n_vertices(); ++v) CHECK(std::isfinite(d[v]));
  for (int v = g.n_vertices(); v < mesh.n_vertices(); ++v) CHECK(std::isinf(d[v]));
}

TEST_CASE("Table 4: geodesic RMSE as the authors' program computes it (within 1%)", "[geodesics][paper]") {
  // Values printed by the authors' published test program (lumped mass, source vertex 0).
  struct Row {
    const char* file;
    bool subdivide;
    double expected;
  };
  for (const Row& row : {Row{"quad-plane.obj", true, 0.026455}, Row{"quad-plane.obj", false, 0.035637},
                         Row{"L-plane.obj", false, 0.057402}, Row{"tetris_2.obj", false, 0.082092}}) {
    POLYDEC_SHARED_MESH(path, row.file);
    INFO(row.file << (row.subdivide ? " (one Catmull-Clark step: QUADS 1)" : ""));
    Mesh mesh = read_mesh(path);
    if (row.subdivide) mesh = catmull_clark(mesh);
    CHECK(euclidean_rmse(mesh) == Approx(row.expected).epsilon(0.01));
  }
}

TEST_CASE("TETRIS 1: degenerate fan triangles get zero weight, result well defined", "[geodesics][paper]") {
  POLYDEC_SHARED_MESH(path, "tetris.obj");
  const Mesh mesh = read_mesh(path);
  const double err = euclidean_rmse(mesh);
  // The authors' program prints 0.17758 (float positions) or 0.18983 (double); the paper 0.2183.
  // The spread comes from near-zero-area fan triangles; see docs/operators.md.
  CHECK(err > 0.15);
  CHECK(err < 0.23);
  // Well defined: insensitive to the tolerance over many orders of magnitude.
  for (double tol : {1e-13, 1e-8, 1e-6}) {
    RefinementOptions ro;
    ro.degenerate_tolerance = tol;
    const Refinement r = refine(mesh, ro);
    CHECK(r.quality.n_degenerate == 6);
  }
}

TEST_CASE("TETRIS 1: the two regimes around exactly degenerate fan triangles", "[geodesics][paper]") {
  POLYDEC_SHARED_MESH(path, "tetris.obj");
  const Mesh mesh = read_mesh(path);
  // tetris.obj lies in a plane y = const; perturb within that plane so the virtual vertices leave
  // the edge lines by ~1e-6 of the edge length: the zero-area fan triangles become slivers.
  const double y = mesh.positions()(0, 1);
  REQUIRE(mesh.positions().col(1).cwiseAbs().maxCoeff() == std::abs(y));
  Eigen::MatrixX3d X = add_noise(mesh, 1e-6, 3).positions();
  X.col(1).setConstant(y);
  const Mesh moved = mesh.with_positions(X);
  const double dropped = euclidean_rmse(mesh);
  const double slivers_kept = euclidean_rmse(moved, true, 1e-12);
  const double slivers_dropped = euclidean_rmse(moved, true, 1e-4);
  CHECK(slivers_dropped == Approx(dropped).epsilon(1e-3));  // continuous when slivers count as degenerate
  CHECK(slivers_kept == Approx(0.1805).epsilon(0.01));      // the sliver limit: a different operator
  CHECK(std::abs(slivers_kept - dropped) > 0.01);
}

TEST_CASE("a strip 2000 edges long: the heat step's reach is reported, and the suggested time factor covers it",
          "[geodesics]") {
  // 2000 x 4 square quads (edge 0.01): at t = h^2 the heat solution falls below double precision's
  // range ~650 edges from the source, beyond which the distance is wrong (flat, too small); the
  // diagnostics must say so, and the suggested factor must give the strip's length (20) to 0.5%.
  Mesh strip = quad_grid(2000, 4);
  Eigen::MatrixX3d X = strip.positions();
  X.col(0) *= 20.0;
  X.col(1) *= 0.04;
  strip = strip.with_positions(X);
  const double length = 20.0;
  HeatDiagnostics first;
  const Eigen::VectorXd d1 = HeatGeodesics(strip).distance(std::span<const int>({0}), &first);
  CHECK(first.unresolved_vertices > strip.n_vertices() / 2);
  CHECK(first.resolved_radius > 0.2 * length);
  CHECK(first.resolved_radius < 0.5 * length);
  CHECK(d1.maxCoeff() < 0.5 * length);
  const double factor = suggested_time_factor(1.0, first, strip.bounding_box_diagonal());
  CHECK(factor > 1.0);
  HeatGeodesicsOptions o;
  o.time_step_factor = factor;
  HeatDiagnostics second;
  const Eigen::VectorXd d2 = HeatGeodesics(strip, o).distance(std::span<const int>({0}), &second);
  CHECK(second.unresolved_vertices == 0);
  CHECK(second.resolved_radius == Approx(d2.maxCoeff()).epsilon(1e-12));
  CHECK(std::abs(d2.maxCoeff() - length) < 0.005 * length);
  // Nothing to suggest when everything is resolved.
  CHECK(suggested_time_factor(factor, second, strip.bounding_box_diagonal()) == factor);
}

TEST_CASE("one suggested time factor resolves the strip from any factor in [1e-4, 1]", "[geodesics]") {
  // Below t = h^2 the implicit heat step's reach grows like ln(1 / factor), not sqrt(factor): a
  // suggestion that scaled the resolved radius as sqrt(t) undershot from small factors (0.13 from
  // 1e-4, 3.3 from 1e-2, still unresolved). From every start the single suggestion must resolve
  // the strip and give its length to 0.5%, and the suggestions must agree (the model's reach does
  // not depend on where it was measured).
  Mesh strip = quad_grid(2000, 4);
  Eigen::MatrixX3d X = strip.positions();
  X.col(0) *= 20.0;
  X.col(1) *= 0.04;
  strip = strip.with_positions(X);
  const double length = 20.0, extent = strip.bounding_box_diagonal();
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (double start : {1e-4, 1e-3, 1e-2, 1e-1, 1.0}) {
    INFO("start factor " << start);
    HeatGeodesicsOptions o;
    o.time_step_factor = start;
    HeatDiagnostics first;
    HeatGeodesics(strip, o).distance(std::span<const int>({0}), &first);
    REQUIRE(first.unresolved_vertices > 0);
    o.time_step_factor = suggested_time_factor(start, first, extent);
    INFO("suggested " << o.time_step_factor);
    HeatDiagnostics second;
    const Eigen::VectorXd d = HeatGeodesics(strip, o).distance(std::span<const int>({0}), &second);
    CHECK(second.unresolved_vertices == 0);
    CHECK(std::abs(d.maxCoeff() - length) < 0.005 * length);
    lo = std::min(lo, o.time_step_factor);
    hi = std::max(hi, o.time_step_factor);
  }
  CHECK(hi < 1.1 * lo);
  // For large factors the reach grows as sqrt(t): the suggestion tends to factor (1.25 extent / r)^2.
  const HeatDiagnostics far{1, 0.01 * extent};
  CHECK(suggested_time_factor(1e6, far, extent) == Approx(1e6 * 125.0 * 125.0).epsilon(1e-6));
  // Never below the factor it started from.
  CHECK(suggested_time_factor(0.5, HeatDiagnostics{1, 2 * extent}, extent) == 0.5);
}

TEST_CASE("distances: one field per source, equal to one-by-one in every block size and option", "[geodesics]") {
  // Two components and an unreferenced vertex: each source's own component is reached only.
  PolygonSoup s;
  const Mesh g = add_noise(hex_grid(5, 4), 0.1, 3), h = hex_sphere(1);
  s.positions.resize(g.n_vertices() + h.n_vertices() + 1, 3);
  s.positions.topRows(g.n_vertices()) = g.positions();
  s.positions.middleRows(g.n_vertices(), h.n_vertices()) = h.positions().rowwise() + Eigen::RowVector3d(5, 0, 0);
  s.positions.bottomRows(1) << 9, 9, 9;
  for (int f = 0; f < g.n_faces(); ++f) s.add_face(g.face(f));
  for (int f = 0; f < h.n_faces(); ++f) {
    std::vector<int> face;
    for (int v : h.face(f)) face.push_back(v + g.n_vertices());
    s.add_face(face);
  }
  const Mesh mesh(std::move(s));
  const std::vector<int> sources = {0, g.n_vertices() + 3, 11, 0, g.n_vertices() + 20};
  for (bool lumped : {true, false})
    for (bool weighted : {true, false}) {
      HeatGeodesicsOptions o;
      o.lumped_mass = lumped;
      o.mass_weighted_source = weighted;
      const HeatGeodesics heat(mesh, o);
      for (int block : {1, 2, 64}) {
        INFO("lumped " << lumped << ", mass-weighted source " << weighted << ", block " << block);
        const Eigen::MatrixXd D = heat.distances(sources, block);
        REQUIRE(D.rows() == mesh.n_vertices());
        REQUIRE(D.cols() == long(sources.size()));
        for (size_t c = 0; c < sources.size(); ++c) {
          const Eigen::VectorXd one = heat.distance(sources[c]);
          double scale = 0;
          for (int v = 0; v < mesh.n_vertices(); ++v) {
            CHECK(std::isinf(D(v, long(c))) == std::isinf(one[v]));
            if (std::isfinite(one[v])) scale = std::max(scale, one[v]);
          }
          for (int v = 0; v < mesh.n_vertices(); ++v)
            if (std::isfinite(one[v])) CHECK(std::abs(D(v, long(c)) - one[v]) <= 1e-12 * scale);
          if (lumped) CHECK(D(sources[c], long(c)) == 0.0);  // the Galerkin mass may put the minimum elsewhere
        }
      }
    }
  const HeatGeodesics heat(mesh);
  // The kept blocks, freed or not, give the same bits.
  const Eigen::MatrixXd first = heat.distances(sources), again = heat.distances(sources);
  heat.release_blocks();
  CHECK(heat.distances(sources) == first);
  CHECK(again == first);
  CHECK_THROWS_AS(heat.distances(std::vector<int>{}), std::out_of_range);
  CHECK_THROWS_AS(heat.distances(std::vector<int>{mesh.n_vertices() - 1}), std::out_of_range);  // unreferenced
  CHECK_THROWS_AS(heat.distances(std::vector<int>{0}, 0), std::invalid_argument);

  // Into a caller's matrix: the same bits, into columns of a larger one too, the other columns
  // untouched; a wrong shape is refused before anything is written.
  const long k = long(sources.size());
  Eigen::MatrixXd into(mesh.n_vertices(), k);
  heat.distances(sources, into);
  CHECK(into == first);
  Eigen::MatrixXd wide = Eigen::MatrixXd::Constant(mesh.n_vertices(), k + 3, -7.0);
  heat.distances(sources, wide.middleCols(2, k));
  CHECK(wide.middleCols(2, k) == first);
  CHECK((wide.leftCols(2).array() == -7.0).all());
  CHECK((wide.rightCols(1).array() == -7.0).all());
  Eigen::MatrixXd short_rows = Eigen::MatrixXd::Constant(mesh.n_vertices() - 1, k, -7.0);
  CHECK_THROWS_AS(heat.distances(sources, short_rows), std::invalid_argument);
  CHECK((short_rows.array() == -7.0).all());
  CHECK_THROWS_AS(heat.distances(sources, wide), std::invalid_argument);
}

TEST_CASE("heat geodesics flush subnormals only inside their calls: the caller's mode is restored",
          "[geodesics]") {
#if defined(__SSE__) || defined(__x86_64__)
  // A strip long enough that the heat step underflows far from the source (values below double's
  // normal range there): the calls run with subnormals flushed to zero and restore the mode.
  const Mesh mesh = quad_grid(1200, 1);
  const HeatGeodesics heat(mesh);
  const unsigned before = _mm_getcsr();
  HeatDiagnostics diagnostics;
  const Eigen::VectorXd d = heat.distance(std::vector<int>{0}, &diagnostics);
  CHECK(_mm_getcsr() == before);
  const Eigen::MatrixXd D = heat.distances(std::vector<int>{0, 5});
  CHECK(_mm_getcsr() == before);
  CHECK(diagnostics.unresolved_vertices > 0);  // the underflowing far field exists
  CHECK(d.allFinite());
  CHECK(D.allFinite());
  CHECK(std::abs(D(2400, 0) - d[2400]) <= 1e-12 * d.maxCoeff());
#endif
}

TEST_CASE("distances equal one-by-one where the heat step underflows, columns mixed in one fan triangle",
          "[geodesics]") {
  // At t = h^2 on a strip of 1200 x 2 square quads the heat solution of one source falls from 1 to
  // 0 (below double's range) within ~650 edges; from ~440 edges on |grad u|^2 leaves [1e-280,
  // 1e280] and the block pass rescales. Sources 300 edges apart put columns in range, rescaled and
  // zero into the same fan triangles; the sources at the ends leave ~530 edges unresolved.
  // distance() takes the one-column route.
  Mesh mesh = quad_grid(1200, 2);
  Eigen::MatrixX3d X = mesh.positions();
  X.col(1) *= 2.0 / 1200;  // square quads
  mesh = mesh.with_positions(X);
  const HeatGeodesics heat(mesh);
  const std::vector<int> sources = {0, 300, 600, 900, 1200};
  const Eigen::MatrixXd D = heat.distances(sources);
  for (size_t c = 0; c < sources.size(); ++c) {
    INFO("source " << sources[c]);
    HeatDiagnostics diagnostics;
    const Eigen::VectorXd one = heat.distance(std::span<const int>(&sources[c], 1), &diagnostics);
    REQUIRE(one.allFinite());
    // Beyond the resolved radius both routes give noise (there a last bit of u turns the gradient).
    const double radius = diagnostics.resolved_radius;
    CHECK(radius > 0.5);
    double worst = 0;
    for (int v = 0; v < mesh.n_vertices(); ++v)
      if (one[v] <= radius) worst = std::max(worst, std::abs(D(v, long(c)) - one[v]));
    CHECK(worst <= 1e-12 * radius);
  }
}

TEST_CASE("the face-wise pass of the paper's operator equals the route through G and D", "[geodesics]") {
  for (const Mesh& mesh : {add_noise(hex_sphere(2), 0.2, 5), quad_grid(6, 5), add_noise(hex_grid(5, 4), 0.1, 3)}) {
    for (bool lumped : {true, false}) {
      INFO(mesh.n_vertices() << " vertices, lumped " << lumped);
      HeatGeodesicsOptions o;
      o.lumped_mass = lumped;
      const HeatGeodesics fused(mesh, o);
      REQUIRE(fused.operators().refinement.has_value());  // the face-wise pass reads it
      CHECK(fused.operators().G.size() == 0);             // and needs no G and D
      OperatorSet ops = build_operators(mesh, parse_laplacian("ours"));
      ops.refinement.reset();  // without its refinement: the matrices are used
      const HeatGeodesics plain(std::move(ops), mesh.mean_edge_length(), o);
      const std::vector<int> sources = {0, mesh.n_vertices() / 2};
      const Eigen::VectorXd a = fused.distance(sources), b = plain.distance(sources);
      CHECK((a - b).cwiseAbs().maxCoeff() <= 1e-12 * b.maxCoeff());
      const Eigen::MatrixXd A = fused.distances(sources), B = plain.distances(sources);
      CHECK((A - B).cwiseAbs().maxCoeff() <= 1e-12 * B.maxCoeff());
    }
  }
  // The other one-virtual-vertex methods carry their refinement too (centroid; virtual vertices
  // lifted off the plane): the face-wise pass from it equals their G and D route.
  const Mesh sphere = add_noise(hex_sphere(2), 0.05, 7);
  for (const auto& [name, lift] : {std::pair<std::string, std::string>{"centroid", "none"}, {"ours", "sphere"}}) {
    INFO(name << ", lift " << lift);
    OperatorOptions oo;
    oo.lift = parse_virtual_lift(lift);
    OperatorSet with = build_operators(sphere, parse_laplacian(name), oo), without = build_operators(sphere, parse_laplacian(name), oo);
    REQUIRE(with.refinement.has_value());
    without.refinement.reset();
    const HeatGeodesics fused(std::move(with), sphere.mean_edge_length()),
        plain(std::move(without), sphere.mean_edge_length());
    const Eigen::VectorXd a = fused.distance(3), b = plain.distance(3);
    CHECK((a - b).cwiseAbs().maxCoeff() <= 1e-12 * b.maxCoeff());
  }
  // An operator set on another refinement (a far larger degenerate-fan tolerance, many fan triangles
  // without stiffness) that carries it: the fan data come from that refinement, equal to its G and D.
  const Mesh mesh = add_noise(hex_grid(5, 4), 0.3, 9);
  RefinementOptions ro;
  ro.degenerate_tolerance = 0.3;
  const Refinement r = refine(mesh, ro);
  REQUIRE(r.quality.n_degenerate > 0);
  OperatorSet carried = operators_on(mesh, r, "ours");
  carried.refinement = r;
  const Eigen::VectorXd a = HeatGeodesics(std::move(carried), mesh.mean_edge_length()).distance(0);
  const Eigen::VectorXd b = HeatGeodesics(operators_on(mesh, r, "ours"), mesh.mean_edge_length()).distance(0);
  CHECK((a - b).cwiseAbs().maxCoeff() <= 1e-12 * b.maxCoeff());
  // Methods without one virtual vertex per face carry none, and keep G and D when sets with a
  // refinement leave them out; a set with neither cannot be solved.
  OperatorOptions no_fan_gradient;
  no_fan_gradient.gradient_with_refinement = false;
  OperatorSet idt = build_operators(mesh, parse_laplacian("intrinsic-delaunay"), no_fan_gradient);
  CHECK_FALSE(idt.refinement.has_value());
  CHECK(idt.G.cols() == mesh.n_vertices());
  CHECK(idt.D.rows() == mesh.n_vertices());
  OperatorSet bare = build_operators(mesh, parse_laplacian("ours"), no_fan_gradient);
  CHECK(bare.G.size() == 0);
  bare.refinement.reset();
  CHECK_THROWS_AS(HeatGeodesics(std::move(bare), mesh.mean_edge_length()), std::invalid_argument);
}

TEST_CASE("distance equals eqs. (31)-(33) solved with dense right-hand sides, for one and several sources",
          "[geodesics]") {
  // The reference: both steps through SparseCholesky::solve on dense right-hand sides, G and D as
  // matrices, vertex 0 pinned in the Poisson step (one component), shifted to minimum 0.
  const Mesh mesh = add_noise(hex_sphere(2), 0.2, 5);
  const int n = mesh.n_vertices();
  const OperatorSet ops = build_operators(mesh, parse_laplacian("ours"));
  const double t = mesh.mean_edge_length() * mesh.mean_edge_length();
  for (bool lumped : {true, false})
    for (bool weighted : {true, false}) {
      HeatGeodesicsOptions o;
      o.lumped_mass = lumped;
      o.mass_weighted_source = weighted;
      const HeatGeodesics heat(mesh, o);
      SparseMatrix Ml(n, n);
      Ml.setIdentity();
      Ml.diagonal() = ops.M_lumped;
      const SparseCholesky heat_chol(SparseMatrix((lumped ? Ml : ops.M) - t * ops.S), "heat");
      std::vector<unsigned char> pinned(size_t(n), 0);
      pinned[0] = 1;
      const SparseCholesky poisson_chol(pin_to_identity(SparseMatrix(-ops.S), pinned), "Poisson");
      for (const std::vector<int>& sources : {std::vector<int>{7}, std::vector<int>{3, n - 1, 3, n / 2}}) {
        INFO("lumped " << lumped << ", mass-weighted " << weighted << ", " << sources.size() << " sources");
        Eigen::VectorXd delta = Eigen::VectorXd::Zero(n);
        for (int s : sources) delta[s] = 1.0;
        const Eigen::VectorXd rhs =
            !weighted ? delta : lumped ? Eigen::VectorXd(ops.M_lumped.cwiseProduct(delta)) : Eigen::VectorXd(ops.M * delta);
        const Eigen::VectorXd u = heat_chol.solve(rhs);
        Eigen::VectorXd g = ops.G * u;
        const int n_blocks = ops.G_blocks.empty() ? int(g.size() / 3) : int(ops.G_blocks.size()) - 1;
        for (int h = 0; h < n_blocks; ++h) {
          const int b0 = ops.G_blocks.empty() ? 3 * h : ops.G_blocks[size_t(h)];
          const int b1 = ops.G_blocks.empty() ? 3 * h + 3 : ops.G_blocks[size_t(h) + 1];
          const double norm = g.segment(b0, b1 - b0).norm();
          if (norm > 0)
            g.segment(b0, b1 - b0) /= -norm;
          else
            g.segment(b0, b1 - b0).setZero();
        }
        Eigen::VectorXd b = -(ops.D * g);
        b[0] = 0;
        Eigen::VectorXd expected = poisson_chol.solve(b);
        expected.array() -= expected.minCoeff();
        const Eigen::VectorXd d = heat.distance(sources);
        CHECK((d - expected).cwiseAbs().maxCoeff() <= 1e-12 * expected.maxCoeff());
      }
    }
}

}  // namespace test_geodesics
