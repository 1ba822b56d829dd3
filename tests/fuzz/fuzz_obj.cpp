// libFuzzer target: the OBJ reader (bytes named fuzz.obj), see fuzz_mesh.h.
#include "fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return occlude::fuzz::FuzzMesh(data, size, "fuzz.obj");
}
