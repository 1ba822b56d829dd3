// The output folder of a command that works on a case config: `--out` when given, else the
// config's `[output] folder`, created and checked before any work starts.
#pragma once

#include <filesystem>
#include <string>

#include "config/case_config.h"

namespace occlude::app {

/// The output folder of a command: --out when given, else the config's [output] folder;
/// UserError naming the config file when neither is set.
std::filesystem::path OutputFolder(const CaseConfig& config, const std::string& out_option);

/// Creates OutputFolder(config, out_option) and returns it; when the folder came from the
/// config, an error names the config's key ("CASE.toml: output.folder: ...").
std::filesystem::path PrepareCaseOutput(const CaseConfig& config, const std::string& out_option);

}  // namespace occlude::app
