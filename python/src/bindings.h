// python/src/bindings.h — shared pieces of the extension polydec._polydec: surface meshes passed as
// MeshHandle (validated once, built from arrays already checked and converted by the Python
// package, python/polydec/_convert.py), and the registration functions of the binding files.
// Every binding copies its inputs into C++ objects while holding the GIL, then releases it
// (py::gil_scoped_release) for validation, assembly, factorization and solves.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include "polydec/apps/applications/spectrum.h"
#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec::python {

namespace py = pybind11;

// Row-major |V| x 3 float64 positions and int32 flat faces, as numpy passes them.
using PositionArray = py::array_t<double, py::array::c_style>;
using IndexArray = py::array_t<int, py::array::c_style>;

// The |V| x 3 positions of a row-major array (copied; needs the GIL); std::invalid_argument for
// another shape.
Eigen::MatrixX3d positions_from_array(const PositionArray& V);

// The polygon soup of the arrays (copied; needs the GIL). Throws std::invalid_argument for a
// wrong shape; index ranges and the rest are validated by Mesh.
PolygonSoup soup_from_arrays(const PositionArray& V, const IndexArray& indices, const IndexArray& offsets);

// A validated surface mesh as the Python class polydec.Mesh holds it: validated once, its
// refinements built on first use per (virtual-vertex rule, planarity) and kept. The planarity
// argument everywhere: < 0 the mesh's own coordinate precision (a read file's digits), 0 the
// doubles taken as exact, > 0 a fixed tolerance (RefinementOptions::planarity_tolerance, the
// command line's --planarity-tolerance). Thread-safe (the bindings release the GIL).
class MeshHandle {
 public:
  explicit MeshHandle(Mesh mesh) : mesh_(std::move(mesh)) {}
  const Mesh& mesh() const { return mesh_; }
  // The mesh with the planarity rule applied to its coordinate precision (for the functions that
  // refine internally).
  Mesh with_planarity(double planarity) const;
  // The refinement for (rule, planarity), built on the first call (with `threads`) and cached.
  std::shared_ptr<const Refinement> refinement(VirtualVertexRule rule, double planarity, int threads = 1) const;
  // Number of cached refinements.
  int n_cached() const;
  // Forgets the cached refinements (for timing a first call again).
  void clear_refinements() const;

 private:
  Mesh mesh_;
  mutable std::mutex mutex_;
  mutable std::map<std::tuple<int, double>, std::shared_ptr<const Refinement>> refinements_;
};

// (positions |V| x 3, indices, offsets) of a mesh, as numpy arrays.
py::tuple mesh_to_arrays(const Mesh& mesh);

// A scipy.sparse.csc_matrix that takes over A's arrays without copying them (numpy views owned by
// a capsule holding the matrix): no second allocation of the values and indices, so no fresh pages
// to fault in per call. A is left empty.
py::object to_scipy(Eigen::SparseMatrix<double>& A);

// A numpy vector that takes over v's storage without copying (v is left empty).
py::array_t<double> to_numpy(Eigen::VectorXd& v);

// f() run with the GIL released, its result returned as f made it: declared as
// `T x = without_gil(...)`, the result is never copied. Assigning it to an object declared before
// the released block would be: Eigen 3.4's SparseMatrix has no move assignment, so every
// struct holding one deep-copies its matrices there (fresh pages to fault in on every call).
template <class F>
auto without_gil(F&& f) {
  py::gil_scoped_release release;
  return std::forward<F>(f)();
}

// (eigenvalues, eigenvectors, info dict with shift, n_converged, n_solves, method) of a spectrum,
// as `spectrum` and `volume_spectrum` return it.
py::tuple spectrum_to_python(const Spectrum& s);

// solve(options) (a Spectrum) with the GIL released, the options set from the arguments, as
// spectrum_to_python.
template <class Solve>
py::tuple spectrum_released(int k, bool lumped_mass, double tolerance, int max_iterations, Solve&& solve) {
  Spectrum s;
  {
    py::gil_scoped_release release;
    SpectrumOptions options;
    options.k = k;
    options.lumped_mass = lumped_mass;
    options.tolerance = tolerance;
    options.max_iterations = max_iterations;
    s = solve(options);
  }
  return spectrum_to_python(s);
}

// h.decompose(omega) with the GIL released, as a dict (HodgeDecomposer and VolumeHodgeDecomposer:
// parts with the same fields).
template <class Decomposer>
py::dict decompose_to_dict(const Decomposer& h, const Eigen::VectorXd& omega) {
  decltype(h.decompose(omega)) p;
  {
    py::gil_scoped_release release;
    p = h.decompose(omega);
  }
  py::dict d;
  d["exact"] = p.exact;
  d["coexact"] = p.coexact;
  d["harmonic"] = p.harmonic;
  d["potential"] = p.potential;
  d["norm"] = p.norm;
  d["norm_exact"] = p.norm_exact;
  d["norm_coexact"] = p.norm_coexact;
  d["norm_harmonic"] = p.norm_harmonic;
  return d;
}

void register_mesh_handle(py::module_& m);
void register_meshes(py::module_& m);
void register_operators(py::module_& m);
void register_solvers(py::module_& m);
void register_spectral(py::module_& m);
void register_volumes(py::module_& m);
void register_groups(py::module_& m);
void register_virtual_lift(py::module_& m);
void register_quadratic(py::module_& m);

}  // namespace polydec::python
