// operators/registry/volume_laplacians.cpp — the volume method registry, gradient and divergence.
#include "polydec/operators/registry/volume_laplacians.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "polydec/dec/volume/whitney.h"
#include "polydec/operators/comparison/volume_diamond.h"
#include "polydec/operators/detail/volume_refinement_in_use.h"

namespace polydec {

namespace volume_laplacians_detail {
namespace {

OperatorSet refined_operators(const VolumeMesh& mesh, CellPointRule rule,
                              const VolumeOperatorOptions& options) {
  VolumeRefinementOptions ropt;
  ropt.cell_rule = rule;
  ropt.threads = options.threads;
  detail::VolumeRefinementInUse in_use(mesh, options.refinement, ropt);
  const VolumeRefinement& r = in_use.get();
  VolumeLaplacian L = assemble_volume_laplacian(mesh, r, nullptr, options.threads);
  OperatorSet ops;
  ops.S.swap(L.S);
  ops.M.swap(L.M);
  ops.M_lumped = std::move(L.M_lumped);
  if (options.with_gradient) {
    Eigen::VectorXd volumes;
    ops.G = volume_gradient(mesh, r, &volumes);
    ops.D = volume_divergence(ops.G, volumes);
  }
  ops.sub_tet_quality = r.quality;
  if (options.keep_refinement) ops.volume_refinement = in_use.release();
  return ops;
}

// One row per method: a new method is one more row.
struct VolumeMethod {
  const char* name;
  OperatorSet (*build)(const VolumeMesh&, const VolumeOperatorOptions&);
};
const VolumeMethod kVolumeMethods[] = {
    {"ours",
     [](const VolumeMesh& m, const VolumeOperatorOptions& o) {
       return refined_operators(m, CellPointRule::SquaredVolume, o);
     }},
    {"polylaplace",
     [](const VolumeMesh& m, const VolumeOperatorOptions& o) {
       return refined_operators(m, CellPointRule::PolyLaplace, o);
     }},
    {"diamond",
     [](const VolumeMesh& m, const VolumeOperatorOptions& o) { return volume_diamond_operators(m, o); }},
};

const VolumeMethod* find_volume_method(const std::string& name) {
  for (const auto& m : kVolumeMethods)
    if (name == m.name) return &m;
  return nullptr;
}

}  // namespace
}  // namespace volume_laplacians_detail

std::vector<std::string> volume_laplacian_names() {
  std::vector<std::string> names;
  for (const auto& m : volume_laplacians_detail::kVolumeMethods) names.emplace_back(m.name);
  return names;
}

LaplacianChoice parse_volume_laplacian(const std::string& spec) {
  if (!volume_laplacians_detail::find_volume_method(spec))
    throw std::invalid_argument(fmt::format("unknown volume Laplacian '{}' (known: {})", spec,
                                            fmt::join(volume_laplacian_names(), ", ")));
  LaplacianChoice c;
  c.method = spec;
  return c;
}

OperatorSet build_volume_operators(const VolumeMesh& mesh, const LaplacianChoice& choice,
                                   const VolumeOperatorOptions& options) {
  const auto* m = volume_laplacians_detail::find_volume_method(choice.method);
  if (!m || choice.has_parameter)
    throw std::invalid_argument(fmt::format("unknown volume Laplacian '{}' (known: {})",
                                            choice.canonical_name(),
                                            fmt::join(volume_laplacian_names(), ", ")));
  if (options.refinement) {
    const CellPointRule rule = choice.method == "polylaplace" ? CellPointRule::PolyLaplace : CellPointRule::SquaredVolume;
    const VolumeRefinementOptions& given = options.refinement->options;
    const VolumeRefinementOptions defaults;
    if (given.cell_rule != rule || given.degenerate_tolerance != defaults.degenerate_tolerance ||
        given.planarity_tolerance != defaults.planarity_tolerance)
      throw std::invalid_argument(fmt::format(
          "build_volume_operators: method '{}' needs a refinement with the {} cell point and the default "
          "tolerances, got {} (degenerate tolerance {:g}, planarity tolerance {:g})",
          choice.method, to_string(rule), to_string(given.cell_rule), given.degenerate_tolerance,
          given.planarity_tolerance));
    check_refinement(mesh, *options.refinement, "build_volume_operators");
  }
  OperatorSet ops = m->build(mesh, options);
  ops.name = m->name;
  ops.n_input_vertices = mesh.n_vertices();
  ops.mean_edge_length = mesh.mean_edge_length();
  return ops;
}

SparseMatrix volume_gradient(const VolumeMesh& mesh, const VolumeRefinement& refinement, Eigen::VectorXd* volumes) {
  check_refinement(mesh, refinement, "volume_gradient");
  std::vector<LengthPower> quantities{{-1, "the gradient's entries"}};
  if (volumes) quantities.push_back({3, "the sub-tetrahedra's volumes"});
  check_length_powers(mesh, quantities);
  const std::vector<RefinedTet> tets = refined_tets(mesh, refinement);
  const int n_refined = mesh.n_vertices() + mesh.n_faces() + mesh.n_cells();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(tets.size() * 12);
  if (volumes) volumes->setZero(Eigen::Index(tets.size()));
  for (size_t k = 0; k < tets.size(); ++k) {
    if (tets[k].quality == SubTet::Degenerate) continue;
    Eigen::Vector3d p[4];
    for (int a = 0; a < 4; ++a) p[a] = refined_position(mesh, refinement, tets[k].v[a]);
    if (volumes) (*volumes)[Eigen::Index(k)] = std::abs(tet_signed_volume(p[0], p[1], p[2], p[3]));
    const Matrix34d g = tet_hat_gradients(p[0], p[1], p[2], p[3]);
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) t.emplace_back(int(3 * k) + d, tets[k].v[a], g(d, a));
  }
  SparseMatrix Gtet(3 * Eigen::Index(tets.size()), n_refined);
  Gtet.setFromTriplets(t.begin(), t.end());
  return SparseMatrix(Gtet * volume_prolongation(mesh, refinement));
}

Eigen::VectorXd sub_tet_volumes(const VolumeMesh& mesh, const VolumeRefinement& refinement) {
  check_refinement(mesh, refinement, "sub_tet_volumes");
  check_length_power(mesh, 3, "the sub-tetrahedra's volumes");
  const std::vector<RefinedTet> tets = refined_tets(mesh, refinement);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(Eigen::Index(tets.size()));
  for (size_t k = 0; k < tets.size(); ++k)
    if (tets[k].quality != SubTet::Degenerate)
      w[Eigen::Index(k)] = std::abs(tet_signed_volume(refined_position(mesh, refinement, tets[k].v[0]),
                                                      refined_position(mesh, refinement, tets[k].v[1]),
                                                      refined_position(mesh, refinement, tets[k].v[2]),
                                                      refined_position(mesh, refinement, tets[k].v[3])));
  return w;
}

SparseMatrix volume_divergence(const SparseMatrix& G, const Eigen::VectorXd& sub_tet_volumes) {
  if (G.rows() != 3 * sub_tet_volumes.size())
    throw std::invalid_argument("volume divergence: one volume per three gradient rows expected");
  Eigen::VectorXd w(G.rows());
  for (Eigen::Index k = 0; k < sub_tet_volumes.size(); ++k)
    w.segment<3>(3 * k).setConstant(sub_tet_volumes[k]);
  return SparseMatrix(-(G.transpose() * w.asDiagonal()));
}

}  // namespace polydec
