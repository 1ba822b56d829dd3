// `--cache DIR` and `--no-cache` of the commands that build oracles or analyse arches (propose,
// refine, report, demo, analyze): where the cache of oracles and arch analyses lives
// (session/oracle_cache.h), or that it is not used.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <utility>

#include "config/case_config.h"

namespace occlude::app {

struct CacheArgs {
  std::string folder;  ///< --cache DIR; empty = the default folder
  bool off = false;    ///< --no-cache
};

/// Adds `--cache DIR` and `--no-cache` (exclusive) to `cmd`.
inline void AddCacheOptions(CLI::App* cmd, CacheArgs* args) {
  auto* folder = cmd->add_option("--cache", args->folder,
                                 "Folder of the cache of oracles and arch analyses (default: "
                                 "$XDG_CACHE_HOME/occlude, else ~/.cache/occlude)");
  cmd->add_flag("--no-cache", args->off,
                "Build every oracle and analysis; neither read nor write the cache")
      ->excludes(folder);
}

/// `config` with the cache settings of the command line.
inline CaseConfig WithCacheArgs(CaseConfig config, const CacheArgs& args) {
  config.cache_enabled = !args.off;
  config.cache_folder = args.folder;
  return config;
}

}  // namespace occlude::app
