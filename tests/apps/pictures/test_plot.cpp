// tests/apps/pictures/test_plot.cpp — convergence plots: fitted slopes, SVG structure (markers, series
// lines, decade ticks, well-formed nesting, escaping), the raster version and file output.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "polydec/apps/applications/convergence.h"
#include "polydec/apps/pictures/plot.h"
#include "polydec/dec/io/mesh_io.h"
#include "tests/support/support.h"

using namespace polydec;

namespace test_plot {

namespace {

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

// Checks that tags nest properly (every open tag closed in order, one root element) and
// that no raw '&' escapes entity syntax; returns the root's name.
std::string check_xml(const std::string& s) {
  std::vector<std::string> stack;
  std::string root;
  int roots = 0;
  for (size_t p = s.find('<'); p != std::string::npos; p = s.find('<', p + 1)) {
    const size_t q = s.find('>', p);
    REQUIRE(q != std::string::npos);
    const std::string tag = s.substr(p + 1, q - p - 1);
    if (tag.front() == '?') continue;
    if (tag.front() == '/') {
      REQUIRE(!stack.empty());
      CHECK(tag.substr(1) == stack.back());
      stack.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \n/"));
    if (stack.empty()) {
      ++roots;
      root = name;
    }
    if (tag.back() != '/') stack.push_back(name);
  }
  CHECK(stack.empty());
  CHECK(roots == 1);
  for (size_t p = s.find('&'); p != std::string::npos; p = s.find('&', p + 1)) {
    const std::string ent = s.substr(p, 6);
    CHECK((ent.rfind("&amp;", 0) == 0 || ent.rfind("&lt;", 0) == 0 || ent.rfind("&gt;", 0) == 0 ||
           ent.rfind("&quot;", 0) == 0));
  }
  return root;
}

// Three series like a convergence study: errors C h^k for k = 2, 2, 1 and h = 2^-j.
std::vector<PlotSeries> study() {
  std::vector<PlotSeries> s = {
      {"triangles", {}, {}}, {"quads & hexagons", {}, {}}, {"first <order>", {}, {}}};
  for (int j = 2; j <= 6; ++j) {
    const double h = std::pow(0.5, j);
    s[0].x.push_back(h);
    s[0].y.push_back(3 * h * h);
    if (j < 6) {
      s[1].x.push_back(h);
      s[1].y.push_back(0.7 * h * h * (1 + 0.01 * j));
    }
    s[2].x.push_back(h);
    s[2].y.push_back(0.05 * h);
  }
  s[2].x.push_back(0.5);  // left out on a log axis
  s[2].y.push_back(0.0);
  return s;
}

}  // namespace

TEST_CASE("loglog_slope recovers the exponent of a power law", "[render]") {
  std::vector<double> h, e;
  for (int j = 1; j <= 6; ++j) {
    h.push_back(std::pow(0.5, j));
    e.push_back(4.2 * std::pow(h.back(), 2.0));
  }
  CHECK(loglog_slope(h, e) == Approx(2.0).epsilon(1e-12));
  h.push_back(-1);  // ignored: not positive
  e.push_back(1);
  CHECK(loglog_slope(h, e) == Approx(2.0).epsilon(1e-12));
  CHECK(std::isnan(loglog_slope({0.1}, {0.2})));
  CHECK(std::isnan(loglog_slope({0.1, 0.1}, {0.2, 0.3})));
}

TEST_CASE("plot_svg: one marker per plotted point, one line per series, decade ticks", "[render]") {
  PlotOptions o;
  o.title = "Poisson convergence";
  const std::vector<PlotSeries> s = study();
  const std::string svg = plot_svg(s, o);
  CHECK(svg.rfind("<?xml", 0) == 0);
  CHECK(check_xml(svg) == "svg");
  CHECK(count(svg, "class=\"marker\"") == 5 + 4 + 5 + 3);  // 3 legend markers; (0.5, 0) left out
  CHECK(count(svg, "class=\"series\"") == 3);
  // h from 2^-6 to 2^-2: decades 10^-2 .. 10^0; errors 7.8e-4 .. 0.1875: 10^-4 .. 10^0.
  CHECK(count(svg, "<tspan") == 3 + 5);
  CHECK(svg.find(">-4</tspan>") != std::string::npos);
  CHECK(svg.find("triangles (slope 2.00)") != std::string::npos);
  CHECK(svg.find("first &lt;order&gt; (slope 1.00)") != std::string::npos);
  CHECK(svg.find("quads &amp; hexagons (slope 1.9") != std::string::npos);
  CHECK(svg.find("Poisson convergence") != std::string::npos);

  SECTION("linear axes: nice ticks, no slopes") {
    PlotOptions lin = o;
    lin.log_x = lin.log_y = false;
    const std::string t = plot_svg(s, lin);
    CHECK(check_xml(t) == "svg");
    CHECK(count(t, "<tspan") == 0);
    CHECK(t.find("slope") == std::string::npos);
    CHECK(count(t, "class=\"marker\"") == 5 + 4 + 6 + 3);  // (0.5, 0) is plotted now
  }
  SECTION("mismatched series are refused") {
    std::vector<PlotSeries> bad = s;
    bad[1].y.pop_back();
    CHECK_THROWS_AS(plot_svg(bad, o), std::invalid_argument);
  }
}

// The legend box (x, y, width, height) of an SVG plot: the one framed white rectangle smaller
// than the canvas.
std::array<double, 4> legend_box(const std::string& svg, int canvas_width) {
  std::vector<std::array<double, 4>> boxes;
  for (size_t at = svg.find("<rect "); at != std::string::npos; at = svg.find("<rect ", at + 1)) {
    std::array<double, 4> r{};
    REQUIRE(std::sscanf(svg.c_str() + at, "<rect x=\"%lf\" y=\"%lf\" width=\"%lf\" height=\"%lf\"", &r[0], &r[1],
                        &r[2], &r[3]) == 4);
    if (r[2] < 0.9 * canvas_width) boxes.push_back(r);
  }
  REQUIRE(boxes.size() == 1);
  return boxes[0];
}

TEST_CASE("plot_svg: the legend goes to a corner that hides no data", "[render]") {
  PlotOptions o;
  o.log_x = o.log_y = false;
  // Data crowd the top left corner (the legend's first choice) and run down to the bottom right;
  // the top right and bottom left corners are empty.
  const auto crowded = legend_box(plot_svg({{"crowded", {0, 0.5, 1, 1.5, 2, 10}, {10, 9.5, 9.8, 9, 8.5, 0}}}, o), o.width);
  const bool right = crowded[0] > 0.5 * o.width, bottom = crowded[1] > 0.5 * o.height;
  CHECK(right != bottom);
  // Data along the bottom and in the top right: the top left is free and kept.
  const auto free = legend_box(plot_svg({{"low", {0, 10}, {0, 1}}, {"high right", {9, 10}, {9, 10}}}, o), o.width);
  CHECK(free[0] < 0.5 * o.width);
  CHECK(free[1] < 0.5 * o.height);
}

TEST_CASE("plot_image draws the series in their colours", "[render]") {
  PlotOptions o;
  o.width = 480;
  o.height = 360;
  const Image img = plot_image(study(), o);
  REQUIRE(img.width == 480);
  REQUIRE(img.height == 360);
  // Every series colour appears (its markers and lines), the background stays white at a corner.
  const std::vector<PlotSeries> s = study();
  const std::string svg = plot_svg(s, o);
  int found = 0;
  for (const std::string col : {"#1f61b3", "#e66b14", "#2e943d"}) {
    REQUIRE(svg.find(col) != std::string::npos);  // the same palette in both outputs
    const Color c(std::stoi(col.substr(1, 2), nullptr, 16) / 255.0,
                  std::stoi(col.substr(3, 2), nullptr, 16) / 255.0,
                  std::stoi(col.substr(5, 2), nullptr, 16) / 255.0);
    int n = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) n += (img.pixel(x, y) - c).cwiseAbs().maxCoeff() < 2.0 / 255;
    found += n > 20;
  }
  CHECK(found == 3);
  CHECK(img.pixel(479, 0) == Color(1, 1, 1));
}

TEST_CASE("write_plot writes SVG or PNG by extension", "[render]") {
  const test::ScratchDir scratch("test_plot");
  const std::string svg = scratch.path("p.svg"), png = scratch.path("p.png");
  write_plot(svg, study(), {});
  write_plot(png, study(), {});
  std::ifstream in(svg);
  std::stringstream ss;
  ss << in.rdbuf();
  CHECK(ss.str() == plot_svg(study(), {}));
  std::ifstream pin(png, std::ios::binary);
  char sig[8] = {};
  pin.read(sig, 8);
  CHECK(std::string(sig + 1, 3) == "PNG");
  CHECK_THROWS_AS(write_plot(scratch.path("x.pdf"), study(), {}), std::invalid_argument);
  CHECK_THROWS_AS(write_plot("/nonexistent-dir/p.svg", study(), {}), FileError);
}

}  // namespace test_plot
