// libFuzzer target: the STL reader (bytes named fuzz.stl), see fuzz_mesh.h.
#include "fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return occlude::fuzz::FuzzMesh(data, size, "fuzz.stl");
}
