// The shared data folder of the measuring programs in bench/: $OCCLUDE_DATA_DIR when set, else
// the folder beside the repository (../shared/data, fixed at configure time).
#pragma once

#include <filesystem>
#include <string>

namespace occlude::bench {

/// The data folder (it may not exist: callers skip or explain).
std::filesystem::path DataDir();

/// DataDir()/cases/<name>: a case folder of the shared data.
std::filesystem::path SharedCaseDir(const std::string& name);

}  // namespace occlude::bench
