// tests/apps/pictures/test_render.cpp — the software renderer: colour maps against published values,
// polygon triangulation, known scenes checked pixel by pixel (colour-mapped ramp, edges,
// isolines, depth order, perspective), coverage of real meshes, PNG round trip, errors.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <set>

#include "polydec/apps/pictures/colormap.h"
#include "polydec/apps/pictures/font.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"
#include "tests/support/support.h"

#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

using namespace polydec;

namespace test_render {

namespace {

using Pixels = std::initializer_list<std::pair<int, int>>;

double max_diff(const Color& a, const Color& b) { return (a - b).cwiseAbs().maxCoeff(); }

// Axis-aligned squares [x0, x0 + size]^2 at height z, counter-clockwise seen from +z.
Mesh squares(const std::vector<Eigen::Vector4d>& sq /* x0, y0, z, size */) {
  PolygonSoup soup;
  soup.positions.resize(4 * int(sq.size()), 3);
  for (int i = 0; i < int(sq.size()); ++i) {
    const double x = sq[i][0], y = sq[i][1], z = sq[i][2], s = sq[i][3];
    soup.positions.row(4 * i + 0) << x, y, z;
    soup.positions.row(4 * i + 1) << x + s, y, z;
    soup.positions.row(4 * i + 2) << x + s, y + s, z;
    soup.positions.row(4 * i + 3) << x, y + s, z;
    const int f[4] = {4 * i, 4 * i + 1, 4 * i + 2, 4 * i + 3};
    soup.add_face(f);
  }
  return Mesh(std::move(soup));
}

// Options for exact pixel checks: no supersampling, no annotations, light along the view.
RenderOptions exact_options(int size) {
  RenderOptions o;
  o.width = o.height = size;
  o.supersample = 1;
  o.margin = 0.1;
  o.colorbar = false;
  o.light_direction = Eigen::Vector3d::UnitZ();
  return o;
}

int covered_pixels(const Image& img, const Color& background) {
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) n += max_diff(img.pixel(x, y), background) > 1e-6;
  return n;
}

double relative_luminance(const Color& c) {
  auto lin = [](double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); };
  return 0.2126 * lin(c[0]) + 0.7152 * lin(c[1]) + 0.0722 * lin(c[2]);
}

double polygon_area(const Eigen::MatrixX3d& p) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (int i = 0; i < p.rows(); ++i) n += p.row(i).cross(p.row((i + 1) % p.rows())).transpose();
  return 0.5 * n.norm();
}

}  // namespace

TEST_CASE("colour maps end at the published end colours", "[render]") {
  // matplotlib's viridis #440154 .. #fde725 (float table values), Google's turbo LUT ends.
  CHECK(max_diff(colormap(Colormap::viridis, 0), {0.267004, 0.004874, 0.329415}) < 1e-3);
  CHECK(max_diff(colormap(Colormap::viridis, 1), {0.993248, 0.906157, 0.143936}) < 1e-3);
  CHECK(max_diff(colormap(Colormap::turbo, 0), {0.18995, 0.07176, 0.23217}) < 1e-3);
  CHECK(max_diff(colormap(Colormap::turbo, 1), {0.47960, 0.01583, 0.01055}) < 1e-3);
  // Mid colour of viridis is #21918c; clamping outside [0, 1] and NaN.
  CHECK(max_diff(colormap(Colormap::viridis, 0.5), Color(33, 145, 140) / 255.0) < 2.0 / 255);
  CHECK(colormap(Colormap::turbo, -3) == colormap(Colormap::turbo, 0));
  CHECK(colormap(Colormap::turbo, 7) == colormap(Colormap::turbo, 1));
  CHECK(colormap(Colormap::viridis, std::nan("")) == colormap(Colormap::viridis, 0));
  CHECK(parse_colormap("turbo") == Colormap::turbo);
  CHECK_THROWS_AS(parse_colormap("jet"), std::invalid_argument);
}

TEST_CASE("colour maps agree with independent published polynomial fits", "[render]") {
  // Polynomial fits published by their authors (viridis: J. Liard 2016, degree 5; turbo:
  // R. Du, Google 2019, degree 5). They deviate from the true maps by up to 0.022 (viridis) and
  // 0.08 (turbo) on [0.05, 0.95]; a mis-transcribed table row or swapped channel would not.
  const double V[3][6] = {
      {0.280268003, -0.143510503, 2.225793877, -14.815088879, 25.212752309, -11.772589584},
      {-0.002117546, 1.617109353, -1.909305070, 2.701152864, -1.685288385, 0.178738871},
      {0.300805501, 2.614650302, -12.019139090, 28.933559110, -33.491294770, 13.762053843}};
  const double T[3][6] = {{0.13572138, 4.61539260, -42.66032258, 132.13108234, -152.94239396, 59.28637943},
                          {0.09140261, 2.19418839, 4.84296658, -14.18503333, 4.27729857, 2.82956604},
                          {0.10667330, 12.64194608, -60.58204836, 110.36276771, -89.90310912, 27.34824973}};
  auto poly = [](const double P[3][6], double t) {
    Color c;
    for (int k = 0; k < 3; ++k) {
      c[k] = 0;
      for (int j = 5; j >= 0; --j) c[k] = c[k] * t + P[k][j];
    }
    return c;
  };
  double ev = 0, et = 0;
  for (int i = 0; i <= 90; ++i) {
    const double t = 0.05 + 0.01 * i;
    ev = std::max(ev, max_diff(colormap(Colormap::viridis, t), poly(V, t)));
    et = std::max(et, max_diff(colormap(Colormap::turbo, t), poly(T, t)));
  }
  CHECK(ev < 0.03);
  CHECK(et < 0.1);
}

TEST_CASE("viridis luminance increases monotonically", "[render]") {
  double prev = -1;
  for (int i = 0; i <= 400; ++i) {
    const double y = relative_luminance(colormap(Colormap::viridis, i / 400.0));
    REQUIRE(y > prev);
    prev = y;
  }
}

TEST_CASE("triangulate_polygon: fans for star-shaped polygons, ear clipping otherwise", "[render]") {
  SECTION("convex hexagon: fan around the centroid") {
    Eigen::MatrixX3d p(6, 3);
    for (int i = 0; i < 6; ++i) p.row(i) << std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), 0;
    const Eigen::MatrixX3i t = triangulate_polygon(p);
    REQUIRE(t.rows() == 6);
    for (int i = 0; i < 6; ++i) CHECK(t(i, 0) == 6);
  }
  SECTION("non-star-shaped planar polygons are covered exactly once") {
    // An L (centroid on a corner) and a U (centroid outside the polygon), in a tilted plane.
    const std::vector<std::vector<Eigen::Vector2d>> shapes = {
        {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},
        {{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 0.5}, {1, 0.5}, {1, 3}, {0, 3}}};
    const Eigen::Vector3d a = Eigen::Vector3d(1, 0.2, 0.3).normalized();
    const Eigen::Vector3d b = a.cross(Eigen::Vector3d(0.1, -0.4, 1)).normalized().cross(a);
    for (const auto& s : shapes) {
      const int k = int(s.size());
      Eigen::MatrixX3d p(k, 3);
      for (int i = 0; i < k; ++i) p.row(i) = (s[i].x() * a + s[i].y() * b).transpose();
      const Eigen::MatrixX3i t = triangulate_polygon(p);
      REQUIRE(t.rows() == k - 2);
      const Eigen::Vector3d n = a.cross(b);
      double area = 0;
      for (int j = 0; j < t.rows(); ++j) {
        REQUIRE(t.row(j).maxCoeff() < k);  // no centroid
        const double aj =
            0.5 * (p.row(t(j, 1)) - p.row(t(j, 0))).cross(p.row(t(j, 2)) - p.row(t(j, 0))).dot(n);
        CHECK(aj > 0);
        area += aj;
      }
      CHECK(area == Approx(polygon_area(p)).epsilon(1e-12));
    }
  }
  SECTION("self-intersecting outline falls back to the fan") {
    Eigen::MatrixX3d p(5, 3);  // a pentagram
    for (int i = 0; i < 5; ++i) p.row(i) << std::cos(i * 4 * M_PI / 5), std::sin(i * 4 * M_PI / 5), 0;
    CHECK(triangulate_polygon(p).rows() == 5);
  }
}

TEST_CASE("render: a colour-mapped ramp on a square facing the camera", "[render]") {
  // Unit square, scalar = x; 200 x 200 pixels with margin 0.1: the square covers pixels
  // [20, 180) in x and y, pixel column i has centre x = (i + 0.5 - 20) / 160.
  const Mesh mesh = squares({{0, 0, 0, 1}});
  const Eigen::VectorXd s = mesh.positions().col(0);
  RenderOptions o = exact_options(200);
  o.edge_width = 2;
  o.edge_opacity = 1;
  o.edge_color = {1, 0, 0};
  const Image img = render(mesh, s, o);
  REQUIRE(img.width == 200);
  REQUIRE(img.height == 200);
  auto ramp = [](int i) { return (i + 0.5 - 20) / 160; };
  // Interior: the colour map at the interpolated value (light along the view: intensity 1).
  for (int i : {30, 64, 100, 143, 170})
    CHECK(max_diff(img.pixel(i, 100), colormap(o.colormap, ramp(i))) < 1e-6);
  CHECK(max_diff(img.pixel(100, 100), colormap(Colormap::viridis, 0.503125)) < 1e-6);
  // Background outside.
  for (auto [x, y] : Pixels{{5, 5}, {195, 100}, {100, 195}, {19, 100}, {100, 180}})
    CHECK(max_diff(img.pixel(x, y), o.background) < 1e-6);
  // Edges: pixel centres within width/2 of the outline are the edge colour; 2 px inside, not.
  for (auto [x, y] : Pixels{{20, 100}, {179, 100}, {100, 20}, {100, 179}, {20, 20}})
    CHECK(max_diff(img.pixel(x, y), o.edge_color) < 1e-6);
  CHECK(max_diff(img.pixel(23, 100), colormap(o.colormap, ramp(23))) < 1e-6);

  SECTION("turbo and a fixed value range") {
    RenderOptions t = o;
    t.colormap = Colormap::turbo;
    t.scalar_min = 0.5;
    t.scalar_max = 1.5;
    const Image it = render(mesh, s, t);
    CHECK(max_diff(it.pixel(60, 100), colormap(Colormap::turbo, 0)) < 1e-6);  // below the range: clamped
    CHECK(max_diff(it.pixel(140, 100), colormap(Colormap::turbo, ramp(140) - 0.5)) < 1e-6);
  }
  SECTION("isolines at the requested levels") {
    RenderOptions t = o;
    t.isolines = 1;  // one level, at 0.5: x = 100 px
    t.isoline_width = 2;
    t.isoline_opacity = 1;
    t.isoline_color = {0, 0, 1};
    const Image it = render(mesh, s, t);
    CHECK(max_diff(it.pixel(99, 100), t.isoline_color) < 1e-6);
    CHECK(max_diff(it.pixel(100, 100), t.isoline_color) < 1e-6);
    CHECK(max_diff(it.pixel(96, 100), colormap(o.colormap, ramp(96))) < 1e-6);
    t.isolines = 0;
    t.isoline_spacing = 0.25;  // levels 0.25, 0.5, 0.75 at x = 60, 100, 140 px
    const Image is = render(mesh, s, t);
    for (int x : {59, 60, 99, 100, 139, 140}) CHECK(max_diff(is.pixel(x, 70), t.isoline_color) < 1e-6);
    for (int x : {80, 120, 160}) CHECK(max_diff(is.pixel(x, 70), colormap(o.colormap, ramp(x))) < 1e-6);
  }
  SECTION("Lambert shading scales the colour by ambient + diffuse |cos|") {
    RenderOptions t = o;
    t.light_direction = {0, 1, 1};  // 45 degrees off the normal
    t.edges = false;
    const Image it = render(mesh, {}, t);
    const double I = t.ambient + (1 - t.ambient) * std::sqrt(0.5);
    CHECK(max_diff(it.pixel(100, 100), I * t.surface_color) < 1e-6);
    t.view_direction = {0, 0, 1};  // from behind: two-sided, same intensity
    CHECK(max_diff(render(mesh, {}, t).pixel(100, 100), I * t.surface_color) < 1e-6);
  }
}

TEST_CASE("render: the nearer of two overlapping squares wins", "[render]") {
  // Square A at z = 0 with value 0, square B at z = 1 with value 1, overlapping on [1, 2]^2.
  for (bool a_first : {true, false}) {
    const Eigen::Vector4d A(0, 0, 0, 2), B(1, 1, 1, 2);
    const Mesh mesh = a_first ? squares({A, B}) : squares({B, A});
    Eigen::VectorXd s = mesh.positions().col(2);  // = the square's z: 0 on A, 1 on B
    RenderOptions o = exact_options(300);
    o.edges = false;
    // Seen from +z (looking along -z) B is in front: the overlap shows B's colour.
    o.view_direction = {0, 0, -1};
    const Image front = render(mesh, s, o);
    CHECK(max_diff(front.pixel(150, 150), colormap(o.colormap, 1)) < 1e-6);
    CHECK(max_diff(front.pixel(60, 240), colormap(o.colormap, 0)) < 1e-6);  // A only
    // Seen from -z, A is in front.
    o.view_direction = {0, 0, 1};
    const Image back = render(mesh, s, o);
    CHECK(max_diff(back.pixel(150, 150), colormap(o.colormap, 0)) < 1e-6);
  }
}

TEST_CASE("render: perspective makes the farther of two equal squares smaller", "[render]") {
  const Mesh mesh = squares({{-2, 0, 0, 1}, {1, 0, -3, 1}});  // right square 3 units farther
  RenderOptions o = exact_options(400);
  o.perspective = true;
  o.edges = false;
  const Image img = render(mesh, {}, o);
  int left = 0, right = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (max_diff(img.pixel(x, y), o.background) > 1e-6) (x < 200 ? left : right)++;
  CHECK(left > 0);
  CHECK(right > 0);
  CHECK(right < 0.8 * left);
  o.perspective = false;  // orthographic: the same size (up to pixel rounding)
  const Image ortho = render(mesh, {}, o);
  left = right = 0;
  for (int y = 0; y < ortho.height; ++y)
    for (int x = 0; x < ortho.width; ++x)
      if (max_diff(ortho.pixel(x, y), o.background) > 1e-6) (x < 200 ? left : right)++;
  CHECK(std::abs(left - right) < 0.02 * left);
}

TEST_CASE("render: a closed sphere covers its silhouette disc without holes", "[render]") {
  const Mesh sphere = uv_sphere(24, 48);
  RenderOptions o = exact_options(300);
  o.margin = 0.05;
  const Image img = render(sphere, sphere.positions().col(2), o);
  // Orthographic view along -z of the unit sphere: the silhouette is the equator polygon
  // (48 sides, circumradius 135 px), area 0.5 n r^2 sin(2 pi / n).
  const double r = 0.45 * 300, expect = 0.5 * 48 * r * r * std::sin(2 * M_PI / 48);
  CHECK(covered_pixels(img, o.background) == Approx(expect).epsilon(0.01));
}

TEST_CASE("render: non-star-shaped polygons (tetris) are covered exactly once", "[render]") {
  POLYDEC_SHARED_MESH(path, "tetris.obj");
  const Mesh mesh = read_mesh(path);
  RenderOptions o = exact_options(300);
  o.margin = 0.05;
  // Planar in y = const: the default view looks straight at it; pixels per unit from the fit.
  auto expected_pixels = [&](const Mesh& m) {
    const Eigen::Vector3d ext = m.positions().colwise().maxCoeff() - m.positions().colwise().minCoeff();
    REQUIRE(ext.y() < 1e-9 * ext.norm());
    const double scale = 0.9 * 300 / std::max(ext.x(), ext.z());
    double area = 0;
    for (int f = 0; f < m.n_faces(); ++f) {
      Eigen::MatrixX3d p(m.face_size(f), 3);
      for (int i = 0; i < p.rows(); ++i) p.row(i) = m.positions().row(m.face(f)[i]);
      area += polygon_area(p);
    }
    return area * scale * scale;
  };
  CHECK(covered_pixels(render(mesh, {}, o), o.background) == Approx(expected_pixels(mesh)).epsilon(0.01));
  // Each polygon alone: its fan around the centroid would spill outside the non-star-shaped ones.
  int n_checked = 0;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    if (mesh.face_size(f) < 5) continue;
    PolygonSoup soup;
    soup.positions.resize(mesh.face_size(f), 3);
    std::vector<int> idx;
    for (int i = 0; i < mesh.face_size(f); ++i) {
      soup.positions.row(i) = mesh.positions().row(mesh.face(f)[i]);
      idx.push_back(i);
    }
    soup.add_face(idx);
    const Mesh one(std::move(soup));
    CHECK(covered_pixels(render(one, {}, o), o.background) == Approx(expected_pixels(one)).epsilon(0.02));
    ++n_checked;
  }
  CHECK(n_checked > 0);
}

TEST_CASE("render: colour bar and labels", "[render]") {
  const Mesh mesh = squares({{0, 0, 0, 1}});
  RenderOptions o;
  o.width = 400;
  o.height = 300;
  o.title = "ramp";
  o.scalar_label = "value";
  const Image img = render(mesh, mesh.positions().col(0) * 3.0, o);
  // The bar lies right of the mesh: somewhere in the right quarter the top colour of the map
  // sits above its bottom colour, in the same column.
  bool found = false;
  for (int x = 300; x < 400 && !found; ++x) {
    int top = -1, bottom = -1;
    for (int y = 0; y < 300; ++y) {
      if (top < 0 && max_diff(img.pixel(x, y), colormap(o.colormap, 0.995)) < 0.02) top = y;
      if (max_diff(img.pixel(x, y), colormap(o.colormap, 0.005)) < 0.02) bottom = y;
    }
    found = top >= 0 && bottom > top + 100;
  }
  CHECK(found);
  // Title text: dark pixels in the top band, centred.
  int dark = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 150; x < 250; ++x) dark += img.pixel(x, y).maxCoeff() < 0.3;
  CHECK(dark > 20);
}

TEST_CASE("font: every glyph is 5x7, distinct, and drawn as designed", "[render]") {
  const std::string chars =
      "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz.,-+:()/=_%!?*[]<>'|^ ";
  std::set<std::string> seen;
  for (char c : chars) {
    REQUIRE(has_glyph(c));
    std::string bits;
    for (const char* row : glyph(c)) {
      REQUIRE(std::string(row).size() == 5);
      bits += row;
    }
    CHECK(seen.insert(bits).second);  // no two characters look the same
  }
  CHECK_FALSE(has_glyph('~'));
  CHECK(text_width("1.5e-3", 2) == (6 * 6 - 1) * 2);
  Image img(20, 20, {1, 1, 1});
  draw_text(img, 3, 4, "8", {0, 0, 0}, 2);
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 5; ++c)
      CHECK((img.pixel(3 + 2 * c + 1, 4 + 2 * r) == Color(0, 0, 0)) == (glyph('8')[r][c] == '#'));
}

TEST_CASE("nice_ticks: round values inside the range", "[render]") {
  const std::vector<double> t = nice_ticks(0, 3.0758, 5);
  REQUIRE(t.size() == 7);  // 0, 0.5, ..., 3
  for (size_t i = 0; i < t.size(); ++i) CHECK(t[i] == Approx(0.5 * i).margin(1e-12));
  const std::vector<double> u = nice_ticks(-0.0123, 0.0411, 4);
  for (double v : u) {
    CHECK(v >= -0.0123);
    CHECK(v <= 0.0411);
  }
  CHECK(u.size() >= 3);
  CHECK(nice_ticks(2, 2, 5).size() == 1);
}

TEST_CASE("render_png writes a decodable PNG of the rendered image", "[render]") {
  const Mesh mesh = hex_grid(4, 4);
  RenderOptions o;
  o.width = 160;
  o.height = 120;
  o.isolines = 4;
  const Eigen::VectorXd s = mesh.positions().col(0) + mesh.positions().col(1);
  const test::ScratchDir scratch("test_render");
  const std::string path = scratch.path("r.png");
  render_png(path, mesh, s, o);
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
  REQUIRE(data != nullptr);
  CHECK(w == 160);
  CHECK(h == 120);
  CHECK(n == 3);
  const Image img = render(mesh, s, o);
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(data[3 * (y * w + x) + c] / 255.0 - img.pixel(x, y)[c]));
  stbi_image_free(data);
  CHECK(worst <= 0.5 / 255 + 1e-6);
  CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST_CASE("render: bad input is refused with a clear error", "[render]") {
  const Mesh mesh = quad_grid(2, 2);
  CHECK_THROWS_AS(render(mesh, Eigen::VectorXd::Zero(3), {}), std::invalid_argument);
  RenderOptions o;
  o.width = 0;
  CHECK_THROWS_AS(render(mesh, {}, o), std::invalid_argument);
  o.width = o.height = 8000;  // 2.56e8 samples with the default supersampling
  CHECK_THROWS_AS(render(mesh, {}, o), std::invalid_argument);
  try {
    render_png("/nonexistent-dir/x.png", mesh, {}, {});
    FAIL("no error");
  } catch (const FileError& e) {
    CHECK(std::string(e.what()).find("/nonexistent-dir/x.png") != std::string::npos);
  }
  // Non-finite values (unreached vertices) get the missing colour instead of NaN pixels.
  Eigen::VectorXd s = mesh.positions().col(0);
  s[0] = INFINITY;
  const Image img = render(mesh, s, {});
  CHECK(std::all_of(img.rgb.begin(), img.rgb.end(), [](float v) { return std::isfinite(v); }));
}

TEST_CASE("polydec geodesics --png and polydec render write pictures", "[render]") {
  POLYDEC_SHARED_MESH(mesh, "quad-sphere.off");
  const test::ScratchDir scratch("test_render_cli");
  const std::string a = scratch.path("geodesics.png"), b = scratch.path("render.png");
  const std::string cli = POLYDEC_CLI_PATH;
  REQUIRE(std::system(
              (cli + " geodesics " + mesh + " --source 0 --png " + a + " --json > /dev/null").c_str()) == 0);
  REQUIRE(std::system(
              (cli + " render " + mesh + " --png " + b + " --scalar z --width 320 --height 240 > /dev/null")
                  .c_str()) == 0);
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(a.c_str(), &w, &h, &n, 3);
  REQUIRE(data != nullptr);
  CHECK((w == 800 && h == 600));
  // The source vertex faces the camera: the darkest colour of viridis (distance 0) is near
  // the centre of the drawing area.
  const Color c0 = colormap(Colormap::viridis, 0);
  bool dark_centre = false;
  for (int y = 250; y < 350; ++y)
    for (int x = 280; x < 400; ++x) {
      const unsigned char* p = data + 3 * (y * w + x);
      const Color c(p[0] / 255.0, p[1] / 255.0, p[2] / 255.0);
      dark_centre |= (c - c0 * c.norm() / c0.norm()).norm() < 0.05 && c.norm() > 0.2;
    }
  stbi_image_free(data);
  CHECK(dark_centre);
  data = stbi_load(b.c_str(), &w, &h, &n, 3);
  REQUIRE(data != nullptr);
  CHECK((w == 320 && h == 240));
  stbi_image_free(data);
  // Usage errors exit with code 2.
  CHECK(WEXITSTATUS(std::system(
            (cli + " render " + mesh + " --png " + b + " --scalar w 2> /dev/null").c_str())) == 2);
}

TEST_CASE("view_facing_vertex looks at a vertex head-on, horizontally", "[render]") {
  const Mesh sphere = uv_sphere(12, 24);
  for (int v : {3, 40, 100}) {
    const Eigen::Vector3d d = view_facing_vertex(sphere, v);
    if (std::abs(sphere.position(v).x()) + std::abs(sphere.position(v).z()) < 1e-9) continue;
    CHECK(std::abs(d.y()) < 1e-12);  // orthogonal to up
    CHECK(d.norm() == Approx(1));
    CHECK(d.dot(sphere.position(v)) < 0);  // from outside towards the centre
    // The same for the mesh with flipped orientation (inward normals).
    PolygonSoup soup;
    soup.positions = sphere.positions();
    for (int f = 0; f < sphere.n_faces(); ++f) {
      std::vector<int> r(sphere.face(f).rbegin(), sphere.face(f).rend());
      soup.add_face(r);
    }
    CHECK((view_facing_vertex(Mesh(std::move(soup)), v) - d).norm() < 1e-12);
  }
  CHECK(view_facing_vertex(quad_grid(3, 3), 0).norm() == 0);  // flat: default view
  CHECK_THROWS_AS(view_facing_vertex(sphere, sphere.n_vertices()), std::out_of_range);
}

TEST_CASE("render: edges fade on dense meshes, stay on coarse ones", "[render]") {
  RenderOptions o = exact_options(200);
  o.edge_width = 2;  // pixel centres at the edges are fully covered
  auto edge_effect = [&](const Mesh& m) {
    RenderOptions no = o;
    no.edges = false;
    const Image a = render(m, {}, o), b = render(m, {}, no);
    double worst = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i) worst = std::max(worst, double(std::abs(a.rgb[i] - b.rgb[i])));
    return worst;
  };
  // Coarse: full opacity on the edge pixels (grey surface towards the edge colour).
  const double full = o.edge_opacity * (o.surface_color - o.edge_color).maxCoeff();
  CHECK(edge_effect(quad_grid(4, 4)) == Approx(full).epsilon(1e-5));
  // 160 px for 80 cells: 2 px per edge, opacity scaled by 2 / 10.
  CHECK(edge_effect(quad_grid(80, 80)) == Approx(0.2 * full).epsilon(0.05));
}

TEST_CASE("render: the picture does not depend on the mesh's scale or position", "[render]") {
  const Mesh mesh = hex_grid(5, 4);
  const Eigen::VectorXd s = mesh.positions().col(0).array().square() + mesh.positions().col(1).array();
  RenderOptions o = exact_options(160);
  o.isolines = 5;
  o.view_direction = {0.3, -0.4, -1};
  const Image ref = render(mesh, s, o);
  for (double scale : {1e-8, 1e8}) {
    const Eigen::MatrixX3d p = (mesh.positions() * scale).rowwise() + Eigen::RowVector3d(3, -2, 5) * scale;
    const Image img = render(mesh.with_positions(p), s, o);
    double worst = 0;
    for (size_t i = 0; i < img.rgb.size(); ++i)
      worst = std::max(worst, double(std::abs(img.rgb[i] - ref.rgb[i])));
    CHECK(worst < 1e-3);
  }
}

TEST_CASE("render: perspective-correct interpolation puts isolines where the geometry is", "[render]") {
  // A square tilted away from the camera (far edge 2 units deeper), scalar = y. Seen in
  // perspective, the isoline s = 0.5 must lie on the projection of the 3D line y = 0.5, which
  // the same square split into two quads along y = 0.5 shows as a polygon edge. Affine
  // interpolation in screen space would put it at the trapezoid's mid-height instead.
  auto tilted = [](bool split) {
    PolygonSoup soup;
    soup.positions.resize(6, 3);
    soup.positions << 0, 0, 0, 1, 0, 0, 1, 0.5, -1, 0, 0.5, -1, 1, 1, -2, 0, 1, -2;
    if (split) {
      soup.add_face(std::vector<int>{0, 1, 2, 3});
      soup.add_face(std::vector<int>{3, 2, 4, 5});
    } else {
      soup.add_face(std::vector<int>{0, 1, 4, 5});
    }
    return Mesh(std::move(soup));
  };
  RenderOptions o = exact_options(300);
  o.perspective = true;
  o.field_of_view = 60;
  o.edge_width = 3;  // silhouette edges are drawn inside only: some pixel centre within 1 px
  o.isoline_width = 2;
  o.edge_opacity = o.isoline_opacity = 1;
  o.edge_color = {1, 0, 0};
  o.isoline_color = {0, 0, 1};
  auto rows = [](const Image& img, int x, const Color& c) {
    std::vector<int> r;
    for (int y = 0; y < img.height; ++y)
      if (max_diff(img.pixel(x, y), c) < 0.02) r.push_back(y);
    return r;
  };
  auto mean = [](const std::vector<double>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
  };
  RenderOptions a = o;
  a.edges = false;
  a.isolines = 1;  // the level 0.5
  const Mesh one = tilted(false), two = tilted(true);
  const Image iso_img = render(one, one.positions().col(1), a);
  const Image edge_img = render(two, {}, o);
  // Column by column (the polygon is drawn as a fan: away from the centre column the
  // isoline crosses fan triangles whose screen-affine interpolation would be off).
  int compared = 0;
  double worst = 0, spread = INFINITY;
  for (int x = 40; x < 260; x += 4) {
    const std::vector<int> iso = rows(iso_img, x, a.isoline_color), edge = rows(edge_img, x, o.edge_color);
    if (iso.empty() || edge.size() < 3) continue;
    std::vector<double> middle;  // between the far (top) and the near (bottom) silhouette edge
    for (int y : edge)
      if (y > edge.front() + 3 && y < edge.back() - 3) middle.push_back(y);
    if (middle.empty()) continue;
    const double edge_row = mean(middle);
    worst = std::max(worst, std::abs(mean(std::vector<double>(iso.begin(), iso.end())) - edge_row));
    spread = std::min(spread, std::abs(0.5 * (edge.front() + edge.back()) - edge_row));
    ++compared;
  }
  CHECK(compared > 20);
  CHECK(worst < 1.0);
  CHECK(spread > 4.0);  // the trapezoid's mid-height is elsewhere: the test can tell
}

TEST_CASE("render: a long title is made to fit", "[render]") {
  RenderOptions o = exact_options(200);
  o.title = std::string(100, 'M');  // 100 glyphs cannot fit 200 px even at scale 1
  const Image img = render(quad_grid(2, 2), {}, o);
  // Ink in the title band stays inside the image with the padding on both sides, and the
  // title is drawn (shortened, ending in "..").
  int first = img.width, last = -1;
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < img.width; ++x)
      if (img.pixel(x, y).maxCoeff() < 0.5) first = std::min(first, x), last = std::max(last, x);
  CHECK(first >= 4);
  CHECK(last <= img.width - 5);
  CHECK(last - first > 150);
}

}  // namespace test_render
