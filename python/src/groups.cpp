// python/src/groups.cpp — the named vertex sets a mesh file carries (gmsh physical groups,
// dec/io/mesh_groups.h), as polydec._polydec.read_mesh_groups.
#include "bindings.h"
#include "polydec/dec/io/mesh_groups.h"

namespace polydec::python {

void register_groups(py::module_& m) {
  m.def(
      "read_mesh_groups",
      [](const std::string& path) {
        MeshGroups g;
        {
          py::gil_scoped_release release;
          g = read_mesh_groups(path);
        }
        py::dict vertices, elements, skipped;
        for (const auto& [name, list] : g.vertices)
          vertices[py::str(name)] = py::array_t<int>(long(list.size()), list.data());
        for (const auto& [name, list] : g.elements)
          elements[py::str(name)] = py::array_t<int>(long(list.size()), list.data());
        for (const auto& [kind, n] : g.skipped) skipped[py::str(kind)] = n;
        return py::make_tuple(vertices, elements, skipped);
      },
      py::arg("path"));
}

}  // namespace polydec::python
