// python/src/virtual_lift.cpp — binding of the paper's operator with lifted virtual vertices
// (dec/surface/virtual_lift.h, OperatorOptions::lift): S, M, lumped M and the virtual points.
#include "bindings.h"
#include "polydec/operators/registry/laplacians.h"

namespace polydec::python {

void register_virtual_lift(py::module_& m) {
  m.def("lifted_operators", [](const MeshHandle& h, const std::string& spec, const std::string& lift,
                               const py::object& positions) {
    const Mesh& mesh = h.mesh();
    OperatorOptions options;
    options.with_gradient = false;
    if (!positions.is_none()) {
      if (lift != "none") throw std::invalid_argument("give either lift or positions, not both");
      const auto P = py::cast<Eigen::MatrixXd>(positions);
      if (P.cols() != 3) throw std::invalid_argument("positions must be an array of shape (|F|, 3)");
      options.lift.kind = VirtualLiftKind::Positions;
      options.lift.positions = P;
    } else {
      options.lift = parse_virtual_lift(lift);
    }
    const LaplacianChoice choice = parse_laplacian(spec);
    Eigen::MatrixX3d points;
    OperatorSet ops = without_gil([&] {
      OperatorSet built = build_operators(mesh, choice, options);  // returned without a copy (NRVO)
      // The refinement the operators were built on, for its virtual points ("ours" and "refined": squared-area).
      RefinementOptions ro;
      ro.rule = parse_virtual_vertex_rule(choice.method == "ours" || choice.method == "refined" ? "squared-area"
                                                                                                 : choice.method);
      ro.lift = options.lift;
      points = refine(mesh, ro).virtual_points;
      return built;
    });
    py::dict d;
    d["name"] = ops.name;
    d["S"] = to_scipy(ops.S);
    d["M"] = to_scipy(ops.M);
    d["M_lumped"] = to_numpy(ops.M_lumped);
    d["virtual_points"] = Eigen::MatrixXd(points);
    return d;
  });
}

}  // namespace polydec::python
