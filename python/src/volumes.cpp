// python/src/volumes.cpp — bindings of polyhedral volume meshes: the VolumeMesh class
// (dec/mesh/volume_mesh.h, dec/io/volume_io.h, dec/mesh/volume_generators.h), the volume operators
// (operators/registry/volume_laplacians.h), volume DEC (dec/volume/hodge_star.h) and the volume applications
// (heat geodesics, spectrum, Poisson, Hodge decomposition). The Python package (polydec/_volume.py)
// checks the array inputs and carries the docstrings.
#include <algorithm>
#include <memory>
#include <mutex>
#include <set>

#include "bindings.h"
#include "polydec/apps/applications/geodesics.h"
#include "polydec/apps/applications/volume/hodge_decomposition.h"
#include "polydec/apps/applications/volume/poisson.h"
#include "polydec/apps/applications/volume/spectrum.h"
#include "polydec/dec/io/volume_io.h"
#include "polydec/dec/mesh/polyhedron_builder.h"
#include "polydec/dec/mesh/volume_generators.h"
#include "polydec/dec/volume/hodge_star.h"
#include "polydec/operators/registry/volume_laplacians.h"

namespace polydec::python {
namespace {

std::vector<int> to_vector(const IndexArray& a) {
  if (a.ndim() != 1) throw std::invalid_argument("index lists must be 1-D arrays");
  return std::vector<int>(a.data(), a.data() + a.size());
}

// Checks offsets of a flat list: |offsets| >= 1, starts at 0, ends at n, never decreases.
void check_offsets(const std::vector<int>& offsets, size_t n, const char* what) {
  if (offsets.empty() || offsets.front() != 0 || offsets.back() != long(n))
    throw std::invalid_argument(std::string(what) +
                                " offsets must start at 0 and end at the number of indices");
  for (size_t k = 0; k + 1 < offsets.size(); ++k)
    if (offsets[k] > offsets[k + 1])
      throw std::invalid_argument(std::string(what) + " offsets decrease at entry " + std::to_string(k));
}

// Runs `make` (a VolumeMesh factory) with the GIL released.
template <class F>
VolumeMesh released(F&& make) {
  py::gil_scoped_release release;
  return make();
}

// Flat (half-faces, offsets) of the cells.
py::tuple cell_arrays(const VolumeMesh& mesh) {
  std::vector<int> hf, off{0};
  for (int c = 0; c < mesh.n_cells(); ++c) {
    for (int h : mesh.cell(c)) hf.push_back(h);
    off.push_back(int(hf.size()));
  }
  return py::make_tuple(py::array_t<int>(long(hf.size()), hf.data()),
                        py::array_t<int>(long(off.size()), off.data()));
}

// A VolumeMesh's refinements (dec/volume/refinement.h, default tolerances), built on first use per
// cell-point rule and kept: the Python VolumeMesh holds one beside its mesh, which the binding keeps
// alive as long as the cache. Thread-safe (the bindings release the GIL).
class VolumeRefinements {
 public:
  explicit VolumeRefinements(const VolumeMesh& mesh) : mesh_(mesh) {}
  // The refinement with `rule`, built on the first call (with `threads`) and cached.
  std::shared_ptr<const VolumeRefinement> get(CellPointRule rule, int threads) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto& r = cached_[int(rule)];
    if (!r) {
      VolumeRefinementOptions options;
      options.cell_rule = rule;
      options.threads = threads;
      r = std::make_shared<const VolumeRefinement>(refine_volume(mesh_, options));
    }
    return r;
  }
  // get(rule, threads) for `mesh`: std::invalid_argument when this cache belongs to another mesh.
  std::shared_ptr<const VolumeRefinement> for_rule(const VolumeMesh& mesh, CellPointRule rule, int threads) {
    if (&mesh != &mesh_) throw std::invalid_argument("the refinement cache belongs to another volume mesh");
    return get(rule, threads);
  }
  // The refinement of a volume method (ours and diamond: squared-volume, polylaplace: polylaplace).
  std::shared_ptr<const VolumeRefinement> for_method(const VolumeMesh& mesh, const LaplacianChoice& choice,
                                                     int threads) {
    return for_rule(mesh, choice.method == "polylaplace" ? CellPointRule::PolyLaplace : CellPointRule::SquaredVolume,
                    threads);
  }
  int n_cached() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return int(std::count_if(std::begin(cached_), std::end(cached_), [](const auto& r) { return bool(r); }));
  }
  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& r : cached_) r.reset();
  }

 private:
  const VolumeMesh& mesh_;
  mutable std::mutex mutex_;
  std::shared_ptr<const VolumeRefinement> cached_[2];  // by CellPointRule
};

// build_volume_operators on the cache's refinement (when a cache is given).
OperatorSet cached_operators(const VolumeMesh& mesh, const LaplacianChoice& choice, VolumeOperatorOptions options,
                             VolumeRefinements* cache) {
  std::shared_ptr<const VolumeRefinement> r;
  if (cache) {
    r = cache->for_method(mesh, choice, options.threads);
    options.refinement = r.get();
  }
  return build_volume_operators(mesh, choice, options);
}

const char* kParts[] = {"S", "M", "M_lumped", "G", "D"};

py::dict volume_operator_dict(const VolumeMesh& mesh, const std::string& spec,
                              const std::set<std::string>& parts, int threads, VolumeRefinements* cache) {
  if (threads < 0) throw std::invalid_argument("threads must be at least 0 (0: all hardware threads)");
  for (const auto& p : parts)
    if (std::find(std::begin(kParts), std::end(kParts), p) == std::end(kParts))
      throw std::invalid_argument("unknown operator part '" + p + "' (known: S, M, M_lumped, G, D)");
  const LaplacianChoice choice = parse_volume_laplacian(spec);
  OperatorSet ops = without_gil([&] {
    VolumeOperatorOptions options;
    options.with_gradient = parts.count("G") || parts.count("D");
    options.threads = threads;
    return cached_operators(mesh, choice, options, cache);
  });
  const SubTetQuality& q = ops.sub_tet_quality;
  py::dict d;
  d["name"] = ops.name;
  d["subtet_degenerate"] = q.n_degenerate;
  d["subtet_inverted"] = q.n_inverted;
  d["cells_affected"] = q.n_cells_affected;
  if (parts.count("S")) d["S"] = to_scipy(ops.S);
  if (parts.count("M")) d["M"] = to_scipy(ops.M);
  if (parts.count("M_lumped")) d["M_lumped"] = to_numpy(ops.M_lumped);
  if (parts.count("G")) d["G"] = to_scipy(ops.G);
  if (parts.count("D")) d["D"] = to_scipy(ops.D);
  if (parts.count("G")) d["G_blocks"] = ops.G_blocks;
  return d;
}

py::dict poisson_dict(const VolumePoissonError& e) {
  py::dict d;
  d["h"] = e.h;
  d["l2_error"] = e.l2_error;
  d["rms_error"] = e.rms_error;
  d["n_vertices"] = e.n_vertices;
  d["n_cells"] = e.n_cells;
  d["n_boundary"] = e.n_boundary;
  d["solution"] = e.solution;
  d["exact"] = e.exact;
  return d;
}

VolumeRefinementOptions refinement_options(const std::string& cell_point) {
  VolumeRefinementOptions o;
  o.cell_rule = parse_cell_point_rule(cell_point);
  return o;
}

}  // namespace

void register_volumes(py::module_& m) {
  py::class_<VolumeMesh>(m, "VolumeMesh")
      .def_static("from_soup",
                  [](const PositionArray& V, const IndexArray& face_indices, const IndexArray& face_offsets,
                     const IndexArray& cell_halffaces, const IndexArray& cell_offsets) {
                    PolyhedronSoup soup;
                    soup.positions = positions_from_array(V);
                    soup.face_indices = to_vector(face_indices);
                    soup.face_offsets = to_vector(face_offsets);
                    soup.cell_halffaces = to_vector(cell_halffaces);
                    soup.cell_offsets = to_vector(cell_offsets);
                    return released([&] { return VolumeMesh(std::move(soup)); });
                  })
      .def_static(
          "from_cells",
          [](const PositionArray& V, const IndexArray& polygon_indices, const IndexArray& polygon_offsets,
             const IndexArray& cell_offsets) {
            const std::vector<int> pi = to_vector(polygon_indices), po = to_vector(polygon_offsets),
                                   co = to_vector(cell_offsets);
            check_offsets(po, pi.size(), "polygon");
            check_offsets(co, po.size() - 1, "cell");
            PolyhedronSoupBuilder builder(positions_from_array(V));
            return released([&] {
              for (size_t c = 0; c + 1 < co.size(); ++c) {
                for (int p = co[c]; p < co[c + 1]; ++p)
                  if (builder.add_polygon({pi.data() + po[p], size_t(po[p + 1] - po[p])}) < 0)
                    throw InvalidMeshError(
                        "cell", long(c),
                        "cell " + std::to_string(c) + ", face " + std::to_string(p - co[c]) +
                            ": the vertices of an earlier face in a cyclic order that is neither the same "
                            "nor reversed");
                builder.end_cell();
              }
              return VolumeMesh(builder.take());
            });
          })
      // Cells by VTK type (10 tetra, 12 hexahedron, 13 wedge, 14 pyramid: their vertices in VTK's
      // order; 42 polyhedron: VTK's face stream, the number of faces, then per face its size and
      // vertices), concatenated in `items` with offsets per cell; vertex indices checked by the caller.
      .def_static(
          "from_typed_cells",
          [](const PositionArray& V, const IndexArray& types, const IndexArray& items, const IndexArray& offsets) {
            const std::vector<int> t = to_vector(types), it = to_vector(items), off = to_vector(offsets);
            check_offsets(off, it.size(), "cell");
            if (off.size() != t.size() + 1)
              throw std::invalid_argument("one cell type per cell expected");
            PolyhedronSoupBuilder builder(positions_from_array(V));
            return released([&] {
              for (size_t c = 0; c < t.size(); ++c) {
                const int* x = it.data() + off[c];
                const int n = off[c + 1] - off[c];
                const std::string where = "cell " + std::to_string(c);
                if (t[c] == kVtkPolyhedron) {
                  int k = 1;
                  for (int face = 0; n > 0 && face < x[0]; ++face) {
                    if (k >= n || x[k] < 3 || x[k] > n - k - 1)
                      throw InvalidMeshError("cell", long(c), where + ": truncated polyhedron face stream");
                    if (builder.add_polygon({x + k + 1, size_t(x[k])}) < 0)
                      throw InvalidMeshError("cell", long(c), where + ", face " + std::to_string(face) +
                                                                  ": the vertices of an earlier face in another "
                                                                  "cyclic order");
                    k += x[k] + 1;
                  }
                  if (n == 0 || k != n)
                    throw InvalidMeshError("cell", long(c), where + ": malformed polyhedron face stream");
                  builder.end_cell();
                  continue;
                }
                if (vtk_cell_size(t[c]) == 0)
                  throw InvalidMeshError("cell", long(c),
                                         where + ": unsupported VTK cell type " + std::to_string(t[c]));
                if (n != vtk_cell_size(t[c]))
                  throw InvalidMeshError("cell", long(c), where + ": " + std::to_string(vtk_cell_size(t[c])) +
                                                              " vertices expected, got " + std::to_string(n));
                if (!builder.add_vtk_cell(t[c], {x, size_t(n)}))
                  throw InvalidMeshError("cell", long(c), where + ": a face has the vertices of an earlier face "
                                                                  "in another cyclic order");
              }
              return VolumeMesh(builder.take());
            });
          })
      .def_static("read",
                  [](const std::string& path) { return released([&] { return read_volume_mesh(path); }); })
      .def("write",
           [](const VolumeMesh& mesh, const std::string& path, const VertexScalars& scalars) {
             py::gil_scoped_release release;
             if (scalars.empty())
               write_volume_mesh(mesh, path);
             else
               write_volume_vtk_with_point_data(mesh, path, scalars);
           })
      .def("with_positions",
           [](const VolumeMesh& mesh, const PositionArray& V) {
             Eigen::MatrixX3d X = positions_from_array(V);
             if (X.rows() != mesh.n_vertices())
               throw std::invalid_argument("with_positions: " + std::to_string(mesh.n_vertices()) +
                                           " positions expected, got " + std::to_string(X.rows()));
             return released([&] { return mesh.with_positions(std::move(X)); });
           })
      .def("with_precision",
           [](const VolumeMesh& mesh, double noise, double planarity_tolerance) {
             return mesh.with_precision(CoordinatePrecision{noise, planarity_tolerance});
           })
      .def_property_readonly("coordinate_noise", [](const VolumeMesh& m) { return m.precision().noise; })
      .def_property_readonly("planarity_tolerance",
                             [](const VolumeMesh& m) { return m.precision().planarity_tolerance; })
      .def_property_readonly("n_vertices", &VolumeMesh::n_vertices)
      .def_property_readonly("n_edges", &VolumeMesh::n_edges)
      .def_property_readonly("n_faces", &VolumeMesh::n_faces)
      .def_property_readonly("n_cells", &VolumeMesh::n_cells)
      .def_property_readonly("n_unreferenced_vertices", &VolumeMesh::n_unreferenced_vertices)
      .def_property_readonly("positions", [](const VolumeMesh& m) { return Eigen::MatrixX3d(m.positions()); })
      .def_property_readonly("faces",
                             [](const VolumeMesh& m) {
                               const auto &I = m.face_indices(), &O = m.face_offsets();
                               return py::make_tuple(py::array_t<int>(long(I.size()), I.data()),
                                                     py::array_t<int>(long(O.size()), O.data()));
                             })
      .def_property_readonly("cells", &cell_arrays)
      .def_property_readonly("face_cells",
                             [](const VolumeMesh& m) {
                               Eigen::MatrixX2i fc(m.n_faces(), 2);
                               for (int f = 0; f < m.n_faces(); ++f)
                                 fc.row(f) << m.face_cells(f)[0], m.face_cells(f)[1];
                               return fc;
                             })
      .def_property_readonly("edges", [](const VolumeMesh& m) { return Eigen::MatrixX2i(m.edges()); })
      .def_property_readonly("boundary_vertices",
                             [](const VolumeMesh& m) {
                               py::array_t<bool> b(m.n_vertices());
                               for (int v = 0; v < m.n_vertices(); ++v)
                                 b.mutable_data()[v] = m.is_boundary_vertex(v);
                               return b;
                             })
      .def_property_readonly("cell_volumes",
                             [](const VolumeMesh& m) {
                               Eigen::VectorXd w(m.n_cells());
                               for (int c = 0; c < m.n_cells(); ++c) w[c] = m.cell_volume(c);
                               return w;
                             })
      .def_property_readonly("volume", &VolumeMesh::volume)
      .def_property_readonly("mean_edge_length", &VolumeMesh::mean_edge_length)
      .def_property_readonly("bounding_box_diagonal", &VolumeMesh::bounding_box_diagonal)
      .def("boundary_surface", [](const VolumeMesh& m) { return mesh_to_arrays(m.boundary_surface()); });

  const auto jitter = [](double amplitude, std::uint64_t seed) { return VolumeJitter{amplitude, seed}; };
  m.def("jitter_interior", [=](const VolumeMesh& mesh, double amplitude, std::uint64_t seed) {
    return released([&] { return jitter_interior(mesh, jitter(amplitude, seed)); });
  });
  m.def("hex_grid_volume", [=](int nx, int ny, int nz, double a, std::uint64_t s) {
    return released([&] { return hex_grid_volume(nx, ny, nz, jitter(a, s)); });
  });
  m.def("tet_grid_volume", [=](int nx, int ny, int nz, double a, std::uint64_t s) {
    return released([&] { return tet_grid_volume(nx, ny, nz, jitter(a, s)); });
  });
  m.def("pyramid_grid_volume", [=](int nx, int ny, int nz, double a, std::uint64_t s) {
    return released([&] { return pyramid_grid_volume(nx, ny, nz, jitter(a, s)); });
  });
  m.def("truncated_octahedra_volume", [=](int n, double a, std::uint64_t s) {
    return released([&] { return truncated_octahedra_volume(n, jitter(a, s)); });
  });
  m.def("cuboctahedra_volume", [=](int n, double a, std::uint64_t s) {
    return released([&] { return cuboctahedra_volume(n, jitter(a, s)); });
  });
  m.def("hex_torus_volume", [=](int n_around, int n_cross, double R, double r, double a, std::uint64_t s) {
    return released([&] { return hex_torus_volume(n_around, n_cross, R, r, jitter(a, s)); });
  });
  m.def("hex_ball_volume", [=](int n, double a, std::uint64_t s) {
    return released([&] { return hex_ball_volume(n, jitter(a, s)); });
  });

  m.def("volume_laplacian_names", &volume_laplacian_names);
  py::class_<VolumeRefinements>(m, "VolumeRefinements")
      .def(py::init<const VolumeMesh&>(), py::keep_alive<1, 2>())
      .def_property_readonly("n_cached", &VolumeRefinements::n_cached)
      .def("clear", &VolumeRefinements::clear);
  m.def("volume_operators", &volume_operator_dict, py::arg("mesh"), py::arg("laplacian"), py::arg("parts"),
        py::arg("threads"), py::arg("cache") = nullptr);

  m.def("volume_dec_max_degree", &volume_dec_max_degree);
  m.def("volume_dec", [](const VolumeMesh& mesh, int max_degree, const std::string& cell_point,
                         const std::string& complex, const std::string& spoke_rule, VolumeRefinements* cache) {
    const VolumeRefinementOptions ropt = refinement_options(cell_point);
    VolumeDecOptions options;
    options.complex = parse_dec_complex(complex);
    options.spoke_rule = parse_spoke_rule(spoke_rule);
    VolumeDec D = without_gil([&] {
      if (max_degree < 0) max_degree = options.complex == DecComplex::Mesh ? 3 : volume_dec_max_degree(mesh);
      options.max_degree = max_degree;
      if (cache) return volume_dec(mesh, *cache->for_rule(mesh, ropt.cell_rule, 1), options);
      return volume_dec(mesh, refine_volume(mesh, ropt), options);
    });
    py::dict d;
    d["max_degree"] = D.max_degree;
    const char* d_names[] = {"d0", "d1", "d2"};
    const char* P_names[] = {"P0", "P1", "P2", "P3"};
    const char* star_names[] = {"star0", "star1", "star2", "star3"};
    py::list d_list, P_list, star_list;  // the same scipy objects as d0, P0, star0, ...
    auto put = [&](const char* name, SparseMatrix& A, py::list& list) {
      const py::object o = to_scipy(A);
      d[name] = o;
      list.append(o);
    };
    for (int k = 0; k <= D.max_degree; ++k) {
      if (k < D.max_degree) put(d_names[k], D.d[k], d_list);
      put(P_names[k], D.P[k], P_list);
      put(star_names[k], D.star[k], star_list);
    }
    d["complex"] = to_string(D.complex);
    if (D.complex == DecComplex::Mesh) {
      d["d"] = d_list;
      d["P"] = P_list;
      d["star"] = star_list;
      d["edges"] = Eigen::MatrixX2i(mesh.edges());
      py::list faces, cells;
      for (int f = 0; f < mesh.n_faces(); ++f) faces.append(std::vector<int>(mesh.face(f).begin(), mesh.face(f).end()));
      for (int c = 0; c < mesh.n_cells(); ++c) cells.append(std::vector<int>(mesh.cell(c).begin(), mesh.cell(c).end()));
      d["faces"] = faces;
      d["cells"] = cells;
      return d;
    }
    if (D.max_degree >= 1) d["pairs"] = D.coarse.simplices(1);
    if (D.max_degree >= 2) d["triples"] = D.coarse.simplices(2);
    if (D.max_degree >= 3) d["quads"] = D.coarse.simplices(3);
    return d;
  });

  m.def("volume_heat_geodesics", [](const VolumeMesh& mesh, const std::string& spec, double time_step_factor,
                                    bool lumped_mass, bool mass_weighted_source, VolumeRefinements* cache) {
    const LaplacianChoice choice = parse_volume_laplacian(spec);
    py::gil_scoped_release release;
    HeatGeodesicsOptions options;
    options.time_step_factor = time_step_factor;
    options.lumped_mass = lumped_mass;
    options.mass_weighted_source = mass_weighted_source;
    return std::make_unique<HeatGeodesics>(cached_operators(mesh, choice, {}, cache), mesh.mean_edge_length(),
                                           options);
  });

  m.def("volume_spectrum", [](const VolumeMesh& mesh, int k, const std::string& spec, bool dirichlet,
                              bool lumped_mass, double tolerance, int max_iterations, VolumeRefinements* cache) {
    const LaplacianChoice choice = parse_volume_laplacian(spec);
    return spectrum_released(k, lumped_mass, tolerance, max_iterations, [&](const SpectrumOptions& options) {
      return volume_laplacian_spectrum(cached_operators(mesh, choice, {.with_gradient = false}, cache), mesh,
                                       dirichlet, options);
    });
  });
  m.def("ball_eigenvalues", [](int count, bool dirichlet) {
    const std::vector<BallEigenvalue> b = ball_eigenvalues(count, dirichlet);
    Eigen::VectorXd lambda(long(b.size()));
    Eigen::VectorXi l(long(b.size())), n(long(b.size()));
    for (size_t i = 0; i < b.size(); ++i) {
      lambda[long(i)] = b[i].lambda;
      l[long(i)] = b[i].l;
      n[long(i)] = b[i].n;
    }
    return py::make_tuple(lambda, l, n);
  });

  m.def("volume_poisson", [](const VolumeMesh& mesh, const Eigen::VectorXd& exact,
                             const Eigen::VectorXd& laplacian, const std::string& spec, bool lumped_mass,
                             VolumeRefinements* cache) {
    const LaplacianChoice choice = parse_volume_laplacian(spec);
    VolumePoissonError e;
    {
      py::gil_scoped_release release;
      e = volume_dirichlet_poisson(cached_operators(mesh, choice, {.with_gradient = false}, cache), mesh,
                                   exact, laplacian, lumped_mass);
    }
    return poisson_dict(e);
  });
  m.def("volume_franke_poisson", [](const VolumeMesh& mesh, const std::string& spec, bool lumped_mass,
                                    VolumeRefinements* cache) {
    const LaplacianChoice choice = parse_volume_laplacian(spec);
    VolumePoissonError e;
    {
      py::gil_scoped_release release;
      e = volume_franke_poisson(cached_operators(mesh, choice, {.with_gradient = false}, cache), mesh, lumped_mass);
    }
    return poisson_dict(e);
  });

  py::class_<VolumeHodgeDecomposer>(m, "VolumeHodgeDecomposer")
      .def(py::init([](const VolumeMesh& mesh, const std::string& cell_point, const std::string& complex,
                       VolumeRefinements* cache) {
        const VolumeRefinementOptions options = refinement_options(cell_point);
        const DecComplex kind = parse_dec_complex(complex);
        py::gil_scoped_release release;
        if (!cache) return std::make_unique<VolumeHodgeDecomposer>(mesh, options, kind);
        const auto r = cache->for_rule(mesh, options.cell_rule, options.threads);
        return std::make_unique<VolumeHodgeDecomposer>(VolumeHodgeDecomposer::on_refinement(mesh, *r, kind));
      }))
      .def("decompose", &decompose_to_dict<VolumeHodgeDecomposer>)
      .def_property_readonly("pairs",
                             [](const VolumeHodgeDecomposer& h) { return Eigen::MatrixX2i(h.cells()); })
      .def_property_readonly("d0", [](const VolumeHodgeDecomposer& h) { return h.dec().d[0]; })
      .def_property_readonly("star1", [](const VolumeHodgeDecomposer& h) { return h.dec().star[1]; })
      .def_property_readonly("harmonic_basis", &VolumeHodgeDecomposer::harmonic_basis);
}

}  // namespace polydec::python
