// tests/apps/applications/test_form_spectrum.cpp — Hodge Laplacian spectra of Whitney 1- and 2-forms:
// residuals against the explicitly assembled operator, zero eigenvalues = Betti numbers, the
// 0-form spectrum inside the 1-form one (eigenvectors d0 x), the unit sphere's l(l+1) with
// multiplicity 2(2l+1), invariances, and the 2-form spectrum converging to the 0-form one.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <random>

#include "polydec/apps/applications/form_spectrum.h"
#include "polydec/apps/applications/spectrum.h"
#include "polydec/dec/surface/complex.h"
#include "polydec/dec/surface/form_span.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/surface/hodge_star.h"
#include "tests/support/feec_meshes.h"
#include "tests/support/renumbered.h"

using namespace polydec;

namespace test_form_spectrum {

namespace {

// Meshes of every kind the form spectra are for (closed, with boundary, higher genus, non-planar,
// non-convex), small enough for a dense check; name, mesh, b1.
struct Case {
  std::string name;
  Mesh mesh;
};

std::vector<Case> meshes() {
  std::vector<Case> m;
  m.push_back({"quad sphere", cube_sphere(3)});
  m.push_back({"hexagon sphere (pentagons)", hex_sphere(1)});
  m.push_back({"non-planar mixed disk", add_noise(test::planar_grid(7, 5, 0.2, true), 0.15, 9)});
  m.push_back({"noisy hexagon torus", test::torus(12, 8, 0.15, true)});
  m.push_back({"genus-2 hexagon surface", test::genus2(1, 0.1, true)});
  // Non-convex faces (tetris.obj has collinear corners, i.e. degenerate fan triangles: those
  // carry no star2, and its 1-form Laplacian has spurious zero modes; docs/spectral.md).
  if (const std::string p = test::shared_path("L-plane.obj"); !p.empty())
    m.push_back({"L-plane (non-convex faces)", read_mesh(p)});
  if (const std::string p = test::shared_path("suzanne-half.obj"); !p.empty())
    m.push_back({"half Suzanne (two boundary loops)", read_mesh(p)});
  return m;
}

// b1 = b0 + b2 - chi for a connected mesh: b2 = 1 when closed.
int first_betti(const Mesh& mesh) {
  REQUIRE(mesh.n_components() == 1);
  return 1 + (mesh.n_boundary_edges() == 0 ? 1 : 0) - mesh.euler_characteristic();
}

double surface_area(const Mesh& mesh) {
  HodgeStarParts parts;
  parts.star1 = parts.star2 = false;
  return hodge_stars(mesh, refine(mesh), CoarseComplex(mesh), parts).star0_lumped.sum();
}

int count_zero(const Eigen::VectorXd& ev, double scale) {
  int z = 0;
  for (double e : ev) z += std::abs(e) <= 1e-7 * scale;
  return z;
}

// star-norm of the part of x outside span(W) (W star-orthonormal), relative to |x|.
double outside(const Eigen::MatrixXd& W, const SparseMatrix& star, const Eigen::VectorXd& x) {
  const Eigen::VectorXd r = x - W * (W.transpose() * (star * x));
  return std::sqrt(std::max(0.0, r.dot(star * r)) / x.dot(star * x));
}

// Largest relative error of each band l = 1..lmax against l(l+1), the sorted eigenvalues taken
// in groups of `multiplicity(l)` after `skip` leading ones.
std::vector<double> band_errors(const Eigen::VectorXd& ev, int skip, int lmax, int factor) {
  std::vector<double> err;
  int i = skip;
  for (int l = 1; l <= lmax; ++l) {
    double e = 0;
    for (int c = 0; c < factor * (2 * l + 1); ++c, ++i)
      e = std::max(e, std::abs(ev[i] / (l * (l + 1.0)) - 1));
    err.push_back(e);
  }
  return err;
}

}  // namespace

TEST_CASE("1-form eigenpairs solve K w = lambda star1 w, explicitly assembled", "[form_spectrum]") {
  for (const auto& [name, mesh] : meshes()) {
    INFO(name);
    FormSpectrumOptions o;
    o.k = 12;
    const FormSpectrum sp = form_spectrum(mesh, o);
    const Refinement ref = refine(mesh);
    const CoarseComplex cx(mesh);
    const HodgeStars H = hodge_stars(mesh, ref, cx);
    const SparseMatrix d0 = cx.d0(), d1 = cx.d1();
    const Eigen::VectorXd minv = H.star0_lumped.cwiseInverse();
    const SparseMatrix G = H.star1 * d0;
    const Eigen::MatrixXd& W = sp.eigenvectors;
    const Eigen::MatrixXd KW = Eigen::MatrixXd(d1.transpose() * (H.star2 * (d1 * W))) +
                               G * (minv.asDiagonal() * (G.transpose() * W));
    const Eigen::MatrixXd R = KW - H.star1 * W * sp.eigenvalues.asDiagonal();
    CHECK(R.norm() <= 1e-7 * (H.star1 * W * sp.eigenvalues.asDiagonal()).norm());
    CHECK((W.transpose() * H.star1 * W - Eigen::MatrixXd::Identity(o.k, o.k)).cwiseAbs().maxCoeff() <= 1e-8);
    for (int i = 1; i < o.k; ++i) CHECK(sp.eigenvalues[i] >= sp.eigenvalues[i - 1]);
    CHECK(sp.eigenvalues.minCoeff() >= -1e-9);
    // The parts sum to the eigenform and their norms to its norm (orthogonal parts).
    CHECK((sp.exact + sp.coexact + sp.harmonic - W).norm() <= 1e-8 * W.norm());
    for (int i = 0; i < o.k; ++i)
      CHECK(std::abs(sp.norm_exact[i] * sp.norm_exact[i] + sp.norm_coexact[i] * sp.norm_coexact[i] +
                     sp.norm_harmonic[i] * sp.norm_harmonic[i] - 1) <= 1e-6);
  }
}

TEST_CASE("1-form zero eigenvalues count the first Betti number, each one harmonic", "[form_spectrum]") {
  for (const auto& [name, mesh] : meshes()) {
    INFO(name);
    const int b1 = first_betti(mesh);
    FormSpectrumOptions o;
    o.k = b1 + 4;
    const FormSpectrum sp = form_spectrum(mesh, o);
    const double area = surface_area(mesh);
    CHECK(count_zero(sp.eigenvalues, 1 / area) == b1);
    for (int i = 0; i < o.k; ++i) {
      INFO("eigenpair " << i << ", lambda " << sp.eigenvalues[i]);
      if (i < b1) {
        CHECK(sp.kinds[size_t(i)] == FormKind::Harmonic);
        CHECK(sp.norm_harmonic[i] >= 1 - 1e-6);
      } else {
        CHECK(sp.kinds[size_t(i)] != FormKind::Harmonic);
        CHECK(sp.norm_harmonic[i] <= 1e-5);
      }
    }
  }
}

TEST_CASE("every nonzero 0-form eigenvalue is a 1-form eigenvalue with eigenvector d0 x", "[form_spectrum]") {
  for (const auto& [name, mesh] : meshes()) {
    INFO(name);
    FormSpectrumOptions o;
    o.k = 24;
    const FormSpectrum sp = form_spectrum(mesh, o);
    SpectrumOptions s0;
    s0.k = 12;
    const Spectrum zero = laplacian_spectrum(mesh, s0);
    const CoarseComplex cx(mesh);
    const SparseMatrix d0 = cx.d0();
    const SparseMatrix star1 = polydec::star1(mesh, refine(mesh), cx);
    int matched = 0;
    for (int j = 1; j < s0.k; ++j) {
      const double lambda = zero.eigenvalues[j];
      if (lambda > sp.eigenvalues[o.k - 1]) break;  // beyond the computed 1-form eigenvalues
      // The 1-form eigenvalues equal to lambda (to solver accuracy) and their eigenvectors.
      std::vector<int> cols;
      double nearest = 1e300;
      for (int i = 0; i < o.k; ++i) {
        nearest = std::min(nearest, std::abs(sp.eigenvalues[i] - lambda) / lambda);
        if (std::abs(sp.eigenvalues[i] - lambda) <= 1e-6 * lambda) cols.push_back(i);
      }
      INFO("0-form eigenvalue " << j << " = " << lambda << ", nearest 1-form relative distance " << nearest);
      REQUIRE(!cols.empty());
      Eigen::MatrixXd Wl(sp.eigenvectors.rows(), long(cols.size()));
      for (size_t c = 0; c < cols.size(); ++c) Wl.col(long(c)) = sp.eigenvectors.col(cols[c]);
      CHECK(outside(Wl, star1, d0 * zero.eigenvectors.col(j)) <= 1e-5);
      for (int c : cols) CHECK(sp.kinds[size_t(c)] == FormKind::Exact);
      ++matched;
    }
    CHECK(matched >= 4);
  }
}

TEST_CASE("unit hexagon sphere: 1-form spectrum approaches l(l+1) with multiplicity 2(2l+1)",
          "[form_spectrum]") {
  // l <= 4: 6 + 10 + 14 + 18 = 48 eigenvalues (no harmonic 1-forms on the sphere).
  std::vector<std::vector<double>> errors;
  // Slightly perturbed (then projected): the exact icosahedral symmetry of hex_sphere makes
  // eigenvalues exactly multiple, and single-vector Lanczos may miss a copy (docs/spectral.md).
  for (int level : {2, 3}) {
    const Mesh mesh = project_to_unit_sphere(add_noise(hex_sphere(level), 0.05, 7));
    FormSpectrumOptions o;
    o.k = 48;
    const FormSpectrum sp = form_spectrum(mesh, o);
    errors.push_back(band_errors(sp.eigenvalues, 0, 4, 2));

    // Half of every band exact, half co-exact.
    int i = 0;
    for (int l = 1; l <= 4; ++l) {
      int exact = 0;
      for (int c = 0; c < 2 * (2 * l + 1); ++c, ++i) exact += sp.kinds[size_t(i)] == FormKind::Exact;
      CHECK(exact == 2 * l + 1);
    }
    for (int l = 1; l <= 4; ++l)
      WARN("hex_sphere(" << level << ") " << mesh.n_faces() << " faces: l = " << l << " max relative error "
                         << errors.back()[size_t(l - 1)]);
  }
  for (int l = 1; l <= 4; ++l) {
    CHECK(errors[0][size_t(l - 1)] <= 0.1);
    CHECK(errors[1][size_t(l - 1)] < 0.5 * errors[0][size_t(l - 1)]);
  }
}

TEST_CASE("form spectra find every copy of a multiple eigenvalue", "[form_spectrum]") {
  // hex_sphere(1) has the icosahedron's symmetry: its 1-form spectrum has exact multiplets (3, 3,
  // 4, ...). The k smallest eigenvalues must be the first k of the k + 3 smallest for every k,
  // also when k cuts through a multiplet (a Lanczos run may return too few copies of one and the
  // next eigenvalue instead; form_spectrum then deflates and searches again).
  const Mesh mesh = hex_sphere(1);
  FormSpectrumOptions o;
  o.degree = 1;
  o.decompose = false;
  o.k = 15;
  const Eigen::VectorXd all = form_spectrum(mesh, o).eigenvalues;
  for (int k = 4; k <= 12; ++k) {
    o.k = k;
    INFO("k = " << k);
    const Eigen::VectorXd ev = form_spectrum(mesh, o).eigenvalues;
    CHECK((ev - all.head(k)).cwiseAbs().maxCoeff() <= 1e-8 * all.maxCoeff());
  }
  // The fourfold multiplet at positions 7..10.
  CHECK(std::abs(all[9] - all[6]) <= 1e-8 * all[6]);
}

TEST_CASE("form spectra do not depend on position, scale (1/s^2) or vertex numbering", "[form_spectrum]") {
  for (const Mesh& mesh : {test::torus(10, 6, 0.15, true), hex_sphere(1)}) {
    for (int degree : {1, 2}) {
      INFO("degree " << degree);
      FormSpectrumOptions o;
      o.degree = degree;
      o.k = 10;
      o.decompose = false;
      const Eigen::VectorXd ev = form_spectrum(mesh, o).eigenvalues;
      const double tol = 1e-7 * ev.maxCoeff();
      const Mesh moved = mesh.with_positions(mesh.positions().rowwise() + Eigen::RowVector3d(3, -7, 11));
      CHECK((form_spectrum(moved, o).eigenvalues - ev).cwiseAbs().maxCoeff() <= tol);
      const double s = 25;
      const Mesh scaled = mesh.with_positions(s * mesh.positions());
      CHECK((s * s * form_spectrum(scaled, o).eigenvalues - ev).cwiseAbs().maxCoeff() <= tol);
      const Mesh renumbered = test::renumbered(mesh, test::random_permutation(mesh.n_vertices(), 17));
      CHECK((form_spectrum(renumbered, o).eigenvalues - ev).cwiseAbs().maxCoeff() <= tol);
    }
  }
}

TEST_CASE("2-form spectrum: one zero on a closed surface, nonzero part converges to the 0-form spectrum",
          "[form_spectrum]") {
  std::vector<double> diff;
  for (int level : {1, 2, 3}) {
    const Mesh mesh = hex_sphere(level);
    FormSpectrumOptions o;
    o.degree = 2;
    o.k = 16;
    const FormSpectrum sp = form_spectrum(mesh, o);
    CHECK(count_zero(sp.eigenvalues, 1.0) == 1);
    CHECK(sp.kinds[0] == FormKind::Harmonic);
    for (int i = 1; i < o.k; ++i) CHECK(sp.kinds[size_t(i)] == FormKind::Exact);
    SpectrumOptions s0;
    s0.k = 16;
    const Spectrum zero = laplacian_spectrum(mesh, s0);
    double d = 0;
    for (int i = 1; i < o.k; ++i) d = std::max(d, std::abs(sp.eigenvalues[i] / zero.eigenvalues[i] - 1));
    diff.push_back(d);
    WARN("hex_sphere(" << level << "): 2-form vs 0-form eigenvalues 1..15, max relative difference " << d);
  }
  CHECK(diff[1] < 0.6 * diff[0]);
  CHECK(diff[2] < 0.6 * diff[1]);
}

TEST_CASE("form spectrum rejects a bad degree or k", "[form_spectrum]") {
  const Mesh mesh = hex_sphere(0);
  FormSpectrumOptions o;
  o.degree = 3;
  CHECK_THROWS_AS(form_spectrum(mesh, o), std::invalid_argument);
  o.degree = 1;
  o.k = 100000;
  CHECK_THROWS_AS(form_spectrum(mesh, o), std::invalid_argument);
}

TEST_CASE("Whitney vectors at the virtual vertices reproduce a constant gradient", "[form_spectrum]") {
  // d0 of a linear function is exactly its gradient's Whitney form on a planar mesh.
  const Mesh mesh = test::planar_grid(6, 5, 0.2, true);
  const Eigen::Vector3d g(0.3, -1.2, 0);
  const Eigen::VectorXd u = mesh.positions() * g;
  const CoarseComplex cx(mesh);
  const Eigen::MatrixX3d U = whitney_vectors_at_virtual_vertices(mesh, refine(mesh), cx.d0() * u);
  for (int f = 0; f < mesh.n_faces(); ++f) CHECK((U.row(f).transpose() - g).norm() <= 1e-10);
}

}  // namespace test_form_spectrum

namespace test_whitney2_face_densities {

TEST_CASE("whitney2_face_densities: the plane's area cochain has density 1 on every face",
          "[form-spectrum]") {
  // Signed areas of the triples (oriented by increasing index) are the cochain of dx ^ dy; P2
  // carries it to the signed areas of the fan triangles (P reproduces affine functions), so
  // integral / area = 1 on counter-clockwise faces.
  for (const Mesh& mesh : {hex_grid(4, 3), add_noise(quad_grid(4, 4), 0.1, 3)}) {
    const Mesh flat = mesh.with_positions(
        (Eigen::MatrixX3d(mesh.positions()) * Eigen::Vector3d(1, 1, 0).asDiagonal()).eval());
    const CoarseComplex cx(flat);
    Eigen::VectorXd c(cx.n_triples());
    for (int t = 0; t < cx.n_triples(); ++t) {
      const Eigen::Vector3d a = flat.position(cx.triples()(t, 0)), b = flat.position(cx.triples()(t, 1)),
                            d = flat.position(cx.triples()(t, 2));
      c[t] = 0.5 * (b - a).cross(d - a).z();
    }
    const Eigen::VectorXd rho = whitney2_face_densities(flat, refine(flat), c);
    REQUIRE(rho.size() == flat.n_faces());
    CHECK((rho.array() - 1.0).abs().maxCoeff() < 1e-12);
    CHECK_THROWS_AS(whitney2_face_densities(flat, refine(flat), Eigen::VectorXd::Zero(c.size() + 1)),
                    std::invalid_argument);
  }
}

}  // namespace test_whitney2_face_densities

namespace test_form_spectrum_mesh_complex {
using namespace test_form_spectrum;

TEST_CASE("mesh complex: 1-form zero eigenvalues count b1, 0-form eigenvalues reappear as exact 1-forms",
          "[form_spectrum][mesh-complex]") {
  for (const auto& [name, mesh] : meshes()) {
    INFO(name);
    const int b1 = first_betti(mesh);
    FormSpectrumOptions o;
    o.complex = DecComplex::Mesh;
    o.k = b1 + 12;
    const FormSpectrum sp = form_spectrum(mesh, o);
    CHECK(sp.rank == mesh.n_edges());
    CHECK(sp.eigenvectors.rows() == mesh.n_edges());
    const double area = surface_area(mesh);
    CHECK(count_zero(sp.eigenvalues, 1 / area) == b1);
    for (int i = 0; i < b1; ++i) CHECK(sp.kinds[size_t(i)] == FormKind::Harmonic);
    // -S = d0^T star1 d0 on the mesh complex too: an eigenfunction x of -S x = lambda M0 x gives the
    // 1-form eigenpair (lambda, d0 x) of K1 w = lambda star1 w.
    SpectrumOptions s0;
    s0.k = 6;
    const Spectrum zero = laplacian_spectrum(mesh, s0);
    const Refinement R = refine(mesh);
    const SparseMatrix d0 = mesh_d0(mesh), star1 = mesh_star1(mesh, R);
    int matched = 0;
    for (int j = 1; j < s0.k; ++j) {
      const double lambda = zero.eigenvalues[j];
      if (lambda > sp.eigenvalues[o.k - 1]) break;
      std::vector<int> cols;
      for (int i = 0; i < o.k; ++i)
        if (std::abs(sp.eigenvalues[i] - lambda) <= 1e-6 * lambda) cols.push_back(i);
      INFO("0-form eigenvalue " << j << " = " << lambda);
      REQUIRE(!cols.empty());
      Eigen::MatrixXd Wl(sp.eigenvectors.rows(), long(cols.size()));
      for (size_t c = 0; c < cols.size(); ++c) Wl.col(long(c)) = sp.eigenvectors.col(cols[c]);
      CHECK(outside(Wl, star1, d0 * zero.eigenvectors.col(j)) <= 1e-5);
      ++matched;
    }
    CHECK(matched >= 2);
  }
}

TEST_CASE("unit sphere: 1- and 2-form spectra of both complexes approach l(l+1)", "[form_spectrum][mesh-complex]") {
  // Errors of the bands l = 1..3 on two refinements, for the complete and the mesh complex.
  for (DecComplex complex : {DecComplex::Complete, DecComplex::Mesh}) {
    std::vector<std::vector<double>> e1, e2;
    for (int level : {2, 3}) {
      const Mesh mesh = project_to_unit_sphere(add_noise(hex_sphere(level), 0.05, 7));
      FormSpectrumOptions o;
      o.complex = complex;
      o.k = 30;  // l <= 3: 2 (3 + 5 + 7)
      o.decompose = complex == DecComplex::Mesh;
      const FormSpectrum sp = form_spectrum(mesh, o);
      e1.push_back(band_errors(sp.eigenvalues, 0, 3, 2));
      if (o.decompose) {
        int i = 0;
        for (int l = 1; l <= 3; ++l) {
          int exact = 0;
          for (int c = 0; c < 2 * (2 * l + 1); ++c, ++i) exact += sp.kinds[size_t(i)] == FormKind::Exact;
          CHECK(exact == 2 * l + 1);
        }
      }
      FormSpectrumOptions o2 = o;
      o2.degree = 2;
      o2.k = 16;  // the zero, then l <= 3
      o2.decompose = false;
      const FormSpectrum sp2 = form_spectrum(mesh, o2);
      CHECK(count_zero(sp2.eigenvalues, 1.0) == 1);
      e2.push_back(band_errors(sp2.eigenvalues, 1, 3, 1));
      for (int l = 1; l <= 3; ++l)
        WARN(to_string(complex) << " complex, hex_sphere(" << level << "), " << mesh.n_faces() << " faces: l = " << l
                                << ", 1-forms max relative error " << e1.back()[size_t(l - 1)] << ", 2-forms "
                                << e2.back()[size_t(l - 1)]);
    }
    for (int l = 1; l <= 3; ++l) {
      CHECK(e1[1][size_t(l - 1)] < 0.5 * e1[0][size_t(l - 1)]);
      CHECK(e2[1][size_t(l - 1)] < 0.5 * e2[0][size_t(l - 1)]);
    }
  }
}

}  // namespace test_form_spectrum_mesh_complex
