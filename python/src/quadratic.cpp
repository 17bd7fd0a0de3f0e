// python/src/quadratic.cpp — binding of the quadratic polygon Laplacian (operators/surface/quadratic.h):
// S, M, the HRZ-lumped M and the dof positions on the vertices and edge midpoints.
#include "polydec/operators/surface/quadratic.h"

#include "bindings.h"

namespace polydec::python {

void register_quadratic(py::module_& m) {
  m.def("quadratic_operators", [](const MeshHandle& h) {
    const Mesh& mesh = h.mesh();
    QuadraticLaplacian Q = without_gil([&] { return quadratic_laplacian(mesh); });
    return py::make_tuple(to_scipy(Q.S), to_scipy(Q.M), to_numpy(Q.M_lumped), Q.dofs);
  });
}

}  // namespace polydec::python
