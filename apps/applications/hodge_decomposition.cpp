// apps/applications/hodge_decomposition.cpp — exact / co-exact / harmonic splitting of 1-cochains.
#include "polydec/apps/applications/hodge_decomposition.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

#include "polydec/dec/surface/hodge_star.h"

namespace polydec {

namespace {

// Vertex components over mesh edges, -1 for unreferenced vertices; also the BFS tree edges.
struct SpanningForest {
  std::vector<int> component;
  std::vector<unsigned char> tree_edge;
  int n_components = 0;
};

SpanningForest primal_forest(const Mesh& mesh) {
  const int nv = mesh.n_vertices(), ne = mesh.n_edges();
  std::vector<int> start(nv + 1, 0), adj(2 * size_t(ne));
  for (int e = 0; e < ne; ++e) ++start[mesh.edges()(e, 0) + 1], ++start[mesh.edges()(e, 1) + 1];
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int e = 0; e < ne; ++e) adj[fill[mesh.edges()(e, 0)]++] = e, adj[fill[mesh.edges()(e, 1)]++] = e;
  SpanningForest F;
  F.component.assign(nv, -1);
  F.tree_edge.assign(ne, 0);
  std::vector<int> queue;
  for (int s = 0; s < nv; ++s) {
    if (F.component[s] >= 0 || start[s] == start[s + 1]) continue;
    F.component[s] = F.n_components;
    queue.assign(1, s);
    for (size_t q = 0; q < queue.size(); ++q) {
      const int v = queue[q];
      for (int k = start[v]; k < start[v + 1]; ++k) {
        const int e = adj[k], u = mesh.edges()(e, 0) == v ? mesh.edges()(e, 1) : mesh.edges()(e, 0);
        if (F.component[u] >= 0) continue;
        F.component[u] = F.n_components;
        F.tree_edge[e] = 1;
        queue.push_back(u);
      }
    }
    ++F.n_components;
  }
  return F;
}

// +1 when halfedge h runs along its edge's orientation (low to high index).
int along(const Mesh& mesh, int h) { return mesh.halfedge_source(h) < mesh.halfedge_target(h) ? 1 : -1; }

}  // namespace

Eigen::MatrixXd cohomology_generators(const Mesh& mesh) {
  const int nf = mesh.n_faces(), ne = mesh.n_edges();
  const SpanningForest T = primal_forest(mesh);
  // Dual graph: nodes 0..nf-1 faces, nf + c the exterior node of component c; one dual edge per
  // mesh edge outside the primal forest.
  std::vector<int> edge_h(2 * size_t(ne), -1);
  for (int h = 0; h < mesh.n_halfedges(); ++h) {
    const int e = mesh.halfedge_edge(h);
    edge_h[2 * e + (edge_h[2 * e] >= 0 ? 1 : 0)] = h;
  }
  const int n_nodes = nf + T.n_components;
  auto face_component = [&](int f) { return T.component[mesh.face(f)[0]]; };
  auto ends = [&](int e) {
    const int f0 = mesh.halfedge_face(edge_h[2 * e]);
    const int f1 = edge_h[2 * e + 1] >= 0 ? mesh.halfedge_face(edge_h[2 * e + 1]) : nf + face_component(f0);
    return std::pair<int, int>(f0, f1);
  };
  std::vector<std::vector<int>> dual_adj(n_nodes);
  for (int e = 0; e < ne; ++e)
    if (!T.tree_edge[e]) {
      const auto [a, b] = ends(e);
      dual_adj[a].push_back(e);
      dual_adj[b].push_back(e);
    }
  // Dual spanning forest rooted at the exterior node of bordered components, else at a face.
  std::vector<int> parent_edge(n_nodes, -1), order;
  std::vector<unsigned char> seen(n_nodes, 0), cotree(ne, 0);
  std::vector<int> roots;
  for (int c = 0; c < T.n_components; ++c)
    if (!dual_adj[nf + c].empty()) roots.push_back(nf + c);
  for (int f = 0; f < nf; ++f) roots.push_back(f);
  for (int r : roots) {
    if (seen[r]) continue;
    seen[r] = 1;
    const size_t first = order.size();
    order.push_back(r);
    for (size_t q = first; q < order.size(); ++q) {
      const int x = order[q];
      for (int e : dual_adj[x]) {
        const auto [a, b] = ends(e);
        const int y = a == x ? b : a;
        if (seen[y]) continue;
        seen[y] = 1;
        parent_edge[y] = e;
        cotree[e] = 1;
        order.push_back(y);
      }
    }
  }
  std::vector<int> leftover;
  for (int e = 0; e < ne; ++e)
    if (!T.tree_edge[e] && !cotree[e]) leftover.push_back(e);

  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(ne, long(leftover.size()));
  std::vector<double> g(ne);
  for (size_t i = 0; i < leftover.size(); ++i) {
    std::fill(g.begin(), g.end(), 0.0);
    g[leftover[i]] = 1.0;
    // Leaves first: each face fixes its parent edge so that its boundary circulation vanishes.
    for (size_t q = order.size(); q-- > 0;) {
      const int f = order[q];
      if (f >= nf || parent_edge[f] < 0) continue;
      double sum = 0;
      int hp = -1;
      for (int h = mesh.face_offsets()[f]; h < mesh.face_offsets()[f + 1]; ++h)
        if (mesh.halfedge_edge(h) == parent_edge[f])
          hp = h;
        else
          sum += along(mesh, h) * g[mesh.halfedge_edge(h)];
      g[parent_edge[f]] = -sum * along(mesh, hp);
    }
    G.col(long(i)) = Eigen::Map<const Eigen::VectorXd>(g.data(), ne);
  }
  return G;
}

Eigen::MatrixXd cohomology_generators(const Mesh& mesh, const CoarseComplex& complex) {
  const Eigen::MatrixXd E = cohomology_generators(mesh);
  const int nf = mesh.n_faces();
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(complex.n_pairs(), E.cols());
  std::vector<unsigned char> assigned(complex.n_pairs());
  for (long i = 0; i < E.cols(); ++i) {
    const auto g = E.col(i);
    // Extend to diagonals by the face potential u (u = 0 at the first corner).
    std::fill(assigned.begin(), assigned.end(), 0);
    std::vector<double> u;
    for (int f = 0; f < nf; ++f) {
      const auto face = mesh.face(f);
      const int h0 = mesh.face_offsets()[f], n = int(face.size());
      u.assign(n, 0.0);
      for (int k = 0; k + 1 < n; ++k) u[k + 1] = u[k] + along(mesh, h0 + k) * g[mesh.halfedge_edge(h0 + k)];
      for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b) {
          const int p = complex.pair_index(face[a], face[b]);
          if (assigned[p]) continue;
          assigned[p] = 1;
          G(p, i) = face[a] < face[b] ? u[b] - u[a] : u[a] - u[b];
        }
    }
  }
  return G;
}

HodgeDecomposer::HodgeDecomposer(const Mesh& mesh, const RefinementOptions& options, DecComplex complex)
    : kind_(complex) {
  const Refinement refinement = refine(mesh, options);
  if (kind_ == DecComplex::Mesh) {
    d0_ = mesh_d0(mesh);
    star1_ = mesh_star1(mesh, refinement);
    edges_ = mesh.edges();
  } else {
    complex_ = CoarseComplex(mesh);
    d0_ = complex_.d0();
    star1_ = polydec::star1(mesh, refinement, complex_);
    edges_ = complex_.pairs();
  }
  // Poisson matrix d0^T star1 d0 = -S, pinned at one vertex per component and at unreferenced vertices.
  const SpanningForest T = primal_forest(mesh);
  pinned_.assign(mesh.n_vertices(), 0);
  std::vector<unsigned char> has_pin(T.n_components, 0);
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    const int c = T.component[v];
    if (c < 0 || !has_pin[c]) pinned_[v] = 1;
    if (c >= 0) has_pin[c] = 1;
  }
  const Eigen::SparseMatrix<double> A = d0_.transpose() * star1_ * d0_;
  poisson_ = std::make_unique<SparseCholesky>(pin_to_identity(A, pinned_), "Poisson matrix d0^T star1 d0 (pinned)");

  // Harmonic basis: generators minus their exact parts, star1-orthonormalised.
  const Eigen::MatrixXd Gen =
      kind_ == DecComplex::Mesh ? cohomology_generators(mesh) : cohomology_generators(mesh, complex_);
  Eigen::MatrixXd H0(Gen.rows(), Gen.cols());
  for (long i = 0; i < Gen.cols(); ++i) {
    const Eigen::VectorXd g = Gen.col(i);
    H0.col(i) = g - d0_ * exact_potential(d0_.transpose() * (star1_ * g));
  }
  const Eigen::MatrixXd SH = star1_ * H0;
  const Eigen::MatrixXd gram = H0.transpose() * SH;
  H_.resize(H0.rows(), 0);
  if (gram.rows() == 0) return;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(gram);
  const double lmax = eig.eigenvalues().cwiseAbs().maxCoeff();
  std::vector<long> keep;
  for (long k = 0; k < gram.rows(); ++k)
    if (eig.eigenvalues()[k] > 1e-12 * lmax) keep.push_back(k);
  H_.resize(H0.rows(), long(keep.size()));
  for (size_t k = 0; k < keep.size(); ++k)
    H_.col(long(k)) = H0 * eig.eigenvectors().col(keep[k]) / std::sqrt(eig.eigenvalues()[keep[k]]);
}

Eigen::VectorXd HodgeDecomposer::exact_potential(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd b = rhs;
  for (long v = 0; v < b.size(); ++v)
    if (pinned_[v]) b[v] = 0;
  return poisson_->solve(b);
}

HodgeParts HodgeDecomposer::decompose(const Eigen::VectorXd& omega) const {
  if (omega.size() != d0_.rows())
    throw std::invalid_argument(fmt::format(
        "hodge decomposition: the 1-form has {} values, the mesh has {} {}", omega.size(), d0_.rows(),
        kind_ == DecComplex::Mesh ? "edges" : "coarse 1-cells (vertex pairs sharing a face)"));
  for (long p = 0; p < omega.size(); ++p)
    if (!std::isfinite(omega[p]))
      throw std::invalid_argument(fmt::format("hodge decomposition: value {} (1-cell {} {}) is not finite", p,
                                              edges_(p, 0), edges_(p, 1)));
  return hodge_parts(omega, exact_potential(d0_.transpose() * (star1_ * omega)), d0_, star1_, H_);
}

HodgeParts hodge_decomposition(const Mesh& mesh, const Eigen::VectorXd& omega) {
  return HodgeDecomposer(mesh).decompose(omega);
}

}  // namespace polydec
