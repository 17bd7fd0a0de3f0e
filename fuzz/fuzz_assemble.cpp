// fuzz/fuzz_assemble.cpp — libFuzzer target "validate then assemble": the bytes are read as a
// small OBJ; when validation accepts the mesh, the refinement and every operator (S, M, lumped
// M, G, D, P) are built and must be free of NaN and Inf (abort otherwise).
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/surface/prolongation.h"
#include "polydec/dec/surface/refinement.h"
#include "polydec/operators/surface/gradient.h"
#include "polydec/operators/surface/laplacian.h"

namespace {

void require_finite(const Eigen::SparseMatrix<double>& A, const char* name) {
  for (int k = 0; k < A.nonZeros(); ++k)
    if (!std::isfinite(A.valuePtr()[k])) {
      std::fprintf(stderr, "non-finite entry in %s\n", name);
      std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace polydec;
  if (size > 4096) return 0;  // small meshes only: the operators are what is exercised
  Mesh mesh;
  try {
    mesh =
        read_mesh_from_memory(std::string_view(reinterpret_cast<const char*>(data), size), "obj", "fuzz.obj");
  } catch (const FileError&) {
    return 0;
  }
  const Refinement r = refine(mesh);
  const Laplacian L = assemble_laplacian(mesh, r);
  require_finite(L.S, "S");
  require_finite(L.M, "M");
  if (!L.M_lumped.allFinite()) {
    std::fprintf(stderr, "non-finite lumped mass\n");
    std::abort();
  }
  require_finite(gradient(mesh, r), "G");
  require_finite(divergence(mesh, r), "D");
  require_finite(prolongation(mesh, r), "P");
  return 0;
}
