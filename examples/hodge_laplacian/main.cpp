// examples/hodge_laplacian/main.cpp — the Hodge Laplacian of 1-forms, composed from d0, d1 and the
// Hodge stars (docs/feec.md), applied to a field:
//   K = d1^T star2 d1 + star1 d0 M0^-1 d0^T star1     (the weak form; M0 the lumped star0),
// on a mesh file (argument) or a generated sphere of hexagons and pentagons. Checks two identities the
// composition must satisfy and exits 1 when one fails:
//   K d0 f = star1 d0 M0^-1 (-S f)     (d1 d0 = 0, and -d0^T star1 d0 = -S: paper eq. 19, 27),
//   the energy (d0 f)^T K (d0 f) = (S f)^T M0^-1 (S f).
#include <polydec/dec/surface/complex.h>
#include <polydec/dec/mesh/generators.h>
#include <polydec/dec/surface/hodge_star.h>
#include <polydec/dec/io/mesh_io.h>
#include <polydec/dec/surface/refinement.h>
#include <polydec/operators/surface/laplacian.h>

#include <cstdio>
#include <exception>

using namespace polydec;

int main(int argc, char** argv) try {
  const Mesh mesh = argc > 1 ? read_mesh(argv[1]) : hex_sphere(2);
  const Refinement r = refine(mesh);
  const CoarseComplex K(mesh);
  const HodgeStars H = hodge_stars(mesh, r, K);
  const Eigen::SparseMatrix<double> d0 = K.d0(), d1 = K.d1();
  const Eigen::VectorXd M0inv = H.star0_lumped.cwiseInverse();

  // The operator, applied without forming it: K w.
  auto apply = [&](const Eigen::VectorXd& w) -> Eigen::VectorXd {
    const Eigen::VectorXd curl_part = d1.transpose() * (H.star2 * (d1 * w));
    const Eigen::VectorXd div = d0.transpose() * (H.star1 * w);
    return curl_part + H.star1 * (d0 * M0inv.cwiseProduct(div));
  };

  // A field: the exact 1-form of f = x^2 - y z.
  const Eigen::MatrixX3d& X = mesh.positions();
  const Eigen::VectorXd f = X.col(0).array().square() - X.col(1).array() * X.col(2).array();
  const Eigen::VectorXd w = d0 * f;
  const Eigen::VectorXd Kw = apply(w);

  const Laplacian L = assemble_laplacian(mesh, r);
  const Eigen::VectorXd expected = H.star1 * (d0 * M0inv.cwiseProduct(-(L.S * f)));
  const double rel = (Kw - expected).norm() / expected.norm();
  const double energy = w.dot(Kw);
  const double energy_expected = (L.S * f).cwiseProduct(M0inv).dot(L.S * f);

  std::printf("mesh: %d vertices, %d faces; |C1| = %d pairs, |C2| = %d triples\n", mesh.n_vertices(),
              mesh.n_faces(), K.n_pairs(), K.n_triples());
  std::printf("|K d0 f - star1 d0 M0^-1 (-S f)| / |...| = %.3e\n", rel);
  std::printf("w^T K w = %.12g, |M0^-1/2 S f|^2 = %.12g\n", energy, energy_expected);
  const bool ok = rel < 1e-10 && std::abs(energy - energy_expected) <= 1e-10 * std::abs(energy_expected);
  std::printf("%s\n", ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "hodge_laplacian: %s\n", e.what());
  return 1;
}
