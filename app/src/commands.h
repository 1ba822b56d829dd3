// The subcommands of `occlude`. Each Add*Command registers its options on the
// CLI11 app and a callback that does the work; errors are thrown as
// occlude::app::UserError (one line, non-zero exit).
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "user_error.h"

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

struct CaseConfig;
/// The output folder of a command: --out when given, else the config's [output] folder;
/// UserError naming the config file when neither is set.
std::filesystem::path OutputFolder(const CaseConfig& config, const std::string& out_option);
/// Creates OutputFolder(config, out_option) and returns it; when the folder came from the
/// config, an error names the config's key ("CASE.toml: output.folder: ...").
std::filesystem::path PrepareCaseOutput(const CaseConfig& config, const std::string& out_option);
/// `occlude propose` on a loaded config (what `propose` and `demo` run): searches, writes the
/// K proposals and the report of the best to OutputFolder(config, out_option), prints them;
/// returns the best pose X_LU.
Eigen::Isometry3d ProposeAndReport(const CaseConfig& config, const std::string& out_option,
                                   double memory_budget_mb);

void AddSynthCommand(CLI::App& app);
void AddDemoCommand(CLI::App& app);
void AddCollideCommand(CLI::App& app);
void AddReportCommand(CLI::App& app);
void AddBenchCommand(CLI::App& app);
void AddValidateCommand(CLI::App& app);
void AddProposeCommand(CLI::App& app);
void AddRefineCommand(CLI::App& app);

}  // namespace occlude::app
