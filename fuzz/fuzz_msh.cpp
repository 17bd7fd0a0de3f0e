// fuzz/fuzz_msh.cpp — libFuzzer target: arbitrary bytes through the gmsh .msh reader, as a volume
// (validation and the OVM/VTK round trips of fuzz/fuzz_volume.h) and as a surface (fuzz/fuzz_common.h).
#include "fuzz/fuzz_common.h"
#include "fuzz/fuzz_volume.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  polydec::fuzz_volume::check_volume_reader(data, size, "msh");
  polydec::fuzz::check_reader(data, size, "msh");
  return 0;
}
