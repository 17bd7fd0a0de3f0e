// fuzz/fuzz_ply.cpp — libFuzzer target: arbitrary bytes through the PLY reader and validation.
#include "fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  polydec::fuzz::check_reader(data, size, "ply");
  return 0;
}
