// apps/cli/spectrum.cpp — `polydec spectrum MESH --k K --out DIR`: the k smallest eigenpairs of
// -S x = lambda M x (manifold harmonics) with Spectra's shift-invert solver; with --form 1|2 those
// of the Hodge Laplacian on Whitney 1- or 2-forms (apps/applications/form_spectrum.h). On a volume mesh
// (.ovm, .vtk, .mesh or --volume): the volume operators (operators/registry/volume_laplacians.h), Neumann,
// eigenvectors as VTK point data (.vtk, or .vtu with --vtu), the picture on a planar cut
// (apps/pictures/volume_cut.h); with --form 1|2|3 the Hodge Laplacian of volume k-forms
// (apps/applications/volume/spectrum.h). With --order 2 the quadratic operators
// (apps/applications/quadratic.h); the files hold the vertex dofs.
#include "polydec/apps/applications/spectrum.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "polydec/apps/applications/form_spectrum.h"
#include "polydec/apps/applications/quadratic.h"
#include "polydec/apps/applications/volume/spectrum.h"
#include "polydec/apps/cli/command.h"
#include "polydec/apps/cli/virtual_lift.h"
#include "polydec/apps/cli/engine.h"
#include "polydec/apps/pictures/render.h"
#include "polydec/apps/pictures/vector_field.h"
#include "polydec/apps/pictures/volume_cut.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/surface/complex.h"
#include "polydec/dec/volume/complex.h"
#include "polydec/operators/registry/volume_laplacians.h"
#include "polydec/operators/surface/face_to_vertex.h"

namespace polydec::cli::spectrum_command {
namespace {

struct Options {
  bool repair = false;  // --repair
  std::string mesh, out, png, mass = "lumped", laplacian = "ours";
  int k = 10, png_index = 1, form = 0, order = 1;
  std::string complex = "complete";  // --complex, for --form 1|2
  bool json = false, volume = false;
  bool vtu = false;      // --vtu: volume eigenvectors as eigenvectors.vtu
  EngineOptions engine;  // --engine, --solver, --petsc-options
  VirtualLiftArgs lift;  // --virtual-lift, --virtual-positions (serial surface spectra)
};

void report(const Options& o, const LazyMesh& mesh, const std::string& laplacian, int n_in, const Spectrum& sp,
            const nlohmann::json* engine, PhaseTimer& timer);

void check_form(const Options& o);
void run_form(const Options& o, const Mesh& mesh, PhaseTimer& timer);
void check_volume_form(const Options& o);
void run_volume_form(const Options& o, const VolumeMesh& mesh, PhaseTimer& timer);
void run_serial(const Options& o, const Mesh& mesh, PhaseTimer& timer);

// Picture options of eigenfunction --png-index (surfaces add smooth shading).
RenderOptions eigenfunction_picture(const Options& o, const std::vector<double>& ev,
                                    const std::string& laplacian) {
  RenderOptions ropt;
  ropt.width = 640;
  ropt.height = 480;
  ropt.isolines = 10;
  ropt.colormap = Colormap::turbo;
  ropt.scalar_label = fmt::format("u{}", o.png_index);
  ropt.title = fmt::format("eigenfunction {}, lambda = {:.4g} ({}, {} mass)", o.png_index, ev[o.png_index],
                           laplacian, o.mass);
  return ropt;
}

void write_eigenvalues(const std::string& path, const std::vector<double>& ev) {
  std::ofstream f(path);
  if (!f) throw FileError(path, 0, -1, "cannot open file for writing");
  for (double e : ev) f << fmt::format("{:.17g}\n", e);
}

// The usage errors of a volume mesh's function spectrum.
void check_volume(const Options& o) {
  if (o.engine.engine != "serial")
    throw UsageError("--engine petsc: volume meshes run on the serial engine only");
  if (o.repair) throw UsageError("--repair applies to surface meshes only");
  if (!o.png.empty() && (o.png_index < 0 || o.png_index >= o.k))
    throw UsageError("--png-index must lie in [0, k)");
}
// A volume mesh: Neumann eigenpairs of the volume operators, files and picture as described in
// docs/volumes.md.
void run_volume(const Options& o, const VolumeMesh& mesh, PhaseTimer& timer) {
  // The operators keep their refinement for the picture (only with --png).
  const OperatorSet ops = timer.time("operators", [&] {
    return build_volume_operators(mesh, parse_volume_laplacian(o.laplacian),
                                  {.with_gradient = false, .keep_refinement = !o.png.empty()});
  });
  SpectrumOptions sopt;
  sopt.k = o.k;
  sopt.lumped_mass = o.mass == "lumped";
  const Spectrum sp = timer.time("solve", [&] { return laplacian_spectrum(ops, sopt); });
  std::vector<double> ev(sp.eigenvalues.data(), sp.eigenvalues.data() + sp.eigenvalues.size());
  nlohmann::json j = {{"mesh", o.mesh},          {"laplacian", ops.name},
                      {"mass", o.mass},          {"vertices", mesh.n_vertices()},
                      {"cells", mesh.n_cells()}, {"k", o.k},
                      {"shift", sp.shift},       {"eigenvalues", ev}};
  const auto t_write = PhaseTimer::Clock::now();
  if (!o.out.empty()) {
    std::filesystem::create_directories(o.out);
    write_eigenvalues(o.out + "/eigenvalues.txt", ev);
    write_dense_matrix_market(o.out + "/eigenvectors.mtx", sp.eigenvectors);
    VertexScalars props;
    for (int i = 0; i < o.k; ++i) props[fmt::format("u{:03d}", i)] = sp.eigenvectors.col(i);
    const std::string field_file = o.vtu ? "eigenvectors.vtu" : "eigenvectors.vtk";
    write_volume_vtk_with_point_data(mesh, o.out + "/" + field_file, props);
    j["out"] = o.out;
    j["files"] = {"eigenvalues.txt", "eigenvectors.mtx", field_file};
  }
  if (!o.png.empty()) {
    render_volume_cut_png(o.png, mesh, *ops.volume_refinement, sp.eigenvectors.col(o.png_index),
                          centre_plane(mesh, Eigen::Vector3d::UnitZ()),
                          eigenfunction_picture(o, ev, ops.name));
    j["png"] = o.png;
  }
  timer.add("write", t_write);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} cells (volume); Laplacian {}, {} mass, shift {:.6g}\n", o.mesh,
             mesh.n_vertices(), mesh.n_cells(), ops.name, o.mass, sp.shift);
  fmt::print("{} smallest eigenvalues of -S x = lambda M x (Neumann):\n", o.k);
  for (int i = 0; i < o.k; ++i) fmt::print("  {:4d}  {:.10g}\n", i, ev[i]);
  if (!o.png.empty()) fmt::print("wrote {}\n", o.png);
  if (!o.out.empty())
    fmt::print(
        "wrote eigenvalues.txt, eigenvectors.mtx (|V| x k) and eigenvectors.{} (point data u000..) to {}\n",
        o.vtu ? "vtu" : "vtk", o.out);
}

void run(const Options& o) {
  if (o.mass != "lumped" && o.mass != "unlumped") throw UsageError("--mass must be lumped or unlumped");
  const bool lifted = o.lift.lift != "none" || !o.lift.positions.empty();
  const char* const lift_usage = "--virtual-lift and --virtual-positions apply to the serial surface spectrum only";
  const char* const order_usage =
      "--order 2: function spectra of surface meshes on the serial engine (no --form, --laplacian, --virtual-lift)";
  if (lifted && (o.volume || o.form != 0 || o.engine.engine != "serial")) throw UsageError(lift_usage);
  if (o.order != 1 && o.order != 2) throw UsageError("--order must be 1 or 2");
  if (o.order == 2 && (o.volume || o.form != 0 || o.engine.engine != "serial" || o.laplacian != "ours" || lifted))
    throw UsageError(order_usage);
  PhaseTimer timer;  // the PETSc engine's phases are its own (engine.per_rank); total and write here
  if (o.engine.engine == "serial") {
    const InputMesh in = timer.time("read", [&] { return load_input_mesh(o.mesh, o.volume, o.repair); });
    if (in.volume) {
      if (lifted) throw UsageError(lift_usage);
      if (o.order == 2) throw UsageError(order_usage);
      if (o.form != 0) {
        check_volume_form(o);
        return run_volume_form(o, *in.volume, timer);
      }
      check_volume(o);
      return run_volume(o, *in.volume, timer);
    }
    if (o.form != 0) {
      check_form(o);
      return run_form(o, *in.surface, timer);
    }
    return run_serial(o, *in.surface, timer);
  }
  // The distributed engine reads the file itself: only its kind is judged here.
  if (o.volume || is_volume_mesh_path(o.mesh)) {
    if (o.form != 0) check_volume_form(o);
    check_volume(o);
  }
  if (o.form != 0) check_form(o);
  if (o.engine.engine == "petsc") {
    // The distributed run (apps/cli/engine.h); rank 0 reports as the serial run does.
    if (o.laplacian != "ours") throw UsageError("--engine petsc computes the paper's Laplacian only (--laplacian ours)");
    if (!o.png.empty() && (o.png_index < 0 || o.png_index >= o.k)) throw UsageError("--png-index must lie in [0, k)");
#ifdef POLYDEC_HAVE_PETSC
    const bool vectors = !o.out.empty() || !o.png.empty();  // only the files and the picture need them
    petsc_spectrum(o.mesh, o.repair, o.k, o.mass == "lumped", vectors, o.engine, [&](const EngineSpectrum& r) {
      report(o, r.mesh, "ours", r.mesh.n_vertices, r.spectrum, &r.summary, timer);
    });
    return;
#else
    throw UsageError("--engine petsc: this polydec was built without PETSc (configure with -DPOLYDEC_WITH_PETSC=ON)");
#endif
  }
  throw UsageError("--engine must be serial or petsc");
}

// The serial function spectrum of a surface.
void run_serial(const Options& o, const Mesh& mesh, PhaseTimer& timer) {
  OperatorOptions oopt;
  oopt.with_gradient = false;
  oopt.lift = virtual_lift(o.lift, mesh);
  const OperatorSet ops = timer.time("operators", [&] {
    return o.order == 2 ? quadratic_operator_set(mesh) : build_operators(mesh, parse_laplacian(o.laplacian), oopt);
  });
  SpectrumOptions sopt;
  sopt.k = o.k;
  sopt.lumped_mass = o.mass == "lumped";
  const Spectrum sp = timer.time("solve", [&] { return laplacian_spectrum(ops, sopt); });
  report(o, LazyMesh::of(mesh), ops.name, ops.n_input_vertices, sp, nullptr, timer);
}

// The outputs of both engines: text or JSON (with the engine's summary), the files, the picture.
void report(const Options& o, const LazyMesh& mesh, const std::string& laplacian, int n_in, const Spectrum& sp,
            const nlohmann::json* engine, PhaseTimer& timer) {
  std::vector<double> ev(sp.eigenvalues.data(), sp.eigenvalues.data() + sp.eigenvalues.size());
  nlohmann::json j = {{"mesh", o.mesh},          {"laplacian", laplacian},
                      {"mass", o.mass},          {"vertices", mesh.n_vertices},
                      {"faces", mesh.n_faces}, {"k", o.k},
                      {"shift", sp.shift},       {"eigenvalues", ev}};
  if (engine) j["engine"] = *engine;
  const auto t_write = PhaseTimer::Clock::now();
  if (!o.out.empty()) {
    std::filesystem::create_directories(o.out);
    write_eigenvalues(o.out + "/eigenvalues.txt", ev);
    write_dense_matrix_market(o.out + "/eigenvectors.mtx", sp.eigenvectors.topRows(n_in));
    VertexScalars props;
    for (int i = 0; i < o.k; ++i) props[fmt::format("u{:03d}", i)] = sp.eigenvectors.col(i).head(n_in);
    write_mesh(o.out + "/eigenvectors.ply", mesh.get(), props);
    j["out"] = o.out;
    j["files"] = {"eigenvalues.txt", "eigenvectors.mtx", "eigenvectors.ply"};
  }
  if (!o.png.empty()) {
    if (o.png_index < 0 || o.png_index >= o.k) throw UsageError("--png-index must lie in [0, k)");
    RenderOptions ropt = eigenfunction_picture(o, ev, laplacian);
    ropt.smooth_shading = true;
    render_png(o.png, mesh.get(), sp.eigenvectors.col(o.png_index).head(n_in), ropt);
    j["png"] = o.png;
  }
  timer.add("write", t_write);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; Laplacian {}, {} mass, shift {:.6g}\n", o.mesh, mesh.n_vertices,
             mesh.n_faces, laplacian, o.mass, sp.shift);
  if (engine) fmt::print("engine petsc: {} ranks, {}\n", (*engine)["ranks"].get<int>(), sp.method);
  fmt::print("{} smallest eigenvalues of -S x = lambda M x:\n", o.k);
  for (int i = 0; i < o.k; ++i) fmt::print("  {:4d}  {:.10g}\n", i, ev[i]);
  if (!o.png.empty()) fmt::print("wrote {}\n", o.png);
  if (!o.out.empty())
    fmt::print("wrote eigenvalues.txt, eigenvectors.mtx (|V| x k) and eigenvectors.ply (u000..) to {}\n",
               o.out);
}


// The eigenpairs of a form spectrum as JSON: index, eigenvalue, kind and the Hodge parts' norms.
nlohmann::json form_eigenpairs_json(const FormSpectrum& sp) {
  nlohmann::json pairs = nlohmann::json::array();
  for (Eigen::Index i = 0; i < sp.eigenvalues.size(); ++i)
    pairs.push_back({{"index", i},
                     {"eigenvalue", sp.eigenvalues[i]},
                     {"kind", form_kind_name(sp.kinds[size_t(i)])},
                     {"norm_exact", sp.norm_exact[i]},
                     {"norm_coexact", sp.norm_coexact[i]},
                     {"norm_harmonic", sp.norm_harmonic[i]}});
  return pairs;
}

// eigenvalues.txt (eigenvalue, kind, the parts' norms a line) and the eigen-cochains with their
// Hodge parts (eigenvectors.mtx, exact.mtx, coexact.mtx, harmonic.mtx) into `dir`.
void write_form_spectrum_files(const std::string& dir, const FormSpectrum& sp) {
  std::filesystem::create_directories(dir);
  const std::string p = dir + "/eigenvalues.txt";
  std::ofstream f(p);
  if (!f) throw FileError(p, 0, -1, "cannot open file for writing");
  for (Eigen::Index i = 0; i < sp.eigenvalues.size(); ++i)
    f << fmt::format("{:.17g} {} {:.6g} {:.6g} {:.6g}\n", sp.eigenvalues[i], form_kind_name(sp.kinds[size_t(i)]),
                     sp.norm_exact[i], sp.norm_coexact[i], sp.norm_harmonic[i]);
  write_dense_matrix_market(dir + "/eigenvectors.mtx", sp.eigenvectors);
  write_dense_matrix_market(dir + "/exact.mtx", sp.exact);
  write_dense_matrix_market(dir + "/coexact.mtx", sp.coexact);
  write_dense_matrix_market(dir + "/harmonic.mtx", sp.harmonic);
}

// The eigenvalues with their kinds and the parts' norms, one line each, on standard output.
void print_form_eigenpairs(const FormSpectrum& sp) {
  fmt::print("{} smallest eigenvalues of the Hodge Laplacian (norms of the exact, co-exact, harmonic parts):\n",
             sp.eigenvalues.size());
  for (Eigen::Index i = 0; i < sp.eigenvalues.size(); ++i)
    fmt::print("  {:4d}  {:.10g}  {:<9} {:.3g} {:.3g} {:.3g}\n", i, sp.eigenvalues[i],
               form_kind_name(sp.kinds[size_t(i)]), sp.norm_exact[i], sp.norm_coexact[i], sp.norm_harmonic[i]);
}

// The usage errors of a surface form spectrum.
void check_form(const Options& o) {
  if (o.form != 1 && o.form != 2) throw UsageError("--form must be 0, 1 or 2");
  if (o.engine.engine != "serial") throw UsageError("--form: only the serial engine computes form spectra");
  if (o.laplacian != "ours")
    throw UsageError("--form: the Hodge Laplacian is built from the paper's stars (--laplacian ours)");
  if (o.k < 1) throw UsageError("--k must be positive");
  if (!o.png.empty() && (o.png_index < 0 || o.png_index >= o.k))
    throw UsageError("--png-index must lie in [0, k)");
  parse_option(parse_dec_complex, o.complex);
}
void run_form(const Options& o, const Mesh& mesh, PhaseTimer& timer) {
  const DecComplex complex = parse_option(parse_dec_complex, o.complex);
  const bool on_mesh = complex == DecComplex::Mesh;
  FormSpectrumOptions fo;
  fo.complex = complex;
  fo.degree = o.form;
  fo.k = o.k;
  fo.lumped_mass = o.mass == "lumped";
  const FormSpectrum sp = timer.time("solve", [&] { return form_spectrum(mesh, fo); });
  if (sp.quality.n_degenerate > 0)
    std::cerr << fmt::format(
        "polydec: warning: {} degenerate fan triangle(s) (zero area, in {} face(s)) carry no Whitney forms: "
        "zero eigenvalues beyond the Betti number may be spurious\n",
        sp.quality.n_degenerate, sp.quality.n_faces_affected);
  const CoarseComplex cx = on_mesh ? CoarseComplex() : CoarseComplex(mesh);
  const long n_cells = on_mesh ? (o.form == 1 ? mesh.n_edges() : mesh.n_faces())
                               : (o.form == 1 ? cx.n_pairs() : cx.n_triples());
  const char* cell_file = on_mesh ? (o.form == 1 ? "edges.txt" : "faces.txt") : (o.form == 1 ? "pairs.txt" : "triples.txt");
  std::vector<double> ev(sp.eigenvalues.data(), sp.eigenvalues.data() + sp.eigenvalues.size());
  const nlohmann::json pairs = form_eigenpairs_json(sp);
  nlohmann::json j = {{"mesh", o.mesh},          {"form", o.form},
                      {"mass", o.mass},          {"vertices", mesh.n_vertices()},
                      {"faces", mesh.n_faces()}, {"complex", to_string(complex)}, {"cells", n_cells},
                      {"rank", sp.rank},         {"k", o.k},
                      {"shift", sp.shift},       {"method", sp.method},
                      {"eigenvalues", ev},       {"eigenpairs", pairs},
                      {"fan_degenerate", sp.quality.n_degenerate}};
  const auto t_write = PhaseTimer::Clock::now();
  if (!o.out.empty()) {
    write_form_spectrum_files(o.out, sp);
    {
      const std::string p = o.out + "/" + cell_file;
      std::ofstream f(p);
      if (!f) throw FileError(p, 0, -1, "cannot open file for writing");
      if (on_mesh && o.form == 1)
        for (int e = 0; e < mesh.n_edges(); ++e) f << mesh.edges()(e, 0) << ' ' << mesh.edges()(e, 1) << '\n';
      else if (on_mesh)
        for (int fc = 0; fc < mesh.n_faces(); ++fc) {
          const auto face = mesh.face(fc);
          for (size_t c = 0; c < face.size(); ++c) f << (c ? " " : "") << face[c];
          f << '\n';
        }
      else if (o.form == 1)
        for (int c = 0; c < cx.n_pairs(); ++c) f << cx.pairs()(c, 0) << ' ' << cx.pairs()(c, 1) << '\n';
      else
        for (int c = 0; c < cx.n_triples(); ++c)
          f << cx.triples()(c, 0) << ' ' << cx.triples()(c, 1) << ' ' << cx.triples()(c, 2) << '\n';
    }
    std::ofstream(o.out + "/spectrum.json") << j.dump(2) << '\n';
    j["out"] = o.out;
    j["files"] = {"eigenvalues.txt", "eigenvectors.mtx", "exact.mtx",
                  "coexact.mtx",     "harmonic.mtx",     cell_file,
                  "spectrum.json"};
  }
  if (!o.png.empty()) {
    const Refinement ref = refine(mesh);
    RenderOptions ropt;
    ropt.width = 800;
    ropt.height = 600;
    ropt.colormap = Colormap::turbo;
    ropt.smooth_shading = true;
    ropt.title = fmt::format("{}-form eigenform {}, lambda = {:.4g} ({})", o.form, o.png_index,
                             ev[size_t(o.png_index)], form_kind_name(sp.kinds[size_t(o.png_index)]));
    if (o.form == 1) {
      const Eigen::MatrixX3d U =
          whitney_vectors_at_virtual_vertices(mesh, ref, sp.eigenvectors.col(o.png_index), complex);
      ropt.scalar_label = "|w|";
      render_vector_field_png(o.png, mesh, face_to_vertex(mesh, U.rowwise().norm()), ref.virtual_points, U,
                              ropt);
    } else {
      ropt.scalar_label = "density";
      ropt.isolines = 10;
      render_png(o.png, mesh,
                 face_to_vertex(mesh, whitney2_face_densities(mesh, ref, sp.eigenvectors.col(o.png_index), complex)),
                 ropt);
    }
    j["png"] = o.png;
  }
  timer.add("write", t_write);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} faces; Whitney {}-forms on the {} complex: {} cells, rank {}; shift {:.6g}\n",
             o.mesh, mesh.n_vertices(), mesh.n_faces(), o.form, to_string(complex), n_cells, sp.rank, sp.shift);
  print_form_eigenpairs(sp);
  if (!o.png.empty()) fmt::print("wrote {}\n", o.png);
  if (!o.out.empty())
    fmt::print(
        "wrote eigenvalues.txt, eigenvectors.mtx (cells x k), exact/coexact/harmonic.mtx, "
        "{} and spectrum.json to {}\n",
        cell_file, o.out);
}

// The usage errors of a volume form spectrum.
void check_volume_form(const Options& o) {
  if (o.form < 1 || o.form > 3) throw UsageError("--form must be 0, 1, 2 or 3 on volume meshes");
  if (o.engine.engine != "serial") throw UsageError("--form: only the serial engine computes form spectra");
  if (o.repair) throw UsageError("--repair applies to surface meshes only");
  if (o.laplacian != "ours")
    throw UsageError("--form: the Hodge Laplacian is built from the paper's stars (--laplacian ours)");
  if (!o.png.empty()) throw UsageError("--png: volume form spectra have no picture");
  if (o.k < 1) throw UsageError("--k must be positive");
  parse_option(parse_dec_complex, o.complex);
}
// Volume k-forms (k = 1, 2, 3): eigenvalues with their Hodge parts, the eigen-cochains on the
// k-cells, the cell list; no picture.
void run_volume_form(const Options& o, const VolumeMesh& mesh, PhaseTimer& timer) {
  const DecComplex complex = parse_option(parse_dec_complex, o.complex);
  const bool on_mesh = complex == DecComplex::Mesh;
  FormSpectrumOptions fo;
  fo.complex = complex;
  fo.degree = o.form;
  fo.k = o.k;
  fo.lumped_mass = o.mass == "lumped";
  const FormSpectrum sp = timer.time("solve", [&] { return volume_form_spectrum(mesh, fo); });
  static const char* const mesh_files[4] = {"", "edges.txt", "faces.txt", "cells.txt"};
  static const char* const complete_files[4] = {"", "pairs.txt", "triples.txt", "quadruples.txt"};
  const char* cell_file = on_mesh ? mesh_files[o.form] : complete_files[o.form];
  std::vector<double> ev(sp.eigenvalues.data(), sp.eigenvalues.data() + sp.eigenvalues.size());
  const nlohmann::json pairs = form_eigenpairs_json(sp);
  nlohmann::json j = {{"mesh", o.mesh},          {"form", o.form},
                      {"mass", o.mass},          {"vertices", mesh.n_vertices()},
                      {"cells", mesh.n_cells()}, {"complex", to_string(complex)},
                      {"k_cells", sp.eigenvectors.rows()}, {"rank", sp.rank},
                      {"k", o.k},                {"shift", sp.shift},
                      {"method", sp.method},     {"eigenvalues", ev},
                      {"eigenpairs", pairs}};
  const auto t_write = PhaseTimer::Clock::now();
  if (!o.out.empty()) {
    write_form_spectrum_files(o.out, sp);
    {
      const std::string p = o.out + "/" + cell_file;
      std::ofstream f(p);
      if (!f) throw FileError(p, 0, -1, "cannot open file for writing");
      auto line = [&](auto range) {
        bool first = true;
        for (int v : range) f << (first ? "" : " ") << v, first = false;
        f << '\n';
      };
      if (on_mesh && o.form == 1)
        for (int e = 0; e < mesh.n_edges(); ++e) f << mesh.edges()(e, 0) << ' ' << mesh.edges()(e, 1) << '\n';
      else if (on_mesh && o.form == 2)
        for (int fc = 0; fc < mesh.n_faces(); ++fc) line(mesh.face(fc));
      else if (on_mesh)
        for (int c = 0; c < mesh.n_cells(); ++c) line(mesh.cell_vertices(c));  // each cell's vertices
      else {
        const Eigen::MatrixXi S = volume_coarse_complex(mesh, o.form).simplices(o.form);
        for (Eigen::Index r = 0; r < S.rows(); ++r) {
          for (Eigen::Index c = 0; c < S.cols(); ++c) f << (c ? " " : "") << S(r, c);
          f << '\n';
        }
      }
    }
    std::ofstream(o.out + "/spectrum.json") << j.dump(2) << '\n';
    j["out"] = o.out;
    j["files"] = {"eigenvalues.txt", "eigenvectors.mtx", "exact.mtx", "coexact.mtx", "harmonic.mtx", cell_file,
                  "spectrum.json"};
  }
  timer.add("write", t_write);
  j["times_ms"] = timer.json();
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} vertices, {} cells (volume); Whitney {}-forms on the {} complex: {} k-cells, rank {}; shift {:.6g}\n",
             o.mesh, mesh.n_vertices(), mesh.n_cells(), o.form, to_string(complex), sp.eigenvectors.rows(), sp.rank,
             sp.shift);
  print_form_eigenpairs(sp);
  if (!o.out.empty())
    fmt::print("wrote eigenvalues.txt, eigenvectors.mtx (k-cells x k), exact/coexact/harmonic.mtx, {} and spectrum.json to {}\n",
               cell_file, o.out);
}

const RegisterCommand reg(
    "spectrum", "Smallest eigenpairs of the Laplacian, -S x = lambda M x (Spectra shift-invert)",
    [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("mesh", o->mesh, mesh_input_help())
          ->required();
      app.add_flag("--volume", o->volume, kVolumeFlagHelp);
      app.add_option("--k", o->k, "number of eigenpairs (default 10)");
      app.add_option(
          "--form", o->form,
          "0 (default): functions, -S x = lambda M x; 1 or 2 (volumes: 1, 2 or 3): Hodge Laplacian of Whitney "
          "k-forms (eigen-cochains, their Hodge parts; --mass is the 0-form mass M0 of the 1-form problem)");
      app.add_option("--out", o->out,
                     "output directory: eigenvalues.txt, eigenvectors.mtx, eigenvectors.ply (volumes: "
                     "eigenvectors.vtk, or with --vtu eigenvectors.vtu, with point data u000..)");
      app.add_flag("--vtu", o->vtu,
                   "volumes: write the eigenvectors as VTK XML (eigenvectors.vtu, ParaView's format)");
      app.add_option("--mass", o->mass, "lumped (default) or unlumped mass");
      app.add_option("--laplacian", o->laplacian,
                     "Laplacian: " + fmt::format("{}", fmt::join(laplacian_names(), ", ")) +
                         " (volumes: " + fmt::format("{}", fmt::join(volume_laplacian_names(), ", ")) + ")");
      app.add_option(
          "--png", o->png,
          "picture of one eigenfunction with isolines (.png); --form 1: the eigen 1-form as arrows, "
          "--form 2: its density; volumes: on the solid cut by the plane z = centre");
      app.add_option("--png-index", o->png_index, "which eigenfunction to draw (default 1)");
      app.add_option("--order", o->order,
                     "1 (default): the paper's operators; 2: quadratic elements on vertex and edge dofs (HRZ-lumped "
                     "or Galerkin mass; files and picture at the vertex dofs)");
      app.add_option("--complex", o->complex,
                     "--form 1|2|3: the cells, complete (default; the paper's vertex pairs, triples, quadruples) or "
                     "mesh (the mesh's edges, faces and cells, dec/surface/mesh_complex.h, dec/volume/mesh_complex.h)");
      app.add_flag("--json", o->json, "print one JSON object instead of text");
      add_virtual_lift_options(app, o->lift);
      add_repair_flag(app, o->repair);
      add_engine_options(app, o->engine);
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::spectrum_command
