// fuzz/fuzz_virtual_positions.cpp — libFuzzer target: the first byte is the face count, the rest a
// virtual-positions file; the reader either throws FileError or returns that many finite rows.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "polydec/dec/io/mesh_io.h"
#include "polydec/dec/io/virtual_positions.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const int n_faces = data[0];
  try {
    const Eigen::MatrixX3d X = polydec::read_virtual_positions_from_memory(
        std::string_view(reinterpret_cast<const char*>(data + 1), size - 1), n_faces, "fuzz");
    if (X.rows() != n_faces || !X.allFinite()) std::abort();
  } catch (const polydec::FileError& e) {
    if (e.file != "fuzz" || e.reason.empty()) std::abort();
  }
  return 0;
}
