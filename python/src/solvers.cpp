// python/src/solvers.cpp — bindings of the applications (apps/applications/): solver classes that
// factor once (HeatGeodesics, HodgeDecomposer, CurvatureFlow) and one-shot functions (spectrum,
// mean curvature, conformal parametrization). Factorizations and solves run without the GIL.
#include "bindings.h"
#include "polydec/apps/applications/curvature.h"
#include "polydec/apps/applications/geodesics.h"
#include "polydec/apps/applications/hodge_decomposition.h"
#include "polydec/apps/applications/parametrization.h"
#include "polydec/apps/applications/smoothing.h"
#include "polydec/apps/applications/spectrum.h"

namespace polydec::python {

py::tuple spectrum_to_python(const Spectrum& s) {
  py::dict info;
  info["shift"] = s.shift;
  info["n_converged"] = s.n_converged;
  info["n_solves"] = s.n_solves;
  info["method"] = s.method;
  return py::make_tuple(s.eigenvalues, s.eigenvectors, info);
}

void register_solvers(py::module_& m) {
  py::class_<HeatGeodesics>(m, "HeatGeodesics")
      .def(py::init([](const MeshHandle& h,
                       const std::string& spec, double time_step_factor, bool lumped_mass,
                       bool mass_weighted_source, double planarity) {
        const Mesh mesh = h.with_planarity(planarity);
        py::gil_scoped_release release;
        HeatGeodesicsOptions options;
        options.time_step_factor = time_step_factor;
        options.lumped_mass = lumped_mass;
        options.mass_weighted_source = mass_weighted_source;
        return std::make_unique<HeatGeodesics>(build_operators(mesh, parse_laplacian(spec), {.gradient_with_refinement = false}),
                                               mesh.mean_edge_length(), options);
      }))
      .def("distance",
           [](const HeatGeodesics& h, const std::vector<int>& sources) {
             py::gil_scoped_release release;
             return h.distance(sources);
           })
      // (distances, {"unresolved_vertices", "resolved_radius"}): HeatDiagnostics as a dict.
      .def("distance_with_diagnostics",
           [](const HeatGeodesics& h, const std::vector<int>& sources) {
             HeatDiagnostics diagnostics;
             Eigen::VectorXd d;
             {
               py::gil_scoped_release release;
               d = h.distance(sources, &diagnostics);
             }
             py::dict info;
             info["unresolved_vertices"] = diagnostics.unresolved_vertices;
             info["resolved_radius"] = diagnostics.resolved_radius;
             return py::make_tuple(d, info);
           })
      .def("distances",
           [](const HeatGeodesics& h, const std::vector<int>& sources, int block) {
             py::gil_scoped_release release;
             return h.distances(sources, block);
           })
      // Into a caller's Fortran-ordered float64 array (checked by the Python wrapper; pybind11
      // refuses any array it cannot map without a copy).
      .def("distances_into",
           [](const HeatGeodesics& h, const std::vector<int>& sources, Eigen::Ref<Eigen::MatrixXd> out, int block) {
             py::gil_scoped_release release;
             h.distances(sources, out, block);
           })
      .def("release_blocks",
           [](const HeatGeodesics& h) {
             py::gil_scoped_release release;
             h.release_blocks();
           })
      .def_property_readonly("time_step", &HeatGeodesics::time_step)
      .def_property_readonly("laplacian", [](const HeatGeodesics& h) { return h.operators().name; });

  m.def("suggested_time_factor", [](double factor, int unresolved_vertices, double resolved_radius, double extent) {
    return suggested_time_factor(factor, HeatDiagnostics{unresolved_vertices, resolved_radius}, extent);
  });

  m.def("spectrum", [](const MeshHandle& h, int k,
                       const std::string& spec, bool lumped_mass, double tolerance, int max_iterations,
                       double planarity) {
    const Mesh mesh = h.with_planarity(planarity);
    return spectrum_released(k, lumped_mass, tolerance, max_iterations, [&](const SpectrumOptions& options) {
      return laplacian_spectrum(build_operators(mesh, parse_laplacian(spec), false), options);
    });
  });

  py::class_<HodgeDecomposer>(m, "HodgeDecomposer")
      .def(py::init(
          [](const MeshHandle& h, const std::string& rule,
             const std::string& complex, double planarity) {
            const Mesh mesh = h.with_planarity(planarity);
            RefinementOptions options;
            options.rule = parse_virtual_vertex_rule(rule);
            const DecComplex kind = parse_dec_complex(complex);
            py::gil_scoped_release release;
            return std::make_unique<HodgeDecomposer>(mesh, options, kind);
          }))
      .def("decompose", &decompose_to_dict<HodgeDecomposer>)
      .def_property_readonly("pairs",
                             [](const HodgeDecomposer& h) { return Eigen::MatrixX2i(h.cells()); })
      .def_property_readonly("d0", [](const HodgeDecomposer& h) { return h.d0(); })
      .def_property_readonly("star1", [](const HodgeDecomposer& h) { return h.star1(); })
      .def_property_readonly("harmonic_basis", [](const HodgeDecomposer& h) { return h.harmonic_basis(); });

  m.def("mean_curvature", [](const MeshHandle& h,
                             const std::string& spec, bool lumped_mass, double planarity) {
    const Mesh mesh = h.with_planarity(planarity);
    py::gil_scoped_release release;
    CurvatureOptions options;
    options.lumped_mass = lumped_mass;
    return mean_curvature(build_operators(mesh, parse_laplacian(spec), false), options);
  });
  m.def("vertex_normals", [](const MeshHandle& h) {
    const Mesh& mesh = h.mesh();
    py::gil_scoped_release release;
    return Eigen::MatrixX3d(vertex_normals(mesh));
  });

  py::class_<CurvatureFlow>(m, "CurvatureFlow")
      .def(py::init([](const MeshHandle& h, double time_step,
                       bool lumped_mass, const std::string& spec, double planarity) {
        const Mesh mesh = h.with_planarity(planarity);
        py::gil_scoped_release release;
        SmoothingOptions options;
        options.time_step = time_step;
        options.lumped_mass = lumped_mass;
        return std::make_unique<CurvatureFlow>(mesh, options, parse_laplacian(spec));
      }))
      .def("step",
           [](CurvatureFlow& flow) {
             Eigen::MatrixX3d X;
             {
               py::gil_scoped_release release;
               X = flow.step().positions();
             }
             return X;
           })
      .def_property_readonly("positions",
                             [](const CurvatureFlow& f) { return Eigen::MatrixX3d(f.mesh().positions()); })
      .def_property_readonly("time_step", &CurvatureFlow::time_step)
      .def_property_readonly("area", &CurvatureFlow::area);

  m.def("conformal_parametrization",
        [](const MeshHandle& h, const std::string& spec, double planarity) {
          const Mesh mesh = h.with_planarity(planarity);
          ConformalParametrization p;
          {
            py::gil_scoped_release release;
            p = spectral_conformal_parametrization(build_operators(mesh, parse_laplacian(spec), false));
          }
          return py::make_tuple(p.uv, p.eigenvalue);
        });
  m.def("conformal_distortion",
        [](const MeshHandle& h, const Eigen::MatrixX2d& uv) {
          const Mesh& mesh = h.mesh();
          py::gil_scoped_release release;
          return conformal_distortion(mesh, uv);
        });
}

}  // namespace polydec::python
