// apps/pictures/plot.cpp — plot layout shared by two canvases: SVG text and a raster Image.
#include "polydec/apps/pictures/plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "polydec/apps/applications/convergence.h"
#include "polydec/apps/pictures/font.h"
#include "polydec/apps/pictures/render.h"

namespace polydec {

namespace {

using Vec2 = Eigen::Vector2d;

// Drawing operations the plot needs; coordinates in pixels, y down.
class Canvas {
 public:
  virtual ~Canvas() = default;
  virtual void line(const Vec2& a, const Vec2& b, const Color& c, double width) = 0;
  virtual void polyline(const std::vector<Vec2>& p, const Color& c, double width) = 0;
  virtual void marker(const Vec2& p, int shape, double r, const Color& c) = 0;
  virtual void rect(const Vec2& a, const Vec2& b, const Color& fill, const Color& stroke) = 0;
  // Text vertically centred on p.y(); anchor -1 left, 0 centre, 1 right.
  virtual void text(const Vec2& p, const std::string& s, int anchor, const Color& c) = 0;
  // "10" with a raised exponent k, centred on p.
  virtual void power_of_ten(const Vec2& p, int k, int anchor, const Color& c) = 0;
  virtual double text_width(const std::string& s) const = 0;
  virtual double text_height() const = 0;
};

// Marker outline with `shape` (0 circle, 1 square, 2 triangle, 3 diamond, 4 inverted
// triangle, 5 pentagon), radius r around p; circles are returned as an empty outline.
std::vector<Vec2> marker_outline(const Vec2& p, int shape, double r) {
  std::vector<Vec2> q;
  auto ring = [&](int k, double phase, double rr) {
    for (int i = 0; i < k; ++i) {
      const double a = phase + 2 * M_PI * i / k;
      q.push_back(p + rr * Vec2(std::cos(a), -std::sin(a)));
    }
  };
  switch (shape % 6) {
    case 1:
      ring(4, M_PI / 4, r * 1.15);
      break;
    case 2:
      ring(3, M_PI / 2, r * 1.25);
      break;
    case 3:
      ring(4, 0, r * 1.3);
      break;
    case 4:
      ring(3, -M_PI / 2, r * 1.25);
      break;
    case 5:
      ring(5, M_PI / 2, r * 1.2);
      break;
    default:
      break;
  }
  return q;
}

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += c;
    }
  }
  return o;
}

std::string hex(const Color& c) {
  auto b = [](double v) { return int(std::lround(255 * std::clamp(v, 0.0, 1.0))); };
  return fmt::format("#{:02x}{:02x}{:02x}", b(c[0]), b(c[1]), b(c[2]));
}

class SvgCanvas : public Canvas {
 public:
  SvgCanvas(int w, int h) : font_(13.0 * h / 480.0) {
    out_ = fmt::format(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
        "font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"{2:.3g}\">\n"
        "<rect x=\"0\" y=\"0\" width=\"{0}\" height=\"{1}\" fill=\"#ffffff\"/>\n",
        w, h, font_);
  }
  void line(const Vec2& a, const Vec2& b, const Color& c, double w) override {
    out_ += fmt::format(
        "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\" "
        "stroke-width=\"{:.3g}\"/>\n",
        a.x(), a.y(), b.x(), b.y(), hex(c), w);
  }
  void polyline(const std::vector<Vec2>& p, const Color& c, double w) override {
    out_ += "<polyline class=\"series\" fill=\"none\" stroke=\"" + hex(c) +
            fmt::format("\" stroke-width=\"{:.3g}\" points=\"", w);
    for (size_t i = 0; i < p.size(); ++i)
      out_ += fmt::format("{}{:.2f},{:.2f}", i ? " " : "", p[i].x(), p[i].y());
    out_ += "\"/>\n";
  }
  void marker(const Vec2& p, int shape, double r, const Color& c) override {
    const std::vector<Vec2> q = marker_outline(p, shape, r);
    if (q.empty()) {
      out_ += fmt::format("<circle class=\"marker\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"{}\"/>\n",
                          p.x(), p.y(), r, hex(c));
      return;
    }
    out_ += "<polygon class=\"marker\" fill=\"" + hex(c) + "\" points=\"";
    for (size_t i = 0; i < q.size(); ++i)
      out_ += fmt::format("{}{:.2f},{:.2f}", i ? " " : "", q[i].x(), q[i].y());
    out_ += "\"/>\n";
  }
  void rect(const Vec2& a, const Vec2& b, const Color& fill, const Color& stroke) override {
    out_ += fmt::format(
        "<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"{}\" stroke=\"{}\"/>\n",
        a.x(), a.y(), b.x() - a.x(), b.y() - a.y(), hex(fill), hex(stroke));
  }
  void text(const Vec2& p, const std::string& s, int anchor, const Color& c) override {
    out_ += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"{}\" fill=\"{}\">{}</text>\n", p.x(),
                        p.y() + 0.35 * font_,
                        anchor < 0   ? "start"
                        : anchor > 0 ? "end"
                                     : "middle",
                        hex(c), xml_escape(s));
  }
  void power_of_ten(const Vec2& p, int k, int anchor, const Color& c) override {
    out_ += fmt::format(
        "<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"{}\" fill=\"{}\">10<tspan dy=\"{:.2f}\" "
        "font-size=\"{:.3g}\">{}</tspan></text>\n",
        p.x(), p.y() + 0.35 * font_,
        anchor < 0   ? "start"
        : anchor > 0 ? "end"
                     : "middle",
        hex(c), -0.45 * font_, 0.75 * font_, k);
  }
  double text_width(const std::string& s) const override { return 0.6 * font_ * double(s.size()); }
  double text_height() const override { return font_; }
  std::string finish() { return out_ + "</svg>\n"; }

 private:
  double font_;
  std::string out_;
};

class ImageCanvas : public Canvas {
 public:
  ImageCanvas(int w, int h) : img_(w, h, {1, 1, 1}), ts_(std::max(1, int(std::lround(h / 300.0)))) {}
  void line(const Vec2& a, const Vec2& b, const Color& c, double w) override { draw_line(img_, a, b, c, w); }
  void polyline(const std::vector<Vec2>& p, const Color& c, double w) override {
    for (size_t i = 0; i + 1 < p.size(); ++i) draw_line(img_, p[i], p[i + 1], c, w);
  }
  void marker(const Vec2& p, int shape, double r, const Color& c) override {
    const std::vector<Vec2> q = marker_outline(p, shape, r);
    if (q.empty()) return draw_disc(img_, p, r, c);
    // Coverage by 4 x 4 samples per pixel of the convex outline.
    const int x0 = int(std::floor(p.x() - 2 * r)), x1 = int(std::ceil(p.x() + 2 * r));
    const int y0 = int(std::floor(p.y() - 2 * r)), y1 = int(std::ceil(p.y() + 2 * r));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        int in = 0;
        for (int j = 0; j < 4; ++j)
          for (int i = 0; i < 4; ++i) {
            const Vec2 s(x + (i + 0.5) / 4, y + (j + 0.5) / 4);
            bool inside = true;
            for (size_t k = 0; k < q.size() && inside; ++k) {
              const Vec2 e = q[(k + 1) % q.size()] - q[k], d = s - q[k];
              inside = e.x() * d.y() - e.y() * d.x() <= 0;  // clockwise on screen (y down)
            }
            in += inside;
          }
        img_.blend(x, y, c, in / 16.0);
      }
  }
  void rect(const Vec2& a, const Vec2& b, const Color& fill, const Color& stroke) override {
    img_.fill_rect(int(std::lround(a.x())), int(std::lround(a.y())), int(std::lround(b.x())),
                   int(std::lround(b.y())), fill);
    line({a.x(), a.y()}, {b.x(), a.y()}, stroke, 1);
    line({b.x(), a.y()}, {b.x(), b.y()}, stroke, 1);
    line({b.x(), b.y()}, {a.x(), b.y()}, stroke, 1);
    line({a.x(), b.y()}, {a.x(), a.y()}, stroke, 1);
  }
  void text(const Vec2& p, const std::string& s, int anchor, const Color& c) override {
    const double w = polydec::text_width(s, ts_);
    const double x = anchor < 0 ? p.x() : anchor > 0 ? p.x() - w : p.x() - 0.5 * w;
    draw_text(img_, int(std::lround(x)), int(std::lround(p.y() - 0.5 * text_height())), s, c, ts_);
  }
  void power_of_ten(const Vec2& p, int k, int anchor, const Color& c) override {
    const std::string e = std::to_string(k);
    const int es = std::max(1, ts_ - 1);
    const double w = polydec::text_width("10", ts_) + es + polydec::text_width(e, es);
    const double x = anchor < 0 ? p.x() : anchor > 0 ? p.x() - w : p.x() - 0.5 * w;
    const int y = int(std::lround(p.y() - 0.5 * text_height()));
    draw_text(img_, int(std::lround(x)), y, "10", c, ts_);
    draw_text(img_, int(std::lround(x + polydec::text_width("10", ts_) + es)), y - 3 * es, e, c, es);
  }
  double text_width(const std::string& s) const override { return polydec::text_width(s, ts_); }
  double text_height() const override { return polydec::text_height(ts_); }
  Image finish() { return std::move(img_); }

 private:
  Image img_;
  int ts_;
};

// One axis: data value -> pixel, ticks and labels.
struct Axis {
  bool log = false;
  double lo = 0, hi = 1;  // in log10 units on a log axis
  double p0 = 0, p1 = 1;  // pixels of lo and hi
  double map(double v) const {
    const double t = ((log ? std::log10(v) : v) - lo) / (hi - lo);
    return p0 + t * (p1 - p0);
  }
  bool valid(double v) const { return std::isfinite(v) && (!log || v > 0); }
};

Axis make_axis(const std::vector<double>& values, bool log) {
  Axis a;
  a.log = log;
  double mn = INFINITY, mx = -INFINITY;
  for (double v : values)
    if (a.valid(v)) {
      mn = std::min(mn, log ? std::log10(v) : v);
      mx = std::max(mx, log ? std::log10(v) : v);
    }
  if (!std::isfinite(mn)) mn = 0, mx = 1;
  if (log) {
    a.lo = std::floor(mn + 1e-9);
    a.hi = std::ceil(mx - 1e-9);
    if (a.hi <= a.lo) a.hi = a.lo + 1;
  } else {
    if (mx <= mn) mn -= 1, mx += 1;
    const std::vector<double> t = nice_ticks(mn, mx, 5);
    const double step = t.size() > 1 ? t[1] - t[0] : (mx - mn);
    a.lo = std::floor(mn / step + 1e-9) * step;
    a.hi = std::ceil(mx / step - 1e-9) * step;
  }
  return a;
}

const Color kPalette[] = {{0.12, 0.38, 0.70}, {0.90, 0.42, 0.08}, {0.18, 0.58, 0.24}, {0.80, 0.14, 0.20},
                          {0.50, 0.32, 0.72}, {0.55, 0.35, 0.25}, {0.85, 0.35, 0.65}, {0.40, 0.40, 0.40}};

// How much of the plotted data a legend box [a, b] would hide: ten for each marker whose disc of
// radius r meets the box, one for each sample (every r) of the lines between consecutive points.
long legend_overlap(const std::vector<std::vector<Vec2>>& drawn, const Vec2& a, const Vec2& b, double r, bool markers,
                    bool lines) {
  auto inside = [&](const Vec2& p) {
    return p.x() > a.x() - r && p.x() < b.x() + r && p.y() > a.y() - r && p.y() < b.y() + r;
  };
  long n = 0;
  for (const std::vector<Vec2>& pts : drawn) {
    if (markers)
      for (const Vec2& p : pts) n += 10 * inside(p);
    if (lines)
      for (size_t j = 1; j < pts.size(); ++j) {
        const int steps = std::clamp(int((pts[j] - pts[j - 1]).norm() / r), 1, 10000);
        for (int k = 1; k < steps; ++k) n += inside(pts[j - 1] + (pts[j] - pts[j - 1]) * (double(k) / steps));
      }
  }
  return n;
}

void draw_plot(Canvas& cv, const std::vector<PlotSeries>& series, const PlotOptions& o) {
  const double u = o.height / 480.0;
  const Color ink{0.1, 0.1, 0.1}, grid{0.88, 0.88, 0.88}, minor_grid{0.95, 0.95, 0.95};
  const double th = cv.text_height();
  const double L = 80 * u, R = o.width - 20 * u, T = (o.title.empty() ? 40 : 55) * u, B = o.height - 55 * u;

  std::vector<double> xs, ys;
  for (const PlotSeries& s : series) {
    xs.insert(xs.end(), s.x.begin(), s.x.end());
    ys.insert(ys.end(), s.y.begin(), s.y.end());
  }
  Axis ax = make_axis(xs, o.log_x), ay = make_axis(ys, o.log_y);
  ax.p0 = L, ax.p1 = R;
  ay.p0 = B, ay.p1 = T;

  // Grid, ticks and tick labels.
  auto ticks = [](const Axis& a, std::vector<double>& major, std::vector<double>& minor) {
    if (a.log) {
      const int every = std::max(1, int(std::ceil((a.hi - a.lo) / 8)));
      for (int k = int(a.lo); k <= int(a.hi); ++k) {
        if ((k - int(a.lo)) % every == 0) major.push_back(k);
        if (every == 1 && k < int(a.hi))
          for (int m = 2; m <= 9; ++m) minor.push_back(k + std::log10(double(m)));
      }
    } else {
      major = nice_ticks(a.lo, a.hi, 5);
    }
  };
  auto pos = [](const Axis& a, double t) { return a.p0 + (t - a.lo) / (a.hi - a.lo) * (a.p1 - a.p0); };
  std::vector<double> xmaj, xmin, ymaj, ymin;
  ticks(ax, xmaj, xmin);
  ticks(ay, ymaj, ymin);
  for (double t : xmin) cv.line({pos(ax, t), T}, {pos(ax, t), B}, minor_grid, 1);
  for (double t : ymin) cv.line({L, pos(ay, t)}, {R, pos(ay, t)}, minor_grid, 1);
  for (double t : xmaj) cv.line({pos(ax, t), T}, {pos(ax, t), B}, grid, 1);
  for (double t : ymaj) cv.line({L, pos(ay, t)}, {R, pos(ay, t)}, grid, 1);
  for (double t : xmin) cv.line({pos(ax, t), B}, {pos(ax, t), B - 3 * u}, ink, 1);
  for (double t : ymin) cv.line({L, pos(ay, t)}, {L + 3 * u, pos(ay, t)}, ink, 1);
  for (double t : xmaj) {
    cv.line({pos(ax, t), B}, {pos(ax, t), B - 6 * u}, ink, 1);
    const Vec2 p(pos(ax, t), B + 6 * u + 0.6 * th);
    if (ax.log)
      cv.power_of_ten(p, int(std::lround(t)), 0, ink);
    else
      cv.text(p, fmt::format("{:.4g}", t), 0, ink);
  }
  for (double t : ymaj) {
    cv.line({L, pos(ay, t)}, {L + 6 * u, pos(ay, t)}, ink, 1);
    const Vec2 p(L - 6 * u, pos(ay, t));
    if (ay.log)
      cv.power_of_ten(p, int(std::lround(t)), 1, ink);
    else
      cv.text(p, fmt::format("{:.4g}", t), 1, ink);
  }
  cv.line({L, B}, {R, B}, ink, 1);
  cv.line({L, T}, {R, T}, ink, 1);
  cv.line({L, T}, {L, B}, ink, 1);
  cv.line({R, T}, {R, B}, ink, 1);
  if (!o.x_label.empty()) cv.text({0.5 * (L + R), o.height - 14 * u}, o.x_label, 0, ink);
  if (!o.y_label.empty()) cv.text({8 * u, T - 1.5 * th - 4 * u}, o.y_label, -1, ink);
  if (!o.title.empty()) cv.text({0.5 * o.width, 18 * u}, o.title, 0, ink);

  // Series: lines, then markers on top.
  const double mr = 4.5 * u, lw = 2 * u;
  std::vector<std::string> labels;
  std::vector<std::vector<Vec2>> drawn;  // each series' points in pixels, for the legend's placement
  for (size_t i = 0; i < series.size(); ++i) {
    const PlotSeries& s = series[i];
    const Color& c = kPalette[i % std::size(kPalette)];
    std::vector<Vec2>& pts = drawn.emplace_back();
    for (size_t j = 0; j < s.x.size(); ++j)
      if (ax.valid(s.x[j]) && ay.valid(s.y[j])) pts.emplace_back(ax.map(s.x[j]), ay.map(s.y[j]));
    if (o.lines && pts.size() > 1) cv.polyline(pts, c, lw);
    if (o.markers)
      for (const Vec2& p : pts) cv.marker(p, int(i), mr, c);
    std::string label = s.name;
    if (o.fit_slopes && o.log_x && o.log_y) {
      const double k = loglog_slope(s.x, s.y);
      if (std::isfinite(k)) label += fmt::format(" (slope {:.2f})", k);
    }
    labels.push_back(label);
  }

  // Legend inside the axes, in the corner (top left, top right, bottom left, bottom right, in
  // that order of preference) that hides the fewest markers and line samples.
  if (!series.empty()) {
    double w = 0;
    for (const std::string& l : labels) w = std::max(w, cv.text_width(l));
    const double row = std::max(th * 1.5, 16 * u), sample = 26 * u;
    const Vec2 size(sample + 18 * u + w, row * double(series.size()) + 8 * u);
    const Vec2 corners[4] = {{L + 10 * u, T + 10 * u},
                             {R - 10 * u - size.x(), T + 10 * u},
                             {L + 10 * u, B - 10 * u - size.y()},
                             {R - 10 * u - size.x(), B - 10 * u - size.y()}};
    Vec2 a = corners[0];
    long fewest = -1;
    for (const Vec2& c : corners) {
      const long hidden = legend_overlap(drawn, c, c + size, mr, o.markers, o.lines);
      if (fewest < 0 || hidden < fewest) fewest = hidden, a = c;
    }
    const Vec2 b = a + size;
    cv.rect(a, b, {1, 1, 1}, {0.7, 0.7, 0.7});
    for (size_t i = 0; i < series.size(); ++i) {
      const Color& c = kPalette[i % std::size(kPalette)];
      const double y = a.y() + 4 * u + row * (i + 0.5);
      if (o.lines) cv.line({a.x() + 6 * u, y}, {a.x() + 6 * u + sample, y}, c, lw);
      if (o.markers) cv.marker({a.x() + 6 * u + 0.5 * sample, y}, int(i), mr, c);
      cv.text({a.x() + 12 * u + sample, y}, labels[i], -1, ink);
    }
  }
}

void check(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  if (o.width < 100 || o.height < 100 || o.width > 16384 || o.height > 16384)
    throw std::invalid_argument("plot: width and height must lie in [100, 16384]");
  for (const PlotSeries& s : series)
    if (s.x.size() != s.y.size())
      throw std::invalid_argument(
          fmt::format("plot: series '{}' has {} x and {} y values", s.name, s.x.size(), s.y.size()));
}

}  // namespace

std::string plot_svg(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  check(series, o);
  SvgCanvas cv(o.width, o.height);
  draw_plot(cv, series, o);
  return cv.finish();
}

Image plot_image(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  check(series, o);
  ImageCanvas cv(o.width, o.height);
  draw_plot(cv, series, o);
  return cv.finish();
}

void write_plot(const std::string& path, const std::vector<PlotSeries>& series, const PlotOptions& o) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".png") return write_png(path, plot_image(series, o));
  if (ext != ".svg") throw std::invalid_argument("write_plot: " + path + ": extension must be .svg or .png");
  write_file_atomically(path, plot_svg(series, o));
}

}  // namespace polydec
