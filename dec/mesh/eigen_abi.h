// dec/mesh/eigen_abi.h — Eigen as polydec's interfaces pass it. A matrix allocated on one side of
// the library's boundary is freed on the other, so both sides must allocate alike. By default
// Eigen's heap follows the vector instructions a file is compiled for: glibc's malloc for x86-64,
// its own aligned malloc (which frees differently) with -mavx or -mavx512f, so a program built with
// -march=native against a library built without would crash in free(). polydec and its users
// therefore compile with -DEIGEN_MAX_ALIGN_BYTES=16 -DEIGEN_MALLOC_ALREADY_ALIGNED=0 (Eigen's own
// allocator everywhere, 16-byte alignment assumed): polydec's CMake package and pkg-config files
// add both, and this header refuses to compile without them.
#pragma once

#include <Eigen/Core>

static_assert(EIGEN_MAX_ALIGN_BYTES == 16 && EIGEN_MALLOC_ALREADY_ALIGNED == 0,
              "polydec: compile with -DEIGEN_MAX_ALIGN_BYTES=16 -DEIGEN_MALLOC_ALREADY_ALIGNED=0 (polydec's CMake "
              "package and pkg-config files add them): Eigen objects cross polydec's interfaces, and both sides must "
              "allocate them alike");
