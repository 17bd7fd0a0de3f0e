// python/src/bindings.h — shared pieces of the extension polydec._polydec: meshes passed as
// (positions, indices, offsets) arrays already checked and converted by the Python package
// (python/polydec/_convert.py), and the registration functions of the binding files.
// Every binding copies its inputs into C++ objects while holding the GIL, then releases it
// (py::gil_scoped_release) for validation, assembly, factorization and solves.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "polydec/dec/mesh.h"

namespace polydec::python {

namespace py = pybind11;

// Row-major |V| x 3 float64 positions and int32 flat faces, as numpy passes them.
using PositionArray = py::array_t<double, py::array::c_style>;
using IndexArray = py::array_t<int, py::array::c_style>;

// The polygon soup of the arrays (copied; needs the GIL). Throws std::invalid_argument for a
// wrong shape; index ranges and the rest are validated by Mesh.
PolygonSoup soup_from_arrays(const PositionArray& V, const IndexArray& indices, const IndexArray& offsets);

// Copies the arrays, then validates the mesh with the GIL released (InvalidMeshError).
Mesh mesh_from_arrays(const PositionArray& V, const IndexArray& indices, const IndexArray& offsets);

// (positions |V| x 3, indices, offsets) of a mesh, as numpy arrays.
py::tuple mesh_to_arrays(const Mesh& mesh);

void register_meshes(py::module_& m);
void register_operators(py::module_& m);
void register_solvers(py::module_& m);
void register_spectral(py::module_& m);
void register_volumes(py::module_& m);

}  // namespace polydec::python
