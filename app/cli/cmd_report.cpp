// `occlude report CASE.toml [--pose FILE] [--out DIR] [--landmarks FILE]`: evaluates one pose
// of a case (the config's start pose, or a pose file) and writes what a surgeon attaches to a plan:
// report.html (self-contained), the contact maps and views as PNG, metrics.json, pose.json
// and the upper jaw at the pose as STL (report_writer.h: nothing half-written).
#include <iostream>
#include <memory>

#include "base/output_files.h"
#include "base/timing.h"
#include "cli/cache_options.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "config/case_config.h"
#include "config/case_output.h"
#include "config/pose_file.h"
#include "report/report_analysis.h"
#include "report/report_writer.h"
#include "session/case_session.h"
#include "session/memory_guard.h"

namespace occlude::app {
namespace {

struct ReportArgs {
  std::string config;
  std::string pose;
  std::string out;
  std::string landmarks;
  double memory_budget_mb = 0;
  CacheArgs cache;
};

void RunReport(const ReportArgs& args) {
  const double start = NowSeconds();
  const CaseConfig config = LoadCaseConfigWithOptions(args.config, args.landmarks, args.cache);
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
  AddLandmarksOption(cmd, &args->landmarks);
  AddCacheOptions(cmd, &args->cache);
  cmd->callback([args] { RunReport(*args); });
}

}  // namespace occlude::app
