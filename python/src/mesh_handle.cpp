// python/src/mesh_handle.cpp — the class polydec._polydec.Mesh (MeshHandle, bindings.h): a surface
// mesh validated once, its refinements cached per (virtual-vertex rule, planarity), its topology
// (boundary loops, edges, counts) and a pickle state that keeps the coordinate precision.
#include <cmath>

#include "bindings.h"

namespace polydec::python {

Mesh MeshHandle::with_planarity(double planarity) const {
  if (planarity < 0) return mesh_;
  CoordinatePrecision p;  // 0: the doubles themselves (noise 0)
  p.planarity_tolerance = planarity;
  return mesh_.with_precision(p);
}

std::shared_ptr<const Refinement> MeshHandle::refinement(VirtualVertexRule rule, double planarity,
                                                         int threads) const {
  const std::tuple<int, double> key{int(rule), planarity < 0 ? -1.0 : planarity};
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = refinements_.find(key);
  if (it != refinements_.end()) return it->second;
  RefinementOptions options;
  options.rule = rule;
  options.threads = threads;
  auto r = std::make_shared<const Refinement>(planarity < 0 ? refine(mesh_, options)
                                                            : refine(with_planarity(planarity), options));
  refinements_.emplace(key, r);
  return r;
}

int MeshHandle::n_cached() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return int(refinements_.size());
}

void MeshHandle::clear_refinements() const {
  std::lock_guard<std::mutex> lock(mutex_);
  refinements_.clear();
}

namespace {

using Handle = std::shared_ptr<MeshHandle>;

Handle make_handle(Mesh mesh) { return std::make_shared<MeshHandle>(std::move(mesh)); }

Eigen::VectorXi to_eigen(const std::vector<int>& v) {
  return Eigen::Map<const Eigen::VectorXi>(v.data(), long(v.size()));
}

// Checks a planarity argument as the Python package passes it (see MeshHandle).
double checked_planarity(double planarity) {
  if (!(std::isfinite(planarity) && planarity < 1))
    throw std::invalid_argument("planarity tolerance must be finite and below 1");
  return planarity;
}

}  // namespace

void register_mesh_handle(py::module_& m) {
  py::class_<MeshHandle, Handle>(m, "Mesh")
      .def_static("from_arrays",
                  [](const PositionArray& V, const IndexArray& I, const IndexArray& O, double noise,
                     double planarity_tolerance) {
                    PolygonSoup soup = soup_from_arrays(V, I, O);
                    soup.precision.noise = noise;
                    soup.precision.planarity_tolerance = planarity_tolerance;
                    py::gil_scoped_release release;
                    return make_handle(Mesh(std::move(soup)));
                  })
      .def("with_positions",
           [](const MeshHandle& h, const PositionArray& V) {
             Eigen::MatrixX3d X = positions_from_array(V);
             py::gil_scoped_release release;
             return make_handle(h.mesh().with_positions(std::move(X)));
           })
      .def("with_planarity",
           [](const MeshHandle& h, double planarity) {
             return make_handle(h.with_planarity(checked_planarity(planarity)));
           })
      .def("refine",
           [](const MeshHandle& h, const std::string& rule, double planarity, int threads) {
             const VirtualVertexRule r = parse_virtual_vertex_rule(rule);
             checked_planarity(planarity);
             std::shared_ptr<const Refinement> ref;
             {
               py::gil_scoped_release release;
               ref = h.refinement(r, planarity, threads);
             }
             py::dict d;
             d["weights"] = Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(ref->weights.data(),
                                                                              long(ref->weights.size())));
             d["virtual_points"] = ref->virtual_points;
             d["degenerate_fan_triangles"] = ref->quality.n_degenerate;
             d["inverted_fan_triangles"] = ref->quality.n_inverted;
             d["faces_affected"] = ref->quality.n_faces_affected;
             return d;
           })
      .def_property_readonly("n_cached_refinements", &MeshHandle::n_cached)
      .def("clear_refinements", &MeshHandle::clear_refinements)
      .def_property_readonly("arrays", [](const MeshHandle& h) { return mesh_to_arrays(h.mesh()); })
      .def_property_readonly("n_vertices", [](const MeshHandle& h) { return h.mesh().n_vertices(); })
      .def_property_readonly("n_faces", [](const MeshHandle& h) { return h.mesh().n_faces(); })
      .def_property_readonly("n_edges", [](const MeshHandle& h) { return h.mesh().n_edges(); })
      .def_property_readonly("n_halfedges", [](const MeshHandle& h) { return h.mesh().n_halfedges(); })
      .def_property_readonly("n_components", [](const MeshHandle& h) { return h.mesh().n_components(); })
      .def_property_readonly("n_unreferenced_vertices",
                             [](const MeshHandle& h) { return h.mesh().n_unreferenced_vertices(); })
      .def_property_readonly("euler_characteristic",
                             [](const MeshHandle& h) { return h.mesh().euler_characteristic(); })
      .def_property_readonly("edges", [](const MeshHandle& h) { return Eigen::MatrixX2i(h.mesh().edges()); })
      .def_property_readonly("boundary_loops",
                             [](const MeshHandle& h) {
                               py::list loops;
                               for (const auto& loop : h.mesh().boundary_loops()) loops.append(to_eigen(loop));
                               return loops;
                             })
      .def_property_readonly("boundary_vertices",
                             [](const MeshHandle& h) {
                               const Mesh& mesh = h.mesh();
                               py::array_t<bool> b(mesh.n_vertices());
                               for (int v = 0; v < mesh.n_vertices(); ++v)
                                 b.mutable_data()[v] = mesh.is_boundary_vertex(v);
                               return b;
                             })
      .def_property_readonly("mean_edge_length", [](const MeshHandle& h) { return h.mesh().mean_edge_length(); })
      .def_property_readonly("bounding_box_diagonal",
                             [](const MeshHandle& h) { return h.mesh().bounding_box_diagonal(); })
      .def_property_readonly("coordinate_noise", [](const MeshHandle& h) { return h.mesh().precision().noise; })
      .def_property_readonly("planarity_tolerance",
                             [](const MeshHandle& h) { return h.mesh().precision().planarity_tolerance; });
}

}  // namespace polydec::python
