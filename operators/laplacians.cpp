// operators/laplacians.cpp — the named Laplacian registry.
#include "operators/laplacians.h"

#include "operators/gradient.h"

#include <fmt/format.h>
#include <stdexcept>

namespace polydec {

std::string LaplacianChoice::canonical_name() const {
  return has_parameter ? fmt::format("{}:{:g}", method, parameter) : method;
}

std::vector<std::string> laplacian_names() { return {"ours", "centroid"}; }

LaplacianChoice parse_laplacian(const std::string& spec) {
  LaplacianChoice c;
  const auto colon = spec.find(':');
  c.method = spec.substr(0, colon);
  if (colon != std::string::npos) {
    try {
      size_t used = 0;
      c.parameter = std::stod(spec.substr(colon + 1), &used);
      if (used != spec.size() - colon - 1) throw std::invalid_argument("trailing characters");
    } catch (const std::exception&) {
      throw std::invalid_argument("bad parameter in Laplacian '" + spec + "'");
    }
    if (!std::isfinite(c.parameter)) throw std::invalid_argument("non-finite parameter in Laplacian '" + spec + "'");
    c.has_parameter = true;
  }
  const auto names = laplacian_names();
  if (std::find(names.begin(), names.end(), c.method) == names.end())
    throw std::invalid_argument(fmt::format("unknown Laplacian '{}' (known: {})", c.method, fmt::join(names, ", ")));
  return c;
}

namespace {

OperatorSet virtual_vertex_operators(const Mesh& mesh, VirtualVertexRule rule, bool with_gradient) {
  OperatorSet ops;
  ops.domain = mesh;
  ops.n_input_vertices = mesh.n_vertices();
  RefinementOptions ro;
  ro.rule = rule;
  const Refinement r = refine(mesh, ro);
  Laplacian L = assemble_laplacian(mesh, r);
  ops.S = std::move(L.S);
  ops.M = std::move(L.M);
  ops.M_lumped = std::move(L.M_lumped);
  ops.quality = r.quality;
  if (with_gradient) {
    ops.G = gradient(mesh, r);
    ops.D = divergence(mesh, r);
  }
  return ops;
}

}  // namespace

OperatorSet build_operators(const Mesh& mesh, const LaplacianChoice& choice, bool with_gradient) {
  OperatorSet ops;
  if (choice.method == "ours")
    ops = virtual_vertex_operators(mesh, VirtualVertexRule::SquaredArea, with_gradient);
  else if (choice.method == "centroid")
    ops = virtual_vertex_operators(mesh, VirtualVertexRule::Centroid, with_gradient);
  else
    throw std::invalid_argument("unknown Laplacian '" + choice.method + "'");
  ops.name = choice.canonical_name();
  return ops;
}

}  // namespace polydec
