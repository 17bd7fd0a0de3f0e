// fuzz/fuzz_medit.cpp — libFuzzer target: arbitrary bytes through the MEDIT .mesh reader, validation
// and the OVM/VTK/MEDIT round trips, and its references as groups (fuzz/fuzz_volume.h).
#include "fuzz/fuzz_volume.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  polydec::fuzz_volume::check_volume_reader(data, size, "mesh");
  polydec::fuzz_volume::check_medit_groups(data, size, false);
  return 0;
}
