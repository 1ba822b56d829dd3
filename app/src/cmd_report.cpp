// `occlude report CASE.toml [--pose FILE] [--out DIR]`: evaluates one pose of a case (the
// config's start pose, or a pose file) and writes what a surgeon attaches to a plan:
// report.html (self-contained), the contact maps and views as PNG, metrics.json, pose.json
// and the upper jaw at the pose as STL (report_writer.h: nothing half-written).
#include <iostream>
#include <memory>

#include "case_config.h"
#include "case_session.h"
#include "commands.h"
#include "memory_guard.h"
#include "output_files.h"
#include "pose_file.h"
#include "report_analysis.h"
#include "report_writer.h"
#include "timing.h"

namespace occlude::app {
namespace {

struct ReportArgs {
  std::string config;
  std::string pose;
  std::string out;
  double memory_budget_mb = 0;
};

void RunReport(const ReportArgs& args) {
  const double start = NowSeconds();
  const CaseConfig config = LoadCaseConfig(args.config);
  // (A flag and a matrix rather than std::optional: GCC 12 warns falsely about the
  // optional's aligned Eigen payload being used uninitialized.)
  const bool pose_file = !args.pose.empty();
  const Eigen::Isometry3d X_LU_file =
      pose_file ? ReadPoseFile(args.pose) : Eigen::Isometry3d::Identity();
  const std::filesystem::path out = PrepareCaseOutput(config, args.out);
  CaseSession session(config, args.memory_budget_mb);
  const Eigen::Isometry3d X_LU = pose_file ? X_LU_file : session.ConfigStartPose();
  ReportAnalysis analysis = AnalyzePose(session, X_LU);
  const std::string source =
      pose_file ? "pose file " + std::filesystem::absolute(args.pose).lexically_normal().string()
                : "start pose of the config";
  StepClock clock;
  clock.Start("rendered the maps and views");
  const ReportFiles files = MakeReportFiles(session, analysis, source);
  clock.Finish();
  WriteReportFiles(out, files);
  const auto& o = analysis.oracle;
  std::cout << config.name << ": contact " << o.contact_area_mm2 << " mm^2 in "
            << analysis.spots.size() << " spots (band " << config.contact_band_mm
            << " mm), maximum penetration " << o.max_penetration_mm << " mm"
            << (o.max_penetration_mm <= config.max_penetration_mm ? ""
                                                                  : " (over the allowed maximum)")
            << "; report in " << (out / "report.html").string() << " (" << NowSeconds() - start
            << " s)\n";
}

}  // namespace

std::filesystem::path OutputFolder(const CaseConfig& config, const std::string& out_option) {
  if (!out_option.empty()) return out_option;
  if (config.output_dir) return *config.output_dir;
  throw UserError(config.file.string() +
                  ": no output folder; set [output] folder = \"...\" or pass --out");
}

std::filesystem::path PrepareCaseOutput(const CaseConfig& config, const std::string& out_option) {
  const std::filesystem::path out = OutputFolder(config, out_option);
  try {
    PrepareOutputDir(out);
  } catch (const UserError& e) {
    if (!out_option.empty()) throw;
    throw UserError(config.file.string() + ": output.folder: " + e.what());
  }
  return out;
}

void AddReportCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "report",
      "Evaluate one pose of a case and write report.html, contact maps, metrics.json, "
      "pose.json and the upper jaw at the pose");
  auto args = std::make_shared<ReportArgs>();
  cmd->add_option("config", args->config, "Case config file (TOML; see examples/)")->required();
  cmd->add_option("--pose", args->pose,
                  "Pose file (JSON with a 4x4 \"X_LU\"); default: the config's start pose");
  cmd->add_option("--out", args->out, "Output folder; default: [output] folder of the config");
  AddMemoryBudgetOption(cmd, &args->memory_budget_mb);
  cmd->callback([args] { RunReport(*args); });
}

}  // namespace occlude::app
