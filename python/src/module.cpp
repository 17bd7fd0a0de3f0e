// python/src/module.cpp — the extension module polydec._polydec: the exception types
// (FileError is both OSError and ValueError; InvalidMeshError a ValueError naming the element;
// SolverError a RuntimeError), the array <-> mesh helpers, the allocator opt-in keep_freed_memory and
// the registration of the bindings.
#include <climits>

#include "bindings.h"
#include "polydec/dec/io/mesh_io.h"
#include "polydec/operators/solvers/cholesky.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace polydec::python {

Eigen::MatrixX3d positions_from_array(const PositionArray& V) {
  if (V.ndim() != 2 || V.shape(1) != 3)
    throw std::invalid_argument("positions must be an array of shape (|V|, 3)");
  Eigen::MatrixX3d X(long(V.shape(0)), 3);
  const double* v = V.data();
  for (long i = 0; i < X.rows(); ++i)
    for (int c = 0; c < 3; ++c) X(i, c) = v[3 * i + c];
  return X;
}

PolygonSoup soup_from_arrays(const PositionArray& V, const IndexArray& indices, const IndexArray& offsets) {
  if (indices.ndim() != 1 || offsets.ndim() != 1 || offsets.size() < 1)
    throw std::invalid_argument("faces must be flat 1-D indices and offsets (|F| + 1 entries)");
  PolygonSoup soup;
  soup.positions = positions_from_array(V);
  soup.face_indices.assign(indices.data(), indices.data() + indices.size());
  soup.face_offsets.assign(offsets.data(), offsets.data() + offsets.size());
  return soup;
}

py::tuple mesh_to_arrays(const Mesh& mesh) {
  const long n = mesh.n_vertices();
  py::array_t<double> V({n, 3L});
  double* v = V.mutable_data();
  for (long i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) v[3 * i + c] = mesh.positions()(i, c);
  const auto& I = mesh.face_indices();
  const auto& O = mesh.face_offsets();
  return py::make_tuple(V, py::array_t<int>(long(I.size()), I.data()),
                        py::array_t<int>(long(O.size()), O.data()));
}

py::object to_scipy(Eigen::SparseMatrix<double>& A) {
  A.makeCompressed();
  auto* owner = new Eigen::SparseMatrix<double>();
  owner->swap(A);
  py::capsule base(owner, [](void* p) { delete static_cast<Eigen::SparseMatrix<double>*>(p); });
  const long nnz = long(owner->nonZeros());
  py::array_t<double> data(nnz, owner->valuePtr(), base);
  py::array_t<int> indices(nnz, owner->innerIndexPtr(), base);
  py::array_t<int> indptr(long(owner->outerSize()) + 1, owner->outerIndexPtr(), base);
  static const py::object csc = py::module_::import("scipy.sparse").attr("csc_matrix");
  return csc(py::make_tuple(data, indices, indptr), py::arg("shape") = py::make_tuple(owner->rows(), owner->cols()),
             py::arg("copy") = false);
}

py::array_t<double> to_numpy(Eigen::VectorXd& v) {
  auto* owner = new Eigen::VectorXd();
  owner->swap(v);
  py::capsule base(owner, [](void* p) { delete static_cast<Eigen::VectorXd*>(p); });
  return py::array_t<double>(long(owner->size()), owner->data(), base);
}

namespace {

// New exception classes, alive as long as the interpreter (module-level objects).
PyObject* new_exception(py::module_& m, const char* name, PyObject* bases, const char* doc) {
  const std::string qualified = std::string("polydec.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases, nullptr);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

}  // namespace

}  // namespace polydec::python

PYBIND11_MODULE(_polydec, m) {
  namespace py = pybind11;
  using namespace polydec::python;
  m.doc() = "polydec's C++ core (use the package polydec, which converts inputs and documents the API)";

  py::tuple file_bases = py::make_tuple(py::handle(PyExc_OSError), py::handle(PyExc_ValueError));
  static PyObject* file_error = new_exception(
      m, "FileError", file_bases.ptr(),
      "A mesh or matrix file that cannot be read or written. An OSError and a ValueError; "
      "attributes filename, line (1-based, 0 when unknown), byte_offset (-1 when unknown), reason.");
  // str() is the message "FILE:LINE: REASON" (OSError's own would print "[Errno None] ..." once
  // filename is set).
  py::setattr(file_error, "__str__", py::module_::import("builtins").attr("BaseException").attr("__str__"));
  static PyObject* mesh_error = new_exception(
      m, "InvalidMeshError", PyExc_ValueError,
      "Arrays that are not a valid polygon mesh (a ValueError); attributes element ('face', 'vertex', "
      "'edge') and index.");
  static PyObject* solver_error = new_exception(
      m, "SolverError", PyExc_RuntimeError, "A factorization or eigen-solver that failed (a RuntimeError).");

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const polydec::FileError& e) {
      py::object err = py::reinterpret_borrow<py::object>(file_error)(e.what());
      err.attr("filename") = e.file;
      err.attr("line") = e.line;
      err.attr("byte_offset") = e.byte_offset;
      err.attr("reason") = e.reason;
      PyErr_SetObject(file_error, err.ptr());
    } catch (const polydec::InvalidMeshError& e) {
      py::object err = py::reinterpret_borrow<py::object>(mesh_error)(e.what());
      err.attr("element") = e.element;
      err.attr("index") = e.index;
      PyErr_SetObject(mesh_error, err.ptr());
    } catch (const polydec::SolverError& e) {
      PyErr_SetString(solver_error, e.what());
    }
  });

  // polydec.keep_freed_memory: glibc keeps up to max_bytes of freed memory at the top of its heap and
  // serves blocks up to 32 MB from the heap (process-wide, on the user's explicit request).
  m.def("keep_freed_memory", [](long long max_bytes) {
    if (max_bytes < 0) throw std::invalid_argument("max_bytes must be at least 0");
#if defined(__GLIBC__)
    const int trim = int(std::min<long long>(max_bytes, INT_MAX));
    return mallopt(M_MMAP_THRESHOLD, 32 << 20) == 1 && mallopt(M_TRIM_THRESHOLD, trim) == 1;
#else
    return false;
#endif
  });

  register_mesh_handle(m);
  register_meshes(m);
  register_operators(m);
  register_solvers(m);
  register_spectral(m);
  register_volumes(m);
  register_groups(m);
  register_virtual_lift(m);
  register_quadratic(m);
}
