// fuzz/fuzz_vtu.cpp — libFuzzer target: arbitrary bytes through the VTK XML (.vtu) readers: the volume
// reader with validation and the OVM/VTK round trips (fuzz/fuzz_volume.h), the surface reader
// (fuzz/fuzz_common.h), the point and cell data reader, and a mesh read back from its own .vtu.
#include "fuzz/fuzz_common.h"
#include "fuzz/fuzz_volume.h"
#include "polydec/dec/io/vtu.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  polydec::fuzz_volume::check_volume_reader(data, size, "vtu");
  polydec::fuzz::check_reader(data, size, "vtu");
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const polydec::VtuFields f = polydec::read_vtu_fields_from_memory(bytes, "fuzz");
    polydec::fuzz::require(f.point_scalars.size() + f.point_vectors.size() + f.cell_scalars.size() <= size,
                           "no more arrays than bytes");
  } catch (const polydec::FileError& e) {
    polydec::fuzz::require(e.file == "fuzz" && !e.reason.empty(), "FileError names the file, with a reason");
  }
  try {
    const polydec::VolumeMesh m = polydec::read_volume_mesh_from_memory(bytes, "vtu", "fuzz");
    const polydec::VolumeMesh r =
        polydec::read_volume_mesh_from_memory(polydec::write_vtu_to_string(m), "vtu", "round trip");
    polydec::fuzz::require(
        r.positions() == m.positions() && r.n_cells() == m.n_cells() && r.n_faces() == m.n_faces(),
        ".vtu round trip keeps positions, cells and faces");
  } catch (const polydec::FileError&) {
  } catch (const polydec::InvalidMeshError&) {
  }
  return 0;
}
