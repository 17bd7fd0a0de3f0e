// python/src/quadratic.cpp — binding of the quadratic polygon Laplacian (operators/surface/quadratic.h):
// S, M, the HRZ-lumped M and the dof positions on the vertices and edge midpoints.
#include "polydec/operators/surface/quadratic.h"

#include "bindings.h"

namespace polydec::python {

void register_quadratic(py::module_& m) {
  m.def("quadratic_operators", [](const MeshHandle& h) {
    const Mesh& mesh = h.mesh();
    QuadraticLaplacian Q;
    {
      py::gil_scoped_release release;
      Q = quadratic_laplacian(mesh);
    }
    return py::make_tuple(Q.S, Q.M, Q.M_lumped, Q.dofs);
  });
}

}  // namespace polydec::python
