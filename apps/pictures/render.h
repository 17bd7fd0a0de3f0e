// apps/pictures/render.h — headless software rendering of a polygon mesh to an image / PNG (no display,
// no GPU): z-buffered rasterization, two-sided Lambert shading, a per-vertex scalar field
// colour-mapped per pixel, isolines, thin polygon edges, a colour bar with the value range and
// an optional title.
//
// Usage:
//   RenderOptions opt;  opt.isolines = 12;  opt.title = "geodesic distance";
//   render_png("out.png", mesh, distance, opt);     // distance: |V| values
//   render_png("mesh.png", mesh, {}, {});            // no scalar: grey shaded mesh with edges
//
// How a polygon is drawn (a triangle as itself): if every triangle of its fan around the vertex centroid
// turns the same way as the polygon (the polygon is star-shaped with respect to its centroid, in the plane of
// its area vector), the fan is used, with the centroid's scalar the mean of the polygon's values; otherwise
// (non-star-shaped polygons, e.g. tetris pieces) the polygon is ear-clipped in that plane, and if even that
// fails (self-intersecting outline) the fan is used anyway. Scalars are interpolated linearly on these
// triangles (perspective-correct). Only the polygon's own edges are drawn, never the triangulation's. Shading
// uses the polygon's area-vector normal (flat per polygon) or, with smooth_shading, area-weighted vertex
// normals; the light is a headlight-like directional light fixed in the camera frame.
//
// Camera: looks along `view_direction` with `up` pointing up on screen; the mesh's
// referenced vertices are fitted into the drawing area leaving `margin`. The default view
// direction (zero vector) looks along -z (y up), or straight at a flat mesh along its
// thinnest bounding-box axis (for a mesh flat in y: along -y with -z up).
#pragma once

#include <limits>
#include <string>

#include "polydec/apps/pictures/colormap.h"
#include "polydec/apps/pictures/image.h"
#include "polydec/dec/mesh/mesh.h"

namespace polydec {

struct RenderOptions {
  int width = 800, height = 600;  // pixels of the output image

  // Camera.
  Eigen::Vector3d view_direction = Eigen::Vector3d::Zero();  // zero: default (see above)
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  bool perspective = false;   // orthographic by default
  double field_of_view = 30;  // degrees, perspective only
  double margin = 0.04;       // free border around the mesh, fraction of the drawing area

  // Surface colour: the scalar through `colormap` over [scalar_min, scalar_max] (NaN: the
  // range of the finite values), or `surface_color` without a scalar. Triangles touching a
  // vertex with a non-finite value get `missing_color`.
  Colormap colormap = Colormap::viridis;
  double scalar_min = std::numeric_limits<double>::quiet_NaN();
  double scalar_max = std::numeric_limits<double>::quiet_NaN();
  Color surface_color{0.78, 0.78, 0.80};
  Color missing_color{0.55, 0.55, 0.55};

  // Isolines of the scalar: every `isoline_spacing` (levels k * spacing), or else
  // `isolines` levels evenly spaced strictly inside [scalar_min, scalar_max]. 0: none.
  int isolines = 0;
  double isoline_spacing = 0;
  double isoline_width = 1.3;  // pixels
  Color isoline_color{0.08, 0.08, 0.08};
  double isoline_opacity = 0.75;

  // Polygon edges.
  bool edges = true;
  double edge_width = 1.0;  // pixels
  Color edge_color{0.12, 0.12, 0.14};
  double edge_opacity = 0.6;
  // On dense meshes edges fade: opacity times min(1, mean on-screen edge length / this), so
  // that polygons of a few pixels do not turn the surface into a texture (0: never).
  double edge_fade_length = 10;  // pixels

  // Shading: intensity = ambient + (1 - ambient) |n . light| (two-sided).
  double ambient = 0.45;
  Eigen::Vector3d light_direction{-0.25, 0.35, 1.0};  // camera frame: x right, y up, z to the viewer
  bool smooth_shading = false;

  // Annotations (pixel sizes scale with the image height).
  bool colorbar = true;  // only with a scalar
  std::string title;
  std::string scalar_label;  // printed above the colour bar
  Color background{1, 1, 1};
  Color text_color{0.1, 0.1, 0.1};

  // k x k samples per pixel for smooth silhouettes (1 = exact pixels); width * height * k^2
  // must stay below 4e7 (16 bytes of memory each).
  int supersample = 2;
};

// Renders the mesh. `vertex_scalar` has |V| values, or is empty for none. Throws
// std::invalid_argument for a scalar of the wrong size or invalid options.
Image render(const Mesh& mesh, const Eigen::VectorXd& vertex_scalar, const RenderOptions& options);

// render() written as PNG to `path` (atomically: temporary file, then rename). Throws
// FileError (dec/io/mesh_io.h) naming the path when it cannot be written.
void render_png(const std::string& path, const Mesh& mesh, const Eigen::VectorXd& vertex_scalar,
                const RenderOptions& options);

// A view direction orthogonal to `up` that looks at vertex v head-on: minus its area-weighted
// vertex normal (oriented outwards: flipped if the mesh's signed volume about its bounding-box
// centre is negative), with the `up` component removed. Zero (the default view) for a flat
// mesh or when that normal is vertical.
Eigen::Vector3d view_facing_vertex(const Mesh& mesh, int v,
                                   const Eigen::Vector3d& up = Eigen::Vector3d::UnitY());

// Triangles used to draw the polygon with corners `p` (k x 3): each row of the result holds
// three indices into the corners, index k standing for the corners' centroid (see above).
Eigen::MatrixX3i triangulate_polygon(const Eigen::MatrixX3d& p);

// Labels of a value axis from lo to hi: about `count` "nice" values (1, 2 or 5 times a power of
// ten) inside [lo, hi].
std::vector<double> nice_ticks(double lo, double hi, int count);

}  // namespace polydec
