// Option checks shared by the subcommands: lengths in mm within a range (the message says what
// the option must be), `--memory-budget-mb` (session/memory_guard.h) and `--landmarks`.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "cli/cache_options.h"
#include "config/case_config.h"

namespace occlude::app {

/// Validator for a length in mm: a finite number in (lo, hi], or [lo, hi] when
/// `lo_inclusive`; the message says what the option must be.
inline CLI::Validator MmBetween(double lo, bool lo_inclusive, double hi, const std::string& what) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double v = std::stod(text, &used);
          if (used == text.size() && (lo_inclusive ? v >= lo : v > lo) && v <= hi) return "";
        } catch (const std::exception&) {
        }
        return "must be " + what + ", got '" + text + "'";
      },
      "MM");
}
/// A voxel size or other positive length.
inline CLI::Validator PositiveMm() { return MmBetween(0.0, false, 1e6, "a positive length in mm"); }
/// A contact band.
inline CLI::Validator BandMm() { return MmBetween(0.0, true, 5.0, "a band in mm between 0 and 5"); }

/// Adds `--landmarks FILE` (given landmarks, overriding the config's [landmarks] file) to `cmd`.
inline void AddLandmarksOption(CLI::App* cmd, std::string* file) {
  cmd->add_option("--landmarks", *file,
                  "Landmark file (CSV jaw,tooth,type,x_mm,y_mm,z_mm; each jaw in its mesh's "
                  "frame) overriding detected landmarks; default: the config's [landmarks] file");
}

/// `config` with --landmarks `file` (when given) as its landmarks_file.
inline CaseConfig WithLandmarksOption(CaseConfig config, const std::string& file) {
  if (!file.empty()) config.landmarks_file = std::filesystem::absolute(file).lexically_normal();
  return config;
}

/// The config `file` with the command line's --landmarks and cache options applied (the
/// commands that build oracles: propose, refine, report).
inline CaseConfig LoadCaseConfigWithOptions(const std::filesystem::path& file,
                                            const std::string& landmarks, const CacheArgs& cache) {
  return WithCacheArgs(WithLandmarksOption(LoadCaseConfig(file), landmarks), cache);
}

/// Adds `--memory-budget-mb MB` (a positive number; 0 = not given) to `cmd`.
inline void AddMemoryBudgetOption(CLI::App* cmd, double* budget_mb) {
  cmd->add_option("--memory-budget-mb", *budget_mb,
                  "Memory the trees and fields may take, MB (default: the config's "
                  "limits.memory_budget_mb, else a quarter of the physical memory)")
      ->check(MmBetween(0.0, false, 1e9, "a positive number of megabytes").description("MB"));
}

}  // namespace occlude::app
