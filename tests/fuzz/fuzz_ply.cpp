// libFuzzer target: the PLY reader (bytes named fuzz.ply), see fuzz_mesh.h.
#include "fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return occlude::fuzz::FuzzMesh(data, size, "fuzz.ply");
}
