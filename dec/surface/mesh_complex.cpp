// dec/surface/mesh_complex.cpp — the mesh complex's d0, d1, the commuting prolongations P1, P2 and
// the stars star1, star2 (dec/surface/mesh_complex.h), face by face through polygon_cochain_maps.
#include "polydec/dec/surface/mesh_complex.h"

#include <Eigen/Geometry>
#include <stdexcept>
#include <vector>

#include "polydec/dec/surface/whitney.h"

namespace polydec {

namespace {

using Triplet = Eigen::Triplet<double>;

// +1 when face f's side from corner k to corner k+1 runs along its mesh edge (i -> j, i < j).
int side_sign(const Mesh& mesh, int h) { return mesh.halfedge_source(h) < mesh.halfedge_target(h) ? 1 : -1; }

Eigen::Vector3d virtual_point(const Refinement& refinement, int f) { return refinement.virtual_points.row(f).transpose(); }

// The kernel of face f.
PolygonCochainMaps face_maps(const Mesh& mesh, const Refinement& refinement, const Eigen::VectorXd& areas, int f,
                             SpokeRule rule) {
  const int h0 = mesh.face_offsets()[f], n = mesh.face_size(f);
  return polygon_cochain_maps({refinement.weights.data() + h0, size_t(n)}, {areas.data() + h0, size_t(n)}, rule);
}

void check_sizes(const Mesh& mesh, const Refinement& refinement, const char* caller) {
  if (int(refinement.weights.size()) != mesh.n_halfedges() || int(refinement.fan.size()) != mesh.n_halfedges() ||
      refinement.virtual_points.rows() != mesh.n_faces())
    throw std::invalid_argument(std::string(caller) + ": the refinement does not belong to this mesh");
}

}  // namespace

DecComplex parse_dec_complex(const std::string& name) {
  if (name == "complete") return DecComplex::Complete;
  if (name == "mesh") return DecComplex::Mesh;
  throw std::invalid_argument("unknown complex '" + name + "' (complete, mesh)");
}

std::string to_string(DecComplex complex) { return complex == DecComplex::Mesh ? "mesh" : "complete"; }

SpokeRule parse_spoke_rule(const std::string& name) {
  if (name == "area") return SpokeRule::AreaConsistent;
  if (name == "minimum-norm") return SpokeRule::MinimumNorm;
  throw std::invalid_argument("unknown spoke rule '" + name + "' (area, minimum-norm)");
}

std::string to_string(SpokeRule rule) { return rule == SpokeRule::MinimumNorm ? "minimum-norm" : "area"; }

PolygonCochainMaps polygon_cochain_maps(std::span<const double> weights, std::span<const double> fan_areas,
                                        SpokeRule rule) {
  const int n = int(weights.size());
  if (n < 3 || fan_areas.size() != weights.size())
    throw std::invalid_argument("polygon_cochain_maps: n >= 3 weights and as many fan areas expected");
  PolygonCochainMaps K;
  K.fractions.resize(n);
  double total = 0;
  for (double a : fan_areas) total += a;
  const bool by_area = rule == SpokeRule::AreaConsistent && total > 0;
  for (int k = 0; k < n; ++k) K.fractions[k] = by_area ? fan_areas[size_t(k)] / total : 1.0 / n;
  // Unshifted spoke i: u(x_f) - u_i = sum_j w_j (e_i + .. + e_{j-1}), i.e. side i + m weighs
  // a_m = w_{i+m+1} + .. + w_{i+n-1}. Shifting spoke i by gamma_i (times the cycle 1^T) gives fan
  // triangle k the share w_k + gamma_{k+1} - gamma_k, so gamma_k = gamma_0 + sum_{l<k} (alpha_l - w_l).
  K.spokes.resize(n, n);
  double shift_sum = 0, delta = 0;
  for (int i = 0; i < n; ++i) {
    double tail = 0;
    for (int m = n - 1; m >= 0; --m) {
      K.spokes(i, (i + m) % n) = tail + delta;
      tail += weights[size_t((i + m) % n)];
    }
    shift_sum += K.spokes.row(i).sum();
    delta += K.fractions[i] - weights[size_t(i)];
  }
  // gamma_0 of least total norm: every coefficient's mean over the n spokes and n sides to zero.
  K.spokes.array() -= shift_sum / (double(n) * n);
  return K;
}

Eigen::VectorXd signed_fan_areas(const Mesh& mesh, const Refinement& refinement) {
  check_sizes(mesh, refinement, "signed_fan_areas");
  Eigen::VectorXd a(mesh.n_halfedges());
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const int h0 = mesh.face_offsets()[f], n = mesh.face_size(f);
    const Eigen::Vector3d xf = virtual_point(refinement, f);
    Eigen::Vector3d N = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k)
      N += (mesh.position(mesh.halfedge_source(h0 + k)) - xf).cross(mesh.position(mesh.halfedge_target(h0 + k)) - xf);
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d t = (mesh.position(mesh.halfedge_source(h0 + k)) - xf)
                                    .cross(mesh.position(mesh.halfedge_target(h0 + k)) - xf);
      a[h0 + k] = (t.dot(N) < 0 ? -0.5 : 0.5) * t.norm();
    }
  }
  return a;
}

SparseMatrix mesh_d0(const Mesh& mesh) {
  const Eigen::MatrixX2i& E = mesh.edges();
  std::vector<Triplet> t;
  t.reserve(2 * size_t(E.rows()));
  for (int e = 0; e < E.rows(); ++e) {
    t.emplace_back(e, E(e, 0), -1.0);
    t.emplace_back(e, E(e, 1), 1.0);
  }
  SparseMatrix d(E.rows(), mesh.n_vertices());
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

SparseMatrix mesh_d1(const Mesh& mesh) {
  std::vector<Triplet> t;
  t.reserve(size_t(mesh.n_halfedges()));
  for (int h = 0; h < mesh.n_halfedges(); ++h)
    t.emplace_back(mesh.halfedge_face(h), mesh.halfedge_edge(h), double(side_sign(mesh, h)));
  SparseMatrix d(mesh.n_faces(), mesh.n_edges());
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

MeshComplexForms mesh_complex_forms(const Mesh& mesh, const Refinement& refinement, SpokeRule rule,
                                    MeshComplexParts parts) {
  check_sizes(mesh, refinement, "mesh complex");
  const int nE = mesh.n_edges(), nF = mesh.n_faces(), nH = mesh.n_halfedges();
  const Eigen::VectorXd areas = signed_fan_areas(mesh, refinement);
  std::vector<Triplet> p1, p2, s1;
  if (parts.P1) {
    p1.reserve(size_t(nE) + size_t(nH) * 6);
    for (int e = 0; e < nE; ++e) p1.emplace_back(e, e, 1.0);
  }
  if (parts.P2) p2.reserve(size_t(nH));
  if (parts.star1) {
    size_t bound = 0;
    for (int f = 0; f < nF; ++f) bound += size_t(mesh.face_size(f)) * size_t(mesh.face_size(f));
    s1.reserve(bound);
  }
  MeshComplexForms out;
  if (parts.star2) out.star2 = Eigen::VectorXd::Zero(nF);
  Eigen::MatrixXd local, R;
  for (int f = 0; f < nF; ++f) {
    const int h0 = mesh.face_offsets()[f], n = mesh.face_size(f);
    const PolygonCochainMaps K = face_maps(mesh, refinement, areas, f, rule);  // once per face for every part
    const Eigen::Vector3d xf = virtual_point(refinement, f);
    auto corner = [&](int k) { return mesh.position(mesh.halfedge_source(h0 + k)); };
    auto next = [&](int k) { return mesh.position(mesh.halfedge_target(h0 + k)); };
    if (parts.P1)
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k)
          if (K.spokes(i, k) != 0.0)
            p1.emplace_back(nE + h0 + i, mesh.halfedge_edge(h0 + k), side_sign(mesh, h0 + k) * K.spokes(i, k));
    // Refined triangle h is oriented by increasing index; side_sign says whether that is the face's way.
    if (parts.P2)
      for (int k = 0; k < n; ++k)
        if (K.fractions[k] != 0.0) p2.emplace_back(h0 + k, f, side_sign(mesh, h0 + k) * K.fractions[k]);
    if (parts.star2)
      for (int k = 0; k < n; ++k)
        if (refinement.fan[h0 + k] != FanTriangle::Degenerate)
          out.star2[f] += K.fractions[k] * K.fractions[k] * whitney2_mass(corner(k), next(k), xf);
    if (!parts.star1) continue;
    local.setZero(n, n);
    R.resize(3, n);
    // Fan triangle k = (x_k, x_{k+1}, x_f): its Whitney edges (0,1), (0,2), (1,2) are side k,
    // spoke k and spoke k+1, each oriented as in the face's basis.
    for (int k = 0; k < n; ++k) {
      if (refinement.fan[h0 + k] == FanTriangle::Degenerate) continue;
      R.row(0).setZero();
      R(0, k) = 1.0;
      R.row(1) = K.spokes.row(k);
      R.row(2) = K.spokes.row((k + 1) % n);
      local.noalias() += R.transpose() * whitney1_mass(corner(k), next(k), xf) * R;
    }
    local = 0.5 * (local + local.transpose()).eval();  // exactly symmetric
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a)
        s1.emplace_back(mesh.halfedge_edge(h0 + a), mesh.halfedge_edge(h0 + b),
                        side_sign(mesh, h0 + a) * side_sign(mesh, h0 + b) * local(a, b));
  }
  auto assemble = [](SparseMatrix& A, long rows, long cols, const std::vector<Triplet>& t) {
    A.resize(rows, cols);
    A.setFromTriplets(t.begin(), t.end());
  };
  if (parts.P1) assemble(out.P1, nE + nH, nE, p1);
  if (parts.P2) assemble(out.P2, nH, nF, p2);
  if (parts.star1) assemble(out.star1, nE, nE, s1);
  return out;
}

SparseMatrix mesh_prolongation1(const Mesh& mesh, const Refinement& refinement, SpokeRule rule) {
  MeshComplexForms F = mesh_complex_forms(mesh, refinement, rule, {.P1 = true});
  SparseMatrix P;
  P.swap(F.P1);  // swap, not move: Eigen 3.4's SparseMatrix copies on move
  return P;
}

SparseMatrix mesh_prolongation2(const Mesh& mesh, const Refinement& refinement, SpokeRule rule) {
  MeshComplexForms F = mesh_complex_forms(mesh, refinement, rule, {.P2 = true});
  SparseMatrix P;
  P.swap(F.P2);
  return P;
}

SparseMatrix mesh_star1(const Mesh& mesh, const Refinement& refinement, SpokeRule rule) {
  MeshComplexForms F = mesh_complex_forms(mesh, refinement, rule, {.star1 = true});
  SparseMatrix S;
  S.swap(F.star1);
  return S;
}

Eigen::VectorXd mesh_star2_diagonal(const Mesh& mesh, const Refinement& refinement, SpokeRule rule) {
  return mesh_complex_forms(mesh, refinement, rule, {.star2 = true}).star2;
}

}  // namespace polydec
