// tests/dec/surface/test_split_refinement.cpp — several virtual vertices per face: interior diagonals,
// the pieces of single polygons, the saw-tooth grid, faces with valid fans kept bit for bit, every
// piece's fan valid (saw-tooth grids, L-SHAPED, TETRIS 1 and 2), the pieces tiling their face, and
// the prolongation (rows sum to 1, positions reproduced on planar faces).
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/mesh/sawtooth_grid.h"
#include "polydec/dec/surface/split_refinement.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_split_refinement {

namespace {

PolygonPositions polygon(const std::vector<Eigen::Vector2d>& p) {
  PolygonPositions X(p.size(), 3);
  for (size_t k = 0; k < p.size(); ++k) X.row(long(k)) << p[k].x(), p[k].y(), 0.0;
  return X;
}

// Twice the vector area of the polygon of corners X (rows) listed by `idx`.
Eigen::Vector3d vector_area2(const PolygonPositions& X, const std::vector<int>& idx) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < idx.size(); ++k) a += X.row(idx[k]).cross(X.row(idx[(k + 1) % idx.size()])).transpose();
  return a;
}

// Twice the signed area of the polygon X listed by `idx`, along the unit vector n.
double area2(const PolygonPositions& X, const std::vector<int>& idx, const Eigen::Vector3d& n = Eigen::Vector3d::UnitZ()) {
  return vector_area2(X, idx).dot(n);
}

// Every piece of every face of `mesh`: its fan triangles (over the piece's own edges) are valid,
// i.e. oriented with the piece and of quality 2 area / longest^2 above 1e-8; returns the smallest.
double check_pieces_valid(const Mesh& mesh, const SplitRefinement& s) {
  double worst = 1;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto face = mesh.face(f);
    for (int p = s.piece_offsets[f]; p < s.piece_offsets[f + 1]; ++p) {
      const int b = s.corner_offsets[p], m = s.corner_offsets[p + 1] - b;
      Eigen::Vector3d c = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
      for (int k = 0; k < m; ++k) c += mesh.position(face[s.corners[b + k]]) / m;
      for (int k = 0; k < m; ++k)
        normal += (mesh.position(face[s.corners[b + k]]) - c).cross(mesh.position(face[s.corners[b + (k + 1) % m]]) - c);
      const Eigen::Vector3d x = s.virtual_points.row(p).transpose();
      for (int k = 0; k < m; ++k) {
        const Eigen::Vector3d a = mesh.position(face[s.corners[b + k]]) - x,
                              d = mesh.position(face[s.corners[b + (k + 1) % m]]) - x;
        const Eigen::Vector3d n2 = a.cross(d);
        const double q = (n2.dot(normal) < 0 ? -1 : 1) * n2.norm() /
                         std::max({a.squaredNorm(), d.squaredNorm(), (d - a).squaredNorm()});
        INFO("face " << f << " piece " << p << " corner " << k);
        CHECK(q > 1e-8);
        worst = std::min(worst, q);
      }
    }
  }
  return worst;
}

// P's rows sum to 1 and P x reproduces the refined positions (vertices and virtual points), relative
// to the mesh's size.
void check_prolongation(const Mesh& mesh, const SplitRefinement& s) {
  const Eigen::SparseMatrix<double> P = split_prolongation(mesh, s);
  REQUIRE(P.rows() == mesh.n_vertices() + s.n_pieces());
  REQUIRE(P.cols() == mesh.n_vertices());
  const Eigen::VectorXd rows = P * Eigen::VectorXd::Ones(mesh.n_vertices());
  CHECK((rows.array() - 1).abs().maxCoeff() < 1e-12);
  const Eigen::MatrixX3d X = split_positions(mesh, s);
  const double scale = mesh.positions().cwiseAbs().maxCoeff() + mesh.mean_edge_length();
  CHECK((P * mesh.positions() - X).cwiseAbs().maxCoeff() < 1e-12 * scale);
}

// The pieces of each (planar) face tile it: their signed areas along the face's normal are positive and
// sum to the face's, and every corner of the face is in some piece.
void check_pieces_tile(const Mesh& mesh, const SplitRefinement& s) {
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const PolygonPositions X = face_positions(mesh, f);
    std::vector<int> all(X.rows());
    for (int k = 0; k < int(X.rows()); ++k) all[k] = k;
    const Eigen::Vector3d n = vector_area2(X, all).normalized();
    double sum = 0;
    std::vector<bool> seen(X.rows(), false);
    for (int p = s.piece_offsets[f]; p < s.piece_offsets[f + 1]; ++p) {
      const std::vector<int> piece(s.corners.begin() + s.corner_offsets[p], s.corners.begin() + s.corner_offsets[p + 1]);
      const double a = area2(X, piece, n);
      CHECK(a > 0);
      sum += a;
      for (int k : piece) seen[k] = true;
    }
    const double whole = area2(X, all, n);
    CHECK(std::abs(sum - whole) <= 1e-12 * std::abs(whole));
    CHECK(std::count(seen.begin(), seen.end(), false) == 0);
  }
}

}  // namespace

TEST_CASE("interior diagonals of convex and non-convex polygons", "[split]") {
  const PolygonPositions hexagon = polygon({{1, 0}, {0.5, 0.9}, {-0.5, 0.9}, {-1, 0}, {-0.5, -0.9}, {0.5, -0.9}});
  CHECK(interior_diagonals(hexagon).size() == 9);  // n (n - 3) / 2
  // L shape, corner 3 reflex: (1, 4) and (2, 5) touch the boundary, (1, 5) runs through corner 3, (2, 4)
  // lies outside.
  const PolygonPositions L = polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  const auto d = interior_diagonals(L);
  const std::vector<std::pair<int, int>> expected{{0, 2}, {0, 3}, {0, 4}, {1, 3}, {3, 5}};
  CHECK(d == expected);
  // Collinear corners: the diagonal through a corner on the line is refused.
  const PolygonPositions flat = polygon({{0, 0}, {1, 0}, {2, 0}, {2, 1}, {0, 1}});
  for (const auto& [i, j] : interior_diagonals(flat)) CHECK(!(i == 0 && j == 2));
  // Clockwise corners give the same diagonals.
  PolygonPositions Lcw = L;
  for (int k = 0; k < 6; ++k) Lcw.row(k).y() = -L(k, 1);
  CHECK(interior_diagonals(Lcw) == expected);
}

TEST_CASE("split polygons: convex whole, saw teeth into the fewest valid pieces", "[split]") {
  const PolygonPositions square = polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  const PolygonSplit a = split_polygon(square);
  CHECK(a.valid);
  CHECK(a.pieces.size() == 1);
  // A cell of sawtooth_grid with two teeth of depth 0.7: not star-shaped, so no single virtual
  // vertex gives a valid fan; one diagonal cuts it into two valid pieces (e.g. two chevrons).
  const double t = 0.7;
  const PolygonPositions saw = polygon({{0, 0}, {0.25, t}, {0.5, 0}, {0.75, t}, {1, 0}, {1, 1}, {0.75, 1 + t},
                                        {0.5, 1}, {0.25, 1 + t}, {0, 1}});
  const PolygonSplit s = split_polygon(saw);
  REQUIRE(s.valid);
  CHECK(s.worst > 0);
  std::vector<int> all(10);
  for (int k = 0; k < 10; ++k) all[k] = k;
  double sum = 0;
  for (const auto& p : s.pieces) {
    CHECK(area2(saw, p) > 0);
    sum += area2(saw, p);
  }
  CHECK(std::abs(sum - area2(saw, all)) < 1e-12);
  CHECK(s.pieces.size() == 2);
  // The same polygon moved, scaled by 1e-6 and rotated out of the xy plane splits the same way.
  Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  PolygonPositions moved = (1e-6 * saw * R.transpose()).rowwise() + Eigen::RowVector3d(5, -3, 2);
  const PolygonSplit sm = split_polygon(moved);
  REQUIRE(sm.valid);
  CHECK(sm.pieces == s.pieces);
  CHECK(std::abs(sm.worst - s.worst) < 1e-6 * s.worst);
}

TEST_CASE("split refinement keeps every face with a valid fan bit for bit", "[split]") {
  for (const Mesh& mesh : {quad_grid(4, 3), hex_grid(4, 4), hex_sphere(1), chevron_grid(4, 4, 0.3),
                           add_noise(torus(8, 5), 0.1, 3)}) {
    const Refinement r = refine(mesh);
    REQUIRE(r.quality.ok());
    const SplitRefinement s = split_refine(mesh);
    CHECK(s.n_faces_split == 0);
    CHECK(s.n_faces_unsplittable == 0);
    REQUIRE(s.n_pieces() == mesh.n_faces());
    CHECK(s.weights == r.weights);
    CHECK(s.virtual_points == r.virtual_points);
    CHECK(s.worst_before == s.worst_after);
    CHECK(s.worst_after > 0);
    check_prolongation(mesh, s);
  }
}

TEST_CASE("sawtooth grids: invalid single fans, valid pieces, P reproduces positions", "[split]") {
  for (const double scale : {1e-6, 1.0, 1e6}) {
    PolygonSoup soup;
    const Mesh m0 = sawtooth_grid(4, 4, 2, 0.7);
    soup.positions = scale * m0.positions();
    soup.positions.rowwise() += scale * Eigen::RowVector3d(3, -1, 0);
    for (int f = 0; f < m0.n_faces(); ++f) soup.add_face(m0.face(f));
    const Mesh mesh(std::move(soup));
    INFO("scale " << scale);
    const SplitRefinement s = split_refine(mesh);
    // Square cells with teeth below them are not star-shaped; the bottom row's (flat below, teeth above)
    // squared-area fans are valid.
    CHECK(s.before.n_faces_affected == 4 * 3);
    CHECK(s.worst_before < 0);
    CHECK(s.after.ok());
    CHECK(s.n_faces_unsplittable == 0);
    CHECK(s.n_faces_split == 4 * 3);
    CHECK(s.worst_after > 0);
    check_pieces_valid(mesh, s);
    check_pieces_tile(mesh, s);
    check_prolongation(mesh, s);
    // Refined triangles: one per piece edge, all positively oriented, covering the square.
    const auto tris = split_triangles(mesh, s);
    const Eigen::MatrixX3d X = split_positions(mesh, s);
    double area = 0;
    for (const auto& t : tris) {
      const double a = (X.row(t[1]) - X.row(t[0])).cross(X.row(t[2]) - X.row(t[0])).z();
      CHECK(a > 0);
      area += 0.5 * a;
    }
    CHECK(std::abs(area - scale * scale) < 1e-12 * scale * scale);
  }
  CHECK_THROWS_AS(sawtooth_grid(2, 2, 2, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(sawtooth_grid(0, 2), std::invalid_argument);
  // One tooth is chevron_grid.
  const Mesh a = sawtooth_grid(3, 2, 1, 0.3), b = chevron_grid(3, 2, 0.3);
  CHECK(a.n_faces() == b.n_faces());
  CHECK(std::abs(a.mean_edge_length() - b.mean_edge_length()) < 1e-14);
}

TEST_CASE("split refinement of the paper's non-convex meshes", "[split]") {
  for (const char* name : {"L-plane.obj", "tetris.obj", "tetris_2.obj"}) {
    POLYDEC_SHARED_MESH(path, name);
    const Mesh mesh = read_mesh(path);
    const SplitRefinement s = split_refine(mesh);
    INFO(name << ": single fans " << s.before.n_faces_affected << " faces affected, split " << s.n_faces_split
              << ", unsplittable " << s.n_faces_unsplittable);
    CHECK(s.n_faces_unsplittable == 0);
    CHECK(s.after.ok());
    CHECK(s.n_faces_split == s.before.n_faces_affected);
    check_pieces_valid(mesh, s);
    check_pieces_tile(mesh, s);
    check_prolongation(mesh, s);
  }
}

}  // namespace test_split_refinement
