// operators/comparison/diamond.cpp — the Diamond Laplacian on polygon meshes [BBA21] and the coarsening shared
// with the volume version (operators/comparison/volume_diamond.cpp).
#include "polydec/operators/comparison/diamond.h"

#include <algorithm>

#include "polydec/dec/surface/prolongation.h"

namespace polydec {

void coarsen_diamonds(const FineDiamonds& fine, const SparseMatrix& P, SparseMatrix& S, SparseMatrix& M,
                      Eigen::VectorXd& M_lumped, SparseMatrix* G, SparseMatrix* D) {
  const long n_rows = 3 * long(fine.weight.size());
  SparseMatrix Gf(n_rows, fine.n_points);
  Gf.setFromTriplets(fine.gradient.begin(), fine.gradient.end());
  const SparseMatrix Gc = Gf * P;
  Eigen::VectorXd w(n_rows);
  for (long k = 0; k < fine.weight.size(); ++k) w.segment<3>(3 * k).setConstant(fine.weight[k]);
  const SparseMatrix Dc = -(SparseMatrix(Gc.transpose()) * w.asDiagonal());
  S = Dc * Gc;
  M = SparseMatrix(P.transpose()) * fine.mass.asDiagonal() * P;
  M_lumped = P.transpose() * fine.mass;
  if (G) *G = Gc;
  if (D) *D = Dc;
}

void fill_diamond_operators(const FineDiamonds& fine, const SparseMatrix& P, bool with_gradient,
                            OperatorSet& ops) {
  ops.n_degenerate_triangles = fine.n_degenerate;
  ops.n_folded_triangles = fine.n_folded;
  coarsen_diamonds(fine, P, ops.S, ops.M, ops.M_lumped, with_gradient ? &ops.G : nullptr,
                   with_gradient ? &ops.D : nullptr);
}

namespace {

Eigen::Vector3d face_vector_area(const Mesh& mesh, int f) {
  const auto face = mesh.face(f);
  const Eigen::Vector3d o = mesh.position(face[0]);
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (size_t k = 1; k + 1 < face.size(); ++k)
    a += (mesh.position(face[k]) - o).cross(mesh.position(face[k + 1]) - o);
  return a / 2;
}

}  // namespace

FineDiamonds surface_diamonds(const Mesh& mesh, const Refinement& refinement) {
  check_refinement(mesh, refinement, "surface_diamonds");
  const int nV = mesh.n_vertices(), nF = mesh.n_faces(), nE = mesh.n_edges();
  std::vector<int> edge_halfedge(nE, -1);
  for (int h = 0; h < mesh.n_halfedges(); ++h)
    if (edge_halfedge[mesh.halfedge_edge(h)] < 0) edge_halfedge[mesh.halfedge_edge(h)] = h;

  FineDiamonds d;
  d.n_points = nV + nF;
  d.weight = Eigen::VectorXd::Zero(nE);
  d.mass = Eigen::VectorXd::Zero(nV + nF);
  d.gradient.reserve(size_t(nE) * 15);
  for (int e = 0; e < nE; ++e) {
    const int h = edge_halfedge[e], o = mesh.halfedge_opposite(h);
    const int i = mesh.halfedge_source(h), j = mesh.halfedge_target(h), f = mesh.halfedge_face(h);
    const int g = o >= 0 ? mesh.halfedge_face(o) : -1;
    const Eigen::Vector3d xi = mesh.position(i), xj = mesh.position(j);
    const Eigen::Vector3d xf = refinement.virtual_points.row(f).transpose();
    const Eigen::Vector3d xg =
        g >= 0 ? Eigen::Vector3d(refinement.virtual_points.row(g).transpose()) : 0.5 * (xi + xj);
    // Diagonals: d1 along the edge, d2 from the right tip to the left one; a = d1 x d2 / 2 is the
    // vector area of the closed quadrilateral (x_i, x_g, x_j, x_f).
    const Eigen::Vector3d d1 = xj - xi, d2 = xf - xg, a2 = d1.cross(d2);
    const double twice_area = a2.norm();
    if (!(twice_area > kDiamondDegenerateTolerance * std::max(d1.squaredNorm(), d2.squaredNorm()))) {
      ++d.n_degenerate;
      continue;
    }
    Eigen::Vector3d faces_normal = face_vector_area(mesh, f);
    if (g >= 0) faces_normal += face_vector_area(mesh, g);
    if (a2.dot(faces_normal) < 0) ++d.n_folded;
    const Eigen::Vector3d n = a2 / twice_area;
    // g . d1 = u_j - u_i and g . d2 = u_f - u_g, g in the plane orthogonal to n (Green's formula).
    const Eigen::Vector3d cu = d2.cross(n) / twice_area, cv = n.cross(d1) / twice_area;
    const double area = twice_area / 2;
    for (int r = 0; r < 3; ++r) {
      const int row = 3 * e + r;
      d.gradient.emplace_back(row, j, cu[r]);
      d.gradient.emplace_back(row, i, -cu[r]);
      d.gradient.emplace_back(row, nV + f, cv[r]);
      if (g >= 0) {
        d.gradient.emplace_back(row, nV + g, -cv[r]);
      } else {  // the edge midpoint
        d.gradient.emplace_back(row, i, -0.5 * cv[r]);
        d.gradient.emplace_back(row, j, -0.5 * cv[r]);
      }
    }
    d.weight[e] = area;
    const double share = g >= 0 ? area / 4 : area / 3;
    d.mass[i] += share;
    d.mass[j] += share;
    d.mass[nV + f] += share;
    if (g >= 0) d.mass[nV + g] += share;
  }
  return d;
}

OperatorSet diamond_operators(const Mesh& mesh, bool with_gradient) {
  OperatorSet ops;
  ops.domain = mesh;
  ops.n_input_vertices = mesh.n_vertices();
  const Refinement r = refine(mesh);
  ops.quality = r.quality;
  fill_diamond_operators(surface_diamonds(mesh, r), prolongation(mesh, r), with_gradient, ops);
  return ops;
}

}  // namespace polydec
