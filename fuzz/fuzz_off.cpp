// fuzz/fuzz_off.cpp — libFuzzer target: arbitrary bytes through the OFF reader and validation.
#include "fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  polydec::fuzz::check_reader(data, size, "off");
  return 0;
}
