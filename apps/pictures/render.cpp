// apps/pictures/render.cpp — the software rasterizer behind render() (see render.h for the model).
#include "polydec/apps/pictures/render.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "polydec/apps/pictures/font.h"

namespace polydec {

Eigen::MatrixX3i triangulate_polygon(const Eigen::MatrixX3d& p) {
  const int k = int(p.rows());
  if (k < 3) throw std::invalid_argument("triangulate_polygon: fewer than 3 corners");
  if (k == 3) return Eigen::RowVector3i(0, 1, 2);
  const Eigen::RowVector3d c = p.colwise().mean();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();  // area vector (Newell)
  for (int i = 0; i < k; ++i) n += p.row(i).cross(p.row((i + 1) % k)).transpose();
  Eigen::MatrixX3i fan(k, 3);
  for (int i = 0; i < k; ++i) fan.row(i) << k, i, (i + 1) % k;
  const double nn = n.norm();
  if (!(nn > 0)) return fan;
  n /= nn;
  // Star-shaped with respect to the centroid: every fan triangle turns like the polygon.
  // The tolerance is relative to the polygon's area (|n| before normalization is twice it).
  bool star = true;
  for (int i = 0; i < k && star; ++i) star = (p.row(i) - c).cross(p.row((i + 1) % k) - c).dot(n) > 1e-9 * nn;
  if (star) return fan;
  // Ear clipping in the plane orthogonal to n (the outline is counter-clockwise there).
  const Eigen::Vector3d a =
      (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(n).normalized();
  const Eigen::Vector3d b = n.cross(a);
  std::vector<Eigen::Vector2d> q(k);
  for (int i = 0; i < k; ++i) q[i] = {p.row(i).dot(a), p.row(i).dot(b)};
  auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  const double eps = 1e-12 * nn;
  std::vector<int> ring(k);
  for (int i = 0; i < k; ++i) ring[i] = i;
  std::vector<Eigen::RowVector3i> tris;
  while (ring.size() > 3) {
    const int m = int(ring.size());
    bool clipped = false;
    for (int j = 0; j < m && !clipped; ++j) {
      const int i0 = ring[(j + m - 1) % m], i1 = ring[j], i2 = ring[(j + 1) % m];
      if (cross(q[i1] - q[i0], q[i2] - q[i1]) <= eps) continue;  // reflex or flat corner
      bool empty = true;
      for (int r = 0; r < m && empty; ++r) {
        const int v = ring[r];
        if (v == i0 || v == i1 || v == i2) continue;
        empty = !(cross(q[i1] - q[i0], q[v] - q[i0]) >= -eps && cross(q[i2] - q[i1], q[v] - q[i1]) >= -eps &&
                  cross(q[i0] - q[i2], q[v] - q[i2]) >= -eps);
      }
      if (!empty) continue;
      tris.emplace_back(i0, i1, i2);
      ring.erase(ring.begin() + j);
      clipped = true;
    }
    if (!clipped) return fan;  // self-intersecting outline
  }
  tris.emplace_back(ring[0], ring[1], ring[2]);
  Eigen::MatrixX3i out(int(tris.size()), 3);
  for (int i = 0; i < int(tris.size()); ++i) out.row(i) = tris[i];
  return out;
}

Eigen::Vector3d view_facing_vertex(const Mesh& mesh, int v, const Eigen::Vector3d& up) {
  if (v < 0 || v >= mesh.n_vertices())
    throw std::out_of_range(fmt::format("view_facing_vertex: no vertex {}", v));
  const Eigen::Vector3d lo = mesh.positions().colwise().minCoeff(),
                        hi = mesh.positions().colwise().maxCoeff();
  if ((hi - lo).minCoeff() <= 1e-3 * (hi - lo).maxCoeff() || up.norm() == 0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d c = 0.5 * (lo + hi);
  double volume = 0;  // six times the signed volume about c, by fans around each face's first corner
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto fv = mesh.face(f);
    for (size_t i = 1; i + 1 < fv.size(); ++i)
      volume +=
          (mesh.position(fv[0]) - c).dot((mesh.position(fv[i]) - c).cross(mesh.position(fv[i + 1]) - c));
  }
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (int f : mesh.vertex_faces(v)) {
    const auto fv = mesh.face(f);
    for (size_t i = 0; i < fv.size(); ++i)
      n += mesh.position(fv[i]).cross(mesh.position(fv[(i + 1) % fv.size()]));
  }
  const Eigen::Vector3d u = up.normalized();
  Eigen::Vector3d d = volume < 0 ? n : Eigen::Vector3d(-n);
  d -= d.dot(u) * u;
  return d.norm() > 1e-6 * n.norm() ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::Zero();
}

std::vector<double> nice_ticks(double lo, double hi, int count) {
  if (!(hi > lo) || count < 1) return {lo};
  const double raw = (hi - lo) / count;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double r = raw / mag;
  const double step = (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10) * mag;
  std::vector<double> t;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1)
    t.push_back(std::abs(k) < 0.5 ? 0.0 : k * step);
  return t;
}

namespace {

struct Camera {
  Eigen::Vector3d right, up, forward, centre;
  bool perspective = false;
  double distance = 0;                               // camera to centre, perspective
  double scale = 1, ox = 0, oy = 0, mx = 0, my = 0;  // screen fit

  // Point in camera frame -> (pixel x, pixel y, depth), depth growing away from the viewer.
  Eigen::Vector3d project(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - centre;
    double x = right.dot(d), y = up.dot(d), z = forward.dot(d);
    if (perspective) {
      z += distance;
      x /= z;
      y /= z;
    }
    return {ox + scale * (x - mx), oy - scale * (y - my), z};
  }
  Eigen::Vector2d plane(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - centre;
    double x = right.dot(d), y = up.dot(d);
    if (perspective) {
      const double z = forward.dot(d) + distance;
      x /= z;
      y /= z;
    }
    return {x, y};
  }
};

// Camera looking at the referenced vertices, fitted into the pixel rectangle
// [ax, ax + aw) x [ay, ay + ah).
Camera make_camera(const Mesh& mesh, const std::vector<int>& used, const RenderOptions& o, double ax,
                   double ay, double aw, double ah) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (int v : used) {
    lo = lo.cwiseMin(mesh.position(v));
    hi = hi.cwiseMax(mesh.position(v));
  }
  if (used.empty()) lo = hi = Eigen::Vector3d::Zero();
  Camera cam;
  cam.centre = 0.5 * (lo + hi);
  Eigen::Vector3d f = o.view_direction, up = o.up;
  if (f.norm() == 0) {
    const Eigen::Vector3d ext = hi - lo;
    int a;
    ext.minCoeff(&a);
    f = -Eigen::Vector3d::UnitZ();
    if (ext[a] <= 1e-3 * ext.maxCoeff() && a == 0) f = -Eigen::Vector3d::UnitX();
    if (ext[a] <= 1e-3 * ext.maxCoeff() && a == 1) {
      f = -Eigen::Vector3d::UnitY();
      up = -Eigen::Vector3d::UnitZ();
    }
  }
  f.normalize();
  if (up.norm() == 0 || f.cross(up.normalized()).norm() < 1e-6) {
    int a;
    f.cwiseAbs().minCoeff(&a);
    up = Eigen::Vector3d::Unit(a);
  }
  cam.forward = f;
  cam.right = f.cross(up).normalized();
  cam.up = cam.right.cross(f);
  cam.perspective = o.perspective;
  const double radius = std::max(0.5 * (hi - lo).norm(), 1e-300);
  cam.distance = radius / std::sin(0.5 * o.field_of_view * M_PI / 180);
  Eigen::Vector2d mn = Eigen::Vector2d::Constant(INFINITY), mxv = -mn;
  for (int v : used) {
    const Eigen::Vector2d q = cam.plane(mesh.position(v));
    mn = mn.cwiseMin(q);
    mxv = mxv.cwiseMax(q);
  }
  if (used.empty()) mn = mxv = Eigen::Vector2d::Zero();
  const Eigen::Vector2d ext = mxv - mn;
  const double fill = 1 - 2 * o.margin;
  double s = INFINITY;
  if (ext.x() > 0) s = std::min(s, fill * aw / ext.x());
  if (ext.y() > 0) s = std::min(s, fill * ah / ext.y());
  cam.scale = std::isfinite(s) ? s : 1;
  cam.mx = 0.5 * (mn.x() + mxv.x());
  cam.my = 0.5 * (mn.y() + mxv.y());
  cam.ox = ax + 0.5 * aw;
  cam.oy = ay + 0.5 * ah;
  return cam;
}

// One drawable corner: pixel position, depth, 1/w for perspective-correct interpolation,
// scalar and (smooth shading) normal in the camera frame.
struct Corner {
  double x, y, depth, q, s;
  Eigen::Vector3d n;
};

struct Isolevels {
  bool on = false;
  double origin = 0, spacing = 1, lo = 0, hi = 0;
  // Distance (in scalar units) from s to the nearest drawn level, or +inf.
  double distance(double s) const {
    const double k = std::round((s - origin) / spacing);
    double best = INFINITY;
    for (double kk : {k - 1, k, k + 1}) {
      const double level = origin + kk * spacing;
      const double tol = 1e-9 * (hi - lo);
      if (level > lo + tol && level < hi - tol) best = std::min(best, std::abs(s - level));
    }
    return best;
  }
};

std::string format_number(double v) { return fmt::format("{:.4g}", v); }

// Output-resolution layout: a title band on top, a colour-bar band on the right, the mesh in
// the rest (the drawing area).
struct Layout {
  int ts = 1, pad = 4;  // text scale, padding (pixels)
  int title_ts = 1;     // title text scale: smaller when the title would not fit
  std::string title;    // the title, shortened with ".." if it does not fit even at scale 1
  int title_h = 0;      // height of the title band
  bool bar = false;
  int bar_w = 0, band = 0;  // colour bar width, width of its band
  int area_w = 1, area_h = 1;
  std::vector<double> ticks;
};

Layout make_layout(const RenderOptions& o, bool has_scalar, double lo, double hi) {
  Layout L;
  const int W = o.width, H = o.height;
  L.ts = std::max(1, int(std::lround(H / 300.0)));
  L.pad = 4 * L.ts;
  L.title = o.title;
  L.title_ts = L.ts;
  while (L.title_ts > 1 && text_width(L.title, L.title_ts) > W - 2 * L.pad) --L.title_ts;
  while (L.title.size() > 2 && text_width(L.title, L.title_ts) > W - 2 * L.pad)
    L.title = L.title.substr(0, L.title.size() - 3) + "..";
  L.title_h = o.title.empty() ? 0 : text_height(L.ts) + 2 * L.pad;
  L.bar = has_scalar && o.colorbar;
  if (L.bar) {
    L.ticks = nice_ticks(lo, hi, 5);
    int label_w = std::max(text_width(format_number(lo), L.ts), text_width(format_number(hi), L.ts));
    for (double t : L.ticks) label_w = std::max(label_w, text_width(format_number(t), L.ts));
    L.bar_w = std::max(10, H / 30);
    L.band = std::min(W / 2, L.pad + L.bar_w + 2 * L.pad + label_w + 2 * L.pad);
  }
  L.area_w = std::max(1, W - L.band);
  L.area_h = std::max(1, H - L.title_h);
  return L;
}

// The colour bar: the map from lo (bottom) to hi (top), isoline levels as thin lines, the end
// values and round values in between as labels, the scalar's name on top.
void draw_colorbar(Image& out, const Layout& L, const RenderOptions& o, double lo, double hi,
                   const Isolevels& iso) {
  const int W = o.width, H = o.height, ts = L.ts, pad = L.pad;
  const int bx0 = W - L.band + pad, bx1 = bx0 + L.bar_w;
  const int by0 = L.title_h + std::max(text_height(ts) + 3 * pad, L.area_h / 10), by1 = H - L.area_h / 10;
  if (by1 - by0 <= 4) return;
  const auto y_of = [&](double v) { return by1 - (hi > lo ? (v - lo) / (hi - lo) : 0.5) * (by1 - by0); };
  for (int y = by0; y < by1; ++y) {
    const double t = (by1 - (y + 0.5)) / double(by1 - by0);
    out.fill_rect(bx0, y, bx1, y + 1, colormap(o.colormap, t));
  }
  if (iso.on)
    for (double l = iso.origin + std::ceil((lo - iso.origin) / iso.spacing) * iso.spacing; l <= hi;
         l += iso.spacing)
      if (iso.distance(l) < 1e-9 * iso.spacing)
        draw_line(out, {double(bx0), y_of(l)}, {double(bx1), y_of(l)}, o.isoline_color, 1.0);
  const Color frame = o.text_color;
  draw_line(out, {bx0 - 0.5, by0 - 0.5}, {bx1 + 0.5, by0 - 0.5}, frame, 1);
  draw_line(out, {bx0 - 0.5, by1 + 0.5}, {bx1 + 0.5, by1 + 0.5}, frame, 1);
  draw_line(out, {bx0 - 0.5, by0 - 0.5}, {bx0 - 0.5, by1 + 0.5}, frame, 1);
  draw_line(out, {bx1 + 0.5, by0 - 0.5}, {bx1 + 0.5, by1 + 0.5}, frame, 1);
  const int th = text_height(ts);
  auto label = [&](double v, double y) {
    draw_line(out, {double(bx1), y}, {double(bx1 + pad), y}, frame, 1);
    draw_text(out, bx1 + 2 * pad, int(std::lround(y - 0.5 * th)), format_number(v), o.text_color, ts);
  };
  label(lo, by1);
  if (hi > lo) label(hi, by0);
  for (double t : L.ticks) {
    const double y = y_of(t);
    if (std::abs(y - by0) > 1.5 * th && std::abs(y - by1) > 1.5 * th) label(t, y);
  }
  if (!o.scalar_label.empty())
    draw_text(out, std::max(0, bx0 - pad), by0 - th - 2 * pad, o.scalar_label, o.text_color, ts);
}

}  // namespace

Image render(const Mesh& mesh, const Eigen::VectorXd& scalar, const RenderOptions& o) {
  if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
    throw std::invalid_argument("render: width and height must lie in [16, 16384]");
  if (o.supersample < 1 || o.supersample > 8)
    throw std::invalid_argument("render: supersample must lie in [1, 8]");
  if (double(o.width) * o.height * o.supersample * o.supersample > 4e7)
    throw std::invalid_argument("render: width * height * supersample^2 exceeds 4e7 samples (16 bytes each)");
  if (!(o.margin >= 0 && o.margin < 0.5)) throw std::invalid_argument("render: margin must lie in [0, 0.5)");
  if (o.perspective && !(o.field_of_view > 0 && o.field_of_view < 180))
    throw std::invalid_argument("render: field_of_view must lie in (0, 180) degrees");
  const bool has_scalar = scalar.size() > 0;
  if (has_scalar && scalar.size() != mesh.n_vertices())
    throw std::invalid_argument(
        fmt::format("render: scalar has {} values, the mesh {} vertices", scalar.size(), mesh.n_vertices()));
  if (!(o.isoline_spacing >= 0) || o.isolines < 0)
    throw std::invalid_argument("render: isoline count and spacing must not be negative");

  // Value range.
  double lo = o.scalar_min, hi = o.scalar_max;
  if (has_scalar) {
    double fmin = INFINITY, fmax = -INFINITY;
    for (int v = 0; v < mesh.n_vertices(); ++v)
      if (std::isfinite(scalar[v]) && !mesh.vertex_faces(v).empty()) {
        fmin = std::min(fmin, scalar[v]);
        fmax = std::max(fmax, scalar[v]);
      }
    if (!std::isfinite(fmin)) fmin = fmax = 0;
    if (!std::isfinite(lo)) lo = fmin;
    if (!std::isfinite(hi)) hi = fmax;
    if (hi < lo) std::swap(lo, hi);
  }
  Isolevels iso;
  if (has_scalar && hi > lo && (o.isoline_spacing > 0 || o.isolines > 0)) {
    iso.on = true;
    iso.lo = lo;
    iso.hi = hi;
    iso.spacing = o.isoline_spacing > 0 ? o.isoline_spacing : (hi - lo) / (o.isolines + 1);
    iso.origin = o.isoline_spacing > 0 ? 0.0 : lo;
  }

  const int W = o.width, H = o.height;
  const Layout L = make_layout(o, has_scalar, lo, hi);

  // Camera and per-vertex projection at the supersampled resolution.
  const int k = o.supersample;
  const int IW = W * k, IH = H * k;
  std::vector<int> used;
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (!mesh.vertex_faces(v).empty()) used.push_back(v);
  const Camera cam =
      make_camera(mesh, used, o, 0, double(L.title_h) * k, double(L.area_w) * k, double(L.area_h) * k);
  const Eigen::Vector3d light =
      o.light_direction.norm() > 0 ? o.light_direction.normalized() : Eigen::Vector3d::UnitZ();
  auto to_camera = [&](const Eigen::Vector3d& n) {
    return Eigen::Vector3d(cam.right.dot(n), cam.up.dot(n), -cam.forward.dot(n));
  };
  auto intensity = [&](const Eigen::Vector3d& n_cam) {
    const double nn = n_cam.norm();
    const double c = nn > 0 ? std::abs(n_cam.dot(light)) / nn : 1.0;
    return o.ambient + (1 - o.ambient) * c;
  };

  std::vector<Eigen::Vector3d> face_n(mesh.n_faces(), Eigen::Vector3d::Zero());
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto fv = mesh.face(f);
    for (size_t i = 0; i < fv.size(); ++i)
      face_n[f] += mesh.position(fv[i]).cross(mesh.position(fv[(i + 1) % fv.size()]));
  }
  std::vector<Eigen::Vector3d> vertex_n;
  if (o.smooth_shading) {
    vertex_n.assign(mesh.n_vertices(), Eigen::Vector3d::Zero());
    for (int f = 0; f < mesh.n_faces(); ++f)
      for (int v : mesh.face(f)) vertex_n[v] += face_n[f];
  }

  // Edge opacity, faded on dense meshes by the mean on-screen edge length (output pixels).
  double edge_alpha = o.edge_opacity;
  if (o.edges && o.edge_fade_length > 0 && mesh.n_halfedges() > 0) {
    double sum = 0;
    for (int h = 0; h < mesh.n_halfedges(); ++h) {
      const Eigen::Vector3d a = cam.project(mesh.position(mesh.halfedge_source(h)));
      const Eigen::Vector3d b = cam.project(mesh.position(mesh.halfedge_target(h)));
      sum += (a - b).head<2>().norm() / k;
    }
    edge_alpha *= std::min(1.0, sum / mesh.n_halfedges() / o.edge_fade_length);
  }

  Image img(IW, IH, o.background);
  std::vector<float> zbuf(size_t(IW) * IH, INFINITY);
  const double edge_w = o.edge_width * k, iso_w = o.isoline_width * k;

  std::vector<Corner> corners;
  std::vector<Eigen::Vector2d> outline;
  Eigen::MatrixX3d P;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto fv = mesh.face(f);
    const int m = int(fv.size());
    P.resize(m, 3);
    for (int i = 0; i < m; ++i) P.row(i) = mesh.position(fv[i]).transpose();
    const Eigen::MatrixX3i tris = triangulate_polygon(P);
    corners.resize(m + 1);
    outline.resize(m);
    bool finite = true;
    double smean = 0;
    const Eigen::Vector3d fn = to_camera(face_n[f]);
    for (int i = 0; i <= m; ++i) {
      const Eigen::Vector3d p =
          i < m ? Eigen::Vector3d(P.row(i).transpose()) : Eigen::Vector3d(P.colwise().mean().transpose());
      const Eigen::Vector3d s = cam.project(p);
      Corner& c = corners[i];
      c.x = s.x();
      c.y = s.y();
      c.depth = s.z();
      c.q = cam.perspective ? 1 / s.z() : 1.0;
      c.s = 0;
      c.n = fn;
      if (i < m) {
        outline[i] = {c.x, c.y};
        if (has_scalar) {
          c.s = scalar[fv[i]];
          finite = finite && std::isfinite(c.s);
          smean += c.s;
        }
        if (o.smooth_shading) c.n = to_camera(vertex_n[fv[i]]);
      }
    }
    corners[m].s = smean / m;
    const double flat_intensity = intensity(fn);

    for (int t = 0; t < tris.rows(); ++t) {
      const Corner& A = corners[tris(t, 0)];
      const Corner& B = corners[tris(t, 1)];
      const Corner& C = corners[tris(t, 2)];
      const double area2 = (B.x - A.x) * (C.y - A.y) - (B.y - A.y) * (C.x - A.x);
      if (!(std::abs(area2) > 1e-12)) continue;
      // Screen-space gradient of the scalar on this triangle (for isoline widths in pixels).
      double grad = 0;
      if (iso.on && finite) {
        const double gx = ((B.s - A.s) * (C.y - A.y) - (C.s - A.s) * (B.y - A.y)) / area2;
        const double gy = ((C.s - A.s) * (B.x - A.x) - (B.s - A.s) * (C.x - A.x)) / area2;
        grad = std::hypot(gx, gy);
      }
      const int x0 = std::max(0, int(std::floor(std::min({A.x, B.x, C.x}))));
      const int x1 = std::min(IW - 1, int(std::ceil(std::max({A.x, B.x, C.x}))));
      const int y0 = std::max(0, int(std::floor(std::min({A.y, B.y, C.y}))));
      const int y1 = std::min(IH - 1, int(std::ceil(std::max({A.y, B.y, C.y}))));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const double px = x + 0.5, py = y + 0.5;
          const double w0 = ((B.x - px) * (C.y - py) - (B.y - py) * (C.x - px)) / area2;
          const double w1 = ((C.x - px) * (A.y - py) - (C.y - py) * (A.x - px)) / area2;
          const double w2 = 1 - w0 - w1;
          if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
          const double Q = w0 * A.q + w1 * B.q + w2 * C.q;
          const double b0 = w0 * A.q / Q, b1 = w1 * B.q / Q, b2 = w2 * C.q / Q;
          const float depth = float(cam.perspective ? 1 / Q : w0 * A.depth + w1 * B.depth + w2 * C.depth);
          float& z = zbuf[size_t(y) * IW + x];
          if (!(depth < z)) continue;
          z = depth;
          Color col = o.surface_color;
          double s = 0;
          if (has_scalar) {
            s = b0 * A.s + b1 * B.s + b2 * C.s;
            col = !finite ? o.missing_color : colormap(o.colormap, hi > lo ? (s - lo) / (hi - lo) : 0.5);
          }
          col *= o.smooth_shading ? intensity(b0 * A.n + b1 * B.n + b2 * C.n) : flat_intensity;
          if (iso.on && finite && grad > 0) {
            const double d = iso.distance(s) / grad;
            const double a = std::clamp(0.5 * iso_w + 0.5 - d, 0.0, 1.0) * o.isoline_opacity;
            col = (1 - a) * col + a * o.isoline_color;
          }
          if (o.edges) {
            double d = INFINITY;
            const Eigen::Vector2d p(px, py);
            for (int i = 0; i < m; ++i) {
              const Eigen::Vector2d& a = outline[i];
              const Eigen::Vector2d ab = outline[(i + 1) % m] - a;
              const double l2 = ab.squaredNorm();
              const double u = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
              d = std::min(d, (p - a - u * ab).norm());
            }
            const double a = std::clamp(0.5 * edge_w + 0.5 - d, 0.0, 1.0) * edge_alpha;
            col = (1 - a) * col + a * o.edge_color;
          }
          img.set(x, y, col);
        }
    }
  }

  Image out = img.downsample(k);

  if (L.bar) draw_colorbar(out, L, o, lo, hi, iso);
  if (!L.title.empty())
    draw_text(out, std::max(L.pad, (W - text_width(L.title, L.title_ts)) / 2),
              L.pad + (text_height(L.ts) - text_height(L.title_ts)) / 2, L.title, o.text_color, L.title_ts);
  return out;
}

void render_png(const std::string& path, const Mesh& mesh, const Eigen::VectorXd& scalar,
                const RenderOptions& o) {
  write_png(path, render(mesh, scalar, o));
}

}  // namespace polydec
