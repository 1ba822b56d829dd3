// The shared data folder (see data_dir.h).
#include "data_dir.h"

#include <cstdlib>

namespace occlude::bench {

std::filesystem::path DataDir() {
  if (const char* env = std::getenv("OCCLUDE_DATA_DIR")) return env;
  return OCCLUDE_DEFAULT_DATA_DIR;
}

std::filesystem::path SharedCaseDir(const std::string& name) { return DataDir() / "cases" / name; }

}  // namespace occlude::bench
