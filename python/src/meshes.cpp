// python/src/meshes.cpp — bindings of reading, writing, generating and transforming meshes
// (dec/io/mesh_io.h, dec/mesh/generators.h). Meshes travel as (positions, indices, offsets).
#include "bindings.h"
#include "polydec/dec/mesh/generators.h"
#include "polydec/dec/io/mesh_io.h"

namespace polydec::python {
namespace {

// Runs a generator with the GIL released and returns the mesh as a polydec._polydec.Mesh.
template <class F>
std::shared_ptr<MeshHandle> generate(F&& make) {
  py::gil_scoped_release release;
  return std::make_shared<MeshHandle>(make());
}

}  // namespace

void register_meshes(py::module_& m) {
  m.def("read_mesh", [](const std::string& path) { return generate([&] { return read_mesh(path); }); });
  m.def("write_mesh",
        [](const std::string& path, const MeshHandle& h,
           const std::map<std::string, Eigen::VectorXd>& scalars, bool binary) {
          const Mesh& mesh = h.mesh();
          py::gil_scoped_release release;
          WriteOptions options;
          options.binary = binary;
          write_mesh(path, mesh, scalars, options);
        });
  m.def("validate", [](const MeshHandle& h) {
    const Mesh& mesh = h.mesh();
    py::dict d;
    d["vertices"] = mesh.n_vertices();
    d["faces"] = mesh.n_faces();
    d["edges"] = mesh.n_edges();
    d["halfedges"] = mesh.n_halfedges();
    d["boundary_loops"] = mesh.boundary_loops().size();
    d["components"] = mesh.n_components();
    d["unreferenced_vertices"] = mesh.n_unreferenced_vertices();
    d["euler_characteristic"] = mesh.euler_characteristic();
    d["edge_list"] = Eigen::MatrixX2i(mesh.edges());
    return d;
  });

  m.def("quad_grid", [](int nx, int ny) { return generate([&] { return quad_grid(nx, ny); }); });
  m.def("triangle_grid", [](int nx, int ny) { return generate([&] { return triangle_grid(nx, ny); }); });
  m.def("hex_grid", [](int nx, int ny) { return generate([&] { return hex_grid(nx, ny); }); });
  m.def("uv_sphere", [](int n_lat, int n_lon) { return generate([&] { return uv_sphere(n_lat, n_lon); }); });
  m.def("cube_sphere", [](int n) { return generate([&] { return cube_sphere(n); }); });
  m.def("hex_sphere", [](int level) { return generate([&] { return hex_sphere(level); }); });
  m.def("torus", [](int n_major, int n_minor, double R, double r) {
    return generate([&] { return torus(n_major, n_minor, R, r); });
  });
  m.def("genus2", [](int subdivisions) { return generate([&] { return genus2(subdivisions); }); });

  m.def("catmull_clark", [](const MeshHandle& h) {
    const Mesh& mesh = h.mesh();
    return generate([&] { return catmull_clark(mesh); });
  });
  m.def("dual", [](const MeshHandle& h) {
    const Mesh& mesh = h.mesh();
    return generate([&] { return dual(mesh); });
  });
  m.def("project_to_unit_sphere", [](const MeshHandle& h) {
    const Mesh& mesh = h.mesh();
    return generate([&] { return project_to_unit_sphere(mesh); });
  });
  m.def("add_noise", [](const MeshHandle& h, double amplitude,
                        std::uint64_t seed) {
    const Mesh& mesh = h.mesh();
    return generate([&] { return add_noise(mesh, amplitude, seed); });
  });
}

}  // namespace polydec::python
