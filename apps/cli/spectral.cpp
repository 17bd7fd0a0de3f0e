// apps/cli/spectral.cpp — `polydec spectral MESH --hks|--wks|--biharmonic V|--diffusion V|--filter K`:
// the spectral shape tools of apps/applications/spectral_tools.h from k eigenpairs, written as
// PLY vertex properties (--out) and a picture (--png).
#include <fmt/format.h>

#include <cmath>

#include "polydec/apps/applications/spectral_tools.h"
#include "polydec/apps/cli/command.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/dec/io/mesh_io.h"

namespace polydec::cli::spectral_command {
namespace {

struct Options {
  bool repair = false;
  std::string mesh, out, png;
  int k = 100, samples = 100, filter = 0, png_sample = -1;
  int biharmonic = -1, diffusion = -1;
  double time = 0;  // diffusion time; 0: 1 / lambda_1
  bool hks = false, wks = false, json = false;
};

// File vertex -> mesh vertex (after --repair), or an out_of_range naming the vertex.
int map_vertex(const std::vector<int>& vertex_map, int v, const char* option) {
  if (v < 0 || v >= int(vertex_map.size()))
    throw std::out_of_range(
        fmt::format("{} {} is out of range (the mesh has {} vertices)", option, v, vertex_map.size()));
  if (vertex_map[size_t(v)] < 0)
    throw std::out_of_range(fmt::format("{} {} was removed by --repair", option, v));
  return vertex_map[size_t(v)];
}

void run(const Options& o) {
  const int n_tools =
      int(o.hks) + int(o.wks) + int(o.biharmonic >= 0) + int(o.diffusion >= 0) + int(o.filter > 0);
  if (n_tools != 1)
    throw UsageError("give exactly one of --hks, --wks, --biharmonic V, --diffusion V, --filter K");
  if (o.out.empty() && o.png.empty() && !o.json)
    throw UsageError("nothing to write: give --out FILE.ply, --png or --json");
  if (o.samples < 2) throw UsageError("--samples must be at least 2");
  std::vector<int> vertex_map;
  PhaseTimer timer;
  const Mesh mesh = timer.time("read", [&] { return load_mesh(o.mesh, o.repair, &vertex_map); });
  const OperatorSet ops = timer.time("operators", [&] { return build_operators(mesh, parse_laplacian("ours"), false); });
  SpectrumOptions so;
  // At most all eigenpairs but one (the solver's limit); --filter K needs K of them.
  const int n_ref = mesh.n_vertices() - mesh.n_unreferenced_vertices();
  if (o.filter >= n_ref)
    throw UsageError(fmt::format("--filter {} must be below the {} vertices", o.filter, n_ref));
  so.k = std::min(std::max(o.k, o.filter), n_ref - 1);
  const Spectrum sp = timer.time("solve", [&] { return laplacian_spectrum(ops, so); });
  nlohmann::json j = {{"mesh", o.mesh},
                      {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()},
                      {"k", so.k},
                      {"lambda_1", sp.eigenvalues.size() > 1 ? sp.eigenvalues[1] : 0.0},
                      {"lambda_max", sp.eigenvalues[sp.eigenvalues.size() - 1]}};
  VertexScalars props;
  Eigen::VectorXd picture;
  std::string label, title;
  Mesh out_mesh = mesh;
  if (o.hks || o.wks) {
    Eigen::MatrixXd sig;
    Eigen::VectorXd x;
    if (o.hks) {
      x = hks_times(sp, o.samples);
      sig = heat_kernel_signature(sp, x);
      j["tool"] = "hks";
      j["times"] = std::vector<double>(x.data(), x.data() + x.size());
    } else {
      const WksSamples ws = wks_samples(sp, o.samples);
      x = ws.energies;
      sig = wave_kernel_signature(sp, x, ws.sigma);
      j["tool"] = "wks";
      j["log_energies"] = std::vector<double>(x.data(), x.data() + x.size());
      j["sigma"] = ws.sigma;
    }
    const char* name = o.hks ? "hks" : "wks";
    for (int s = 0; s < o.samples; ++s) props[fmt::format("{}_{:03d}", name, s)] = sig.col(s);
    const int ps = o.png_sample >= 0 ? o.png_sample : o.samples / 2;
    if (ps >= o.samples) throw UsageError("--png-sample must lie in [0, samples)");
    picture = sig.col(ps);
    label = fmt::format("{}_{:03d}", name, ps);
    title = o.hks ? fmt::format("heat kernel signature, t = {:.4g}", x[ps])
                  : fmt::format("wave kernel signature, log e = {:.4g}", x[ps]);
  } else if (o.biharmonic >= 0 || o.diffusion >= 0) {
    const bool bih = o.biharmonic >= 0;
    const int v = bih ? map_vertex(vertex_map, o.biharmonic, "--biharmonic")
                      : map_vertex(vertex_map, o.diffusion, "--diffusion");
    const double t = o.time > 0 ? o.time : 1 / sp.eigenvalues[1];
    picture = bih ? biharmonic_distance(sp, v, 0) : diffusion_distance(sp, t, v, 0);
    label = bih ? "biharmonic" : "diffusion";
    props[label] = picture;
    j["tool"] = label;
    j["source"] = v;
    if (!bih) j["time"] = t;
    j["max_distance"] = picture.maxCoeff();
    title = bih ? fmt::format("biharmonic distance from vertex {}", v)
                : fmt::format("diffusion distance from vertex {}, t = {:.4g}", v, t);
  } else {
    const Eigen::MatrixX3d Y = lowpass_filter(sp, ops.M_lumped, mesh.positions(), o.filter);
    out_mesh = mesh.with_positions(Y);
    picture = (Y - mesh.positions()).rowwise().norm();
    label = "displacement";
    props[label] = picture;
    j["tool"] = "filter";
    j["eigenvectors_kept"] = o.filter;
    j["max_displacement"] = picture.maxCoeff();
    title = fmt::format("low-pass filter, {} eigenvectors", o.filter);
  }
  const auto t_write = PhaseTimer::Clock::now();
  if (!o.out.empty()) {
    write_mesh(o.out, out_mesh, props);
    j["out"] = o.out;
  }
  if (!o.png.empty()) {
    RenderOptions r;
    r.width = 800;
    r.height = 600;
    r.colormap = Colormap::turbo;
    r.isolines = 12;
    r.smooth_shading = true;
    r.scalar_label = label;
    r.title = title;
    render_png(o.png, out_mesh, picture, r);
    j["png"] = o.png;
  }
  timer.add("write", t_write);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; {} eigenpairs, lambda_1 = {:.6g}, lambda_max = {:.6g}\n", o.mesh,
             mesh.n_vertices(), mesh.n_faces(), so.k, sp.eigenvalues[1],
             sp.eigenvalues[sp.eigenvalues.size() - 1]);
  fmt::print("{}: {} in [{:.6g}, {:.6g}]\n", j["tool"].get<std::string>(), label, picture.minCoeff(),
             picture.maxCoeff());
  if (!o.out.empty()) fmt::print("wrote {}\n", o.out);
  if (!o.png.empty()) fmt::print("wrote {}\n", o.png);
}

const RegisterCommand reg(
    "spectral",
    "Spectral shape tools: heat/wave kernel signatures, biharmonic/diffusion distance, low-pass filter",
    [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("mesh", o->mesh, mesh_input_help(false))->required();
      app.add_flag("--hks", o->hks,
                   "heat kernel signature at --samples log-spaced times (properties hks_000..)");
      app.add_flag("--wks", o->wks, "wave kernel signature at --samples log energies (properties wks_000..)");
      app.add_option("--biharmonic", o->biharmonic, "biharmonic distance from this vertex (file index)");
      app.add_option("--diffusion", o->diffusion, "diffusion distance from this vertex (file index)");
      app.add_option("--time", o->time, "diffusion time (default 1 / lambda_1)");
      app.add_option("--filter", o->filter,
                     "keep the first K eigenvectors of the coordinates (manifold harmonics)");
      app.add_option("--k", o->k, "number of eigenpairs (default 100; --filter K uses max(k, K))");
      app.add_option("--samples", o->samples, "HKS times / WKS energies (default 100)");
      app.add_option("--out", o->out,
                     "PLY file with the values as vertex properties (--filter: the filtered mesh)");
      app.add_option("--png", o->png, "picture (.png)");
      app.add_option("--png-sample", o->png_sample, "which HKS/WKS sample to draw (default the middle one)");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      add_repair_flag(app, o->repair);
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::spectral_command
