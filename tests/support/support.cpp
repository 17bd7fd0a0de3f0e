// tests/support/support.cpp — the configure-time paths of tests/support/support.h (compile definitions of this file
// only, CMakeLists.txt).
#include "tests/support/support.h"

namespace polydec::test {

const char* shared_data_dir() { return POLYDEC_SHARED_DATA_DIR; }
const char* test_data_dir() { return POLYDEC_TEST_DATA_DIR; }
const char* cli_path() { return POLYDEC_CLI_PROGRAM; }

}  // namespace polydec::test
