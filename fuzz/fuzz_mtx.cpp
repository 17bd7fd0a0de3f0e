// fuzz/fuzz_mtx.cpp — libFuzzer target: arbitrary bytes through the Matrix Market reader; it
// either throws FileError or returns a matrix whose entries lie inside its declared size.
#include <cstdint>
#include <cstdlib>

#include "polydec/dec/io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const auto A = polydec::read_matrix_market_from_memory(
        std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
    for (int j = 0; j < A.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
        if (it.row() < 0 || it.row() >= A.rows()) std::abort();
  } catch (const polydec::FileError&) {
  }
  return 0;
}
