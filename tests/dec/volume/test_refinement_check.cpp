// tests/dec/volume/test_refinement_check.cpp — a refinement that does not belong to the mesh it is passed
// with (another mesh's, a default-constructed or a truncated one) is refused with
// std::invalid_argument naming the function, before anything is read, by the surface and volume
// functions taking a mesh with its refinement; the mesh's own refinement still gives operators with
// their defining properties (constants in the kernel, partition of unity, exact linear gradients).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "polydec/dec/surface/complex.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/surface/hodge_star.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/dec/surface/refinement.h"
#include "polydec/dec/volume/complex.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/dec/volume/refinement.h"
#include "polydec/operators/surface/gradient.h"
#include "polydec/operators/surface/laplacian.h"
#include "polydec/operators/volume/laplacian.h"
#include "polydec/operators/registry/volume_laplacians.h"

using namespace polydec;

namespace test_refinement_check {
namespace {

// `call` throws std::invalid_argument whose message starts with "<name>: the refinement does not
// belong to this mesh".
template <class Call>
void refused(const std::string& name, Call&& call) {
  INFO(name);
  CHECK_THROWS_AS(call(), std::invalid_argument);
  CHECK_THROWS_WITH(call(), Catch::StartsWith(name + ": the refinement does not belong to this mesh"));
}

// Largest |row sum| of A relative to its largest |entry|.
double relative_row_sum(const SparseMatrix& A) {
  return (A * Eigen::VectorXd::Ones(A.cols())).cwiseAbs().maxCoeff() / A.coeffs().cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("volume functions refuse a refinement of another mesh", "[refinement-check][volume]") {
  const VolumeMesh mesh = hex_grid_volume(3, 2, 2, VolumeJitter{0.2, 7});
  const VolumeRefinement own = refine_volume(mesh);
  const SimplexComplex3 coarse = volume_coarse_complex(mesh), refined = volume_refined_complex(mesh, own);
  // Fewer faces and cells (another grid), the same counts with other cells (6 tetrahedra per cube:
  // more faces), a default-constructed refinement, and truncated ones.
  const VolumeRefinement smaller = refine_volume(hex_grid_volume(2, 2, 2));
  const VolumeRefinement tets = refine_volume(tet_grid_volume(1, 1, 2));
  const VolumeRefinement empty;
  VolumeRefinement short_tets = own, short_weights = own, shifted = own;
  short_tets.tets.pop_back();
  short_weights.cell_weights.pop_back();
  shifted.tet_offsets[1] += 1;  // cell 0 one sub-tetrahedron too many, cell 1 one short
  for (const VolumeRefinement* bad : std::initializer_list<const VolumeRefinement*>{
           &smaller, &tets, &empty, &short_tets, &short_weights, &shifted}) {
    refused("assemble_volume_laplacian", [&] { assemble_volume_laplacian(mesh, *bad); });
    refused("cell_matrices", [&] {  // over all cells, as an assembly would call it
      Eigen::MatrixXd S, M;
      for (int c = 0; c < mesh.n_cells(); ++c) cell_matrices(mesh, *bad, c, &S, &M);
    });
    refused("volume_prolongation", [&] { volume_prolongation(mesh, *bad); });
    refused("volume_prolongation_k", [&] { volume_prolongation_k(mesh, *bad, coarse, refined, 1); });
    refused("volume_refined_star", [&] { volume_refined_star(mesh, *bad, refined, 2); });
    refused("volume_refined_complex", [&] { volume_refined_complex(mesh, *bad); });
    refused("volume_dec", [&] { volume_dec(mesh, *bad, 1); });
    refused("refined_tets", [&] { refined_tets(mesh, *bad); });
    refused("volume_gradient", [&] { volume_gradient(mesh, *bad); });
    refused("sub_tet_volumes", [&] { sub_tet_volumes(mesh, *bad); });
  }
  // Per-cell and per-vertex functions check what they read: cell 0's weights and sub-tetrahedra
  // (truncations at the end do not concern it), the point arrays and the index's range.
  refused("cell_matrices", [&] { cell_matrices(mesh, shifted, 0, nullptr, nullptr); });
  refused("cell_matrices", [&] { cell_matrices(mesh, short_tets, mesh.n_cells() - 1, nullptr, nullptr); });
  CHECK_NOTHROW(cell_matrices(mesh, short_tets, 0, nullptr, nullptr));
  CHECK_THROWS_WITH(cell_matrices(mesh, own, mesh.n_cells(), nullptr, nullptr),
                    Catch::Contains("cell_matrices: cell") && Catch::Contains("out of range"));
  refused("refined_position", [&] { refined_position(mesh, smaller, mesh.n_vertices()); });
  refused("refined_position", [&] { refined_position(mesh, empty, mesh.n_vertices()); });
  const int n_refined = mesh.n_vertices() + mesh.n_faces() + mesh.n_cells();
  CHECK_THROWS_WITH(refined_position(mesh, own, n_refined),
                    Catch::Contains("refined_position: refined vertex"));
  // The message names the first mismatch with both counts.
  CHECK_THROWS_WITH(volume_gradient(mesh, smaller),
                    Catch::Contains(std::to_string(smaller.face_points.rows()) + " face points for " +
                                    std::to_string(mesh.n_faces()) + " faces"));
  CHECK_THROWS_WITH(refined_tets(mesh, shifted), Catch::Contains("cell 0 has"));
  CHECK_THROWS_WITH(refined_tets(mesh, short_weights), Catch::Contains("cell weights for offsets ending at"));

  // The mesh's own refinement: S 1 = 0, M sums to the volume of [0, 1]^3, P's rows are partitions
  // of unity, the cell matrices are the assembled ones' pieces (cell 0's rows sum to 0), the
  // sub-tetrahedra are those of the refinement, and a linear function's gradient is exact.
  const VolumeLaplacian L = assemble_volume_laplacian(mesh, own);
  CHECK(relative_row_sum(L.S) < 1e-12);
  CHECK(L.M_lumped.sum() == Approx(1.0).epsilon(1e-12));
  const SparseMatrix P = volume_prolongation(mesh, own);
  CHECK((P * Eigen::VectorXd::Ones(P.cols()) - Eigen::VectorXd::Ones(P.rows())).cwiseAbs().maxCoeff() <
        1e-12);
  Eigen::MatrixXd Sc;
  cell_matrices(mesh, own, 0, &Sc, nullptr);
  CHECK(Sc.rowwise().sum().cwiseAbs().maxCoeff() < 1e-12 * Sc.cwiseAbs().maxCoeff());
  CHECK(refined_tets(mesh, own).size() == own.tets.size());
  CHECK(volume_prolongation_k(mesh, own, coarse, refined, 1).rows() == refined.n_simplices(1));
  const Eigen::Vector3d a(0.3, -1.2, 2.0);
  const Eigen::VectorXd u = mesh.positions() * a;
  const Eigen::VectorXd g = volume_gradient(mesh, own) * u;
  double err = 0;
  for (long t = 0; t < g.size() / 3; ++t)
    if (own.tets[size_t(t)] != SubTet::Degenerate) err = std::max(err, (g.segment<3>(3 * t) - a).norm());
  CHECK(err < 1e-10 * a.norm());
  CHECK(refined_position(mesh, own, n_refined - 1) == own.cell_points.row(mesh.n_cells() - 1).transpose());
}

TEST_CASE("surface functions refuse a refinement of another mesh", "[refinement-check]") {
  const Mesh mesh = hex_grid(4, 3);
  const Refinement own = refine(mesh);
  const CoarseComplex complex(mesh);
  // Another grid (other counts), a default-constructed refinement, truncated ones.
  const Refinement other = refine(quad_grid(3, 3));
  const Refinement empty;
  Refinement short_fan = own, short_points = own;
  short_fan.fan.pop_back();
  short_points.virtual_points.conservativeResize(mesh.n_faces() - 1, 3);
  for (const Refinement* bad :
       std::initializer_list<const Refinement*>{&other, &empty, &short_fan, &short_points}) {
    refused("assemble_laplacian", [&] { assemble_laplacian(mesh, *bad); });
    refused("stiffness", [&] { stiffness(mesh, *bad); });
    refused("prolongation", [&] { prolongation(mesh, *bad); });
    refused("prolongation1", [&] { prolongation1(mesh, *bad, complex); });
    refused("refined_star1", [&] { refined_star1(mesh, *bad); });
    refused("hodge_stars", [&] { hodge_stars(mesh, *bad, complex); });
    refused("star2", [&] { star2(mesh, *bad, complex); });
    refused("gradient", [&] { gradient(mesh, *bad); });
    refused("divergence", [&] { divergence(mesh, *bad); });
    refused("refined_mesh", [&] { refined_mesh(mesh, *bad); });
  }
  CHECK_THROWS_WITH(gradient(mesh, short_fan),
                    Catch::Contains(std::to_string(mesh.n_halfedges() - 1) + " fan triangles for " +
                                    std::to_string(mesh.n_halfedges()) + " halfedges"));

  // The mesh's own refinement: S 1 = 0, P's rows are partitions of unity, and the gradient of a
  // linear function in the mesh's plane (z = 0) is exact on every non-degenerate fan triangle.
  const Laplacian L = assemble_laplacian(mesh, own);
  CHECK(relative_row_sum(L.S) < 1e-12);
  const SparseMatrix P = prolongation(mesh, own);
  CHECK((P * Eigen::VectorXd::Ones(P.cols()) - Eigen::VectorXd::Ones(P.rows())).cwiseAbs().maxCoeff() <
        1e-12);
  const Eigen::Vector3d a(0.7, -1.3, 0.0);
  const Eigen::VectorXd g = gradient(mesh, own) * (mesh.positions() * a);
  double err = 0;
  for (int h = 0; h < mesh.n_halfedges(); ++h)
    if (own.fan[size_t(h)] != FanTriangle::Degenerate) err = std::max(err, (g.segment<3>(3 * h) - a).norm());
  CHECK(err < 1e-10 * a.norm());
}

}  // namespace test_refinement_check
