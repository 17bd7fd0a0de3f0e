// fuzz/fuzz_common.h — shared by the libFuzzer targets: the reader contract every fuzzed input
// must satisfy. A reader either throws FileError (anything else escaping is a bug: libFuzzer
// reports the uncaught exception as a crash) or returns a soup whose offsets are consistent and
// whose indices are in range; that soup is then handed to validation, which may only throw
// InvalidMeshError.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "polydec/dec/io/mesh_io.h"

namespace polydec::fuzz {

inline void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "contract violated: %s\n", what);
    std::abort();
  }
}

inline void check_reader(const uint8_t* data, size_t size, const char* format) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  PolygonSoup s;
  try {
    s = read_polygon_soup_from_memory(bytes, format, "fuzz");
  } catch (const FileError& e) {
    require(e.file == "fuzz", "FileError names the file");
    require(!e.reason.empty(), "FileError has a reason");
    require(e.line >= 0 && e.byte_offset >= -1 && e.byte_offset <= long(size), "FileError position in range");
    return;
  }
  require(s.face_offsets.size() >= 1 && s.face_offsets.front() == 0, "offsets start at 0");
  require(s.face_offsets.back() == int(s.face_indices.size()), "offsets end at the index count");
  for (size_t f = 0; f + 1 < s.face_offsets.size(); ++f)
    require(s.face_offsets[f] <= s.face_offsets[f + 1], "offsets non-decreasing");
  for (int i : s.face_indices) require(i >= 0 && i < s.n_vertices(), "indices in range");
  try {
    const Mesh m(std::move(s));
    require(m.n_vertices() >= 0, "mesh");
  } catch (const InvalidMeshError&) {
  }
}

}  // namespace polydec::fuzz
