// apps/applications/smoothing.cpp — conformalized mean curvature flow (eq. 28).
#include "polydec/apps/applications/smoothing.h"

#include <cmath>
#include <stdexcept>

namespace polydec {

// Re-assembles the mass on moved positions: for the virtual-vertex methods with the kept face
// pattern and refinement options, for other methods through build_operators.
struct CurvatureFlow::MassAssembler {
  bool virtual_vertex = false;
  RefinementOptions refinement_options;
  FacePattern pattern;
};

CurvatureFlow::CurvatureFlow(const Mesh& mesh, const SmoothingOptions& options, const LaplacianChoice& choice)
    : mesh_(mesh), options_(options), choice_(choice), assembler_(std::make_shared<MassAssembler>()) {
  const OperatorSet ops = build_operators(mesh, choice, false);
  if (ops.domain.n_vertices() != mesh.n_vertices())
    throw std::invalid_argument(
        "curvature flow: Laplacian '" + ops.name +
        "' lives on a refined mesh; the flow needs operators on the input's vertices");
  if (!options.lumped_mass && ops.M.size() == 0)
    throw std::invalid_argument("curvature flow: Laplacian '" + ops.name + "' defines no unlumped mass");
  if (!(options.time_step >= 0) || !std::isfinite(options.time_step))
    throw std::invalid_argument("curvature flow: the time step must be finite and >= 0 (0: automatic)");
  name_ = ops.name;
  S0_ = ops.S;
  if (choice.method == "ours" || choice.method == "centroid") {
    assembler_->virtual_vertex = true;
    assembler_->refinement_options.rule =
        choice.method == "ours" ? VirtualVertexRule::SquaredArea : VirtualVertexRule::Centroid;
    assembler_->pattern = face_pattern(mesh);
  }
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (mesh.vertex_faces(v).empty())
      throw std::invalid_argument("curvature flow: vertex " + std::to_string(v) + " belongs to no face");
  assemble_mass();
  area_ = M_lumped_.sum();
  if (!(area_ > 0)) throw std::invalid_argument("curvature flow: the mesh has zero area");
  eps_ = options.time_step > 0 ? options.time_step : 1e-3 * area_;
}

void CurvatureFlow::assemble_mass() {
  const int nv = mesh_.n_vertices();
  SparseMatrix M;
  if (assembler_->virtual_vertex) {
    LaplacianParts parts;
    parts.stiffness = false;
    parts.mass = !options_.lumped_mass;
    parts.lumped_mass = true;
    Laplacian L =
        assemble_laplacian(mesh_, refine(mesh_, assembler_->refinement_options), parts, &assembler_->pattern);
    M_lumped_ = std::move(L.M_lumped);
    M = std::move(L.M);
  } else {
    OperatorSet ops = build_operators(mesh_, choice_, false);
    M_lumped_ = std::move(ops.M_lumped);
    M = std::move(ops.M);
  }
  if (options_.lumped_mass) {
    M_.resize(nv, nv);
    M_.setIdentity();
    M_.diagonal() = M_lumped_;
  } else {
    M_ = std::move(M);
  }
}

const Mesh& CurvatureFlow::step() {
  // (M^t - eps S^0) X' = M^t X; the pattern of M^t lies in that of S^0, so refactor() applies.
  const SparseMatrix A = M_ - eps_ * S0_;
  if (chol_)
    chol_->refactor(A);
  else
    chol_ = std::make_unique<SparseCholesky>(A, "M^t - eps S^0 (curvature flow)");
  Eigen::MatrixX3d X = chol_->solve(Eigen::MatrixXd(M_ * mesh_.positions()));
  if (!X.allFinite()) throw SolverError("curvature flow: the step produced non-finite positions");
  mesh_ = mesh_.with_positions(X);
  // New mass, then translate the area centroid to the origin and restore the input's area. The
  // mass is quadratic in the positions and translation-invariant: rescaling it by s^2 is exact.
  assemble_mass();
  const double area = M_lumped_.sum();
  if (!(area > 0)) throw SolverError("curvature flow: the surface collapsed to zero area");
  const Eigen::RowVector3d c = (M_lumped_.transpose() * X) / area;
  const double s = std::sqrt(area_ / area);
  X = s * (X.rowwise() - c);
  mesh_ = mesh_.with_positions(X);
  M_ *= s * s;
  M_lumped_ *= s * s;
  return mesh_;
}

std::vector<Mesh> curvature_flow(const Mesh& mesh, int steps, const SmoothingOptions& options,
                                 const LaplacianChoice& choice) {
  if (steps < 0) throw std::invalid_argument("curvature flow: negative number of steps");
  CurvatureFlow flow(mesh, options, choice);
  std::vector<Mesh> out{mesh};
  for (int i = 0; i < steps; ++i) out.push_back(flow.step());
  return out;
}

}  // namespace polydec
