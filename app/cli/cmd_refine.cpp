// `occlude refine CASE.toml [--out DIR] [--from-config] [--watch]`: interactive refinement.
// Starts from the last result in the output folder (pose.json written by propose or refine)
// or, without one or with --from-config, from the config's [start] pose; applies the
// [adjust] deltas (mm, degrees about the pivot at that pose); re-optimizes locally on the
// finest oracle with the config's locked degrees of freedom, bounds, band and penetration
// limit; writes the result, the report and refine.json; and prints what changed.
// --watch keeps the trees and repeats on every save of the config file, always from the same
// base pose (the one at launch), so editing [adjust] moves the result predictably.
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "base/json_values.h"
#include "base/output_files.h"
#include "base/timing.h"
#include "base/user_error.h"
#include "cli/cache_options.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "config/case_output.h"
#include "config/plan_config.h"
#include "config/pose_file.h"
#include "report/report_analysis.h"
#include "report/report_writer.h"
#include "report/search_document.h"
#include "session/case_session.h"
#include "session/memory_guard.h"

namespace occlude::app {
namespace {

using nlohmann::json;

struct RefineArgs {
  std::string config;
  std::string out;
  bool from_config = false;
  bool watch = false;
  int max_refinements = 0;  ///< --watch: stop after this many (0 = until interrupted)
  double poll_seconds = 0.2;
  double memory_budget_mb = 0;
  CacheArgs cache;
};

json Metrics(const planner::PoseEvaluation& e) {
  return {{"contact_area_mm2", e.contact_area_mm2},
          {"contact_samples", e.contact_samples},
          {"max_penetration_mm", e.max_penetration_mm},
          {"constrained_penetration_mm", e.constrained_penetration_mm},
          {"feasible", e.feasible}};
}

std::string Triple(const Eigen::Vector3d& v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << "(" << v.x() << ", " << v.y() << ", " << v.z()
    << ")";
  return s.str();
}

// One refinement from `base`; writes the outputs and prints the changes.
void RefineOnce(CaseSession& session, const Eigen::Isometry3d& base, const std::string& base_source,
                const std::filesystem::path& out) {
  const double start = NowSeconds(), cpu_start = ThreadCpuSeconds();
  const CaseConfig& config = session.config();
  const Eigen::Isometry3d X_adjusted =
      planner::ComposePose(config.adjust, base * session.pivot_L(), base);
  planner::PlanRequest request = PlanRequestFromConfig(config, X_adjusted, session.pivot_L());
  request.solver = config.solver.name == "nlopt-local" ? planner::SolverKind::kNloptLocal
                                                       : planner::SolverKind::kCeres;
  request.num_starts = 1;
  request.max_proposals = 1;
  request.num_threads = 1;
  // Locally, the finest oracle alone (built on first use, kept by --watch).
  const planner::OracleSchedule finest = {
      {&session.FinestOracle(), collision::AccuracyLevel::kSubVoxel}};
  const planner::PoseEvaluation before = planner::EvaluatePose(finest.front(), base, request);
  const planner::PoseEvaluation adjusted =
      planner::EvaluatePose(finest.front(), X_adjusted, request);
  const planner::PlanResult result = planner::Plan(finest, request);
  const planner::Proposal& after = result.proposals.front();
  const planner::PoseParameters moved =
      planner::DecomposePose(after.X_LU, base * session.pivot_L(), base);
  const planner::PoseParameters absolute =
      planner::DecomposePose(after.X_LU, session.pivot_L(), Eigen::Isometry3d::Identity());

  SearchSummary summary{"refine", base_source + " + [adjust]", &result, session.pivot_L(),
                        session.jaws().upper_U.get()};
  ReportAnalysis analysis = AnalyzePose(session, after.X_LU);
  const ReportFiles files =
      MakeReportFiles(session, analysis, "`occlude refine` from " + base_source,
                      SearchJson(summary, false), SearchHtml(summary));
  const json refine = {
      {"base", {{"source", base_source}, {"X_LU", json::parse(MatrixJson(base.matrix()))}}},
      {"adjust",
       {{"translation_mm", Vec(config.adjust.translation_mm)},
        {"rotation_deg", Vec(config.adjust.rotation_deg)}}},
      {"result",
       {{"X_LU", json::parse(MatrixJson(after.X_LU.matrix()))},
        {"translation_mm", Vec(absolute.translation_mm)},
        {"rotation_deg", Vec(absolute.rotation_deg)},
        {"status", planner::ToString(after.status)}}},
      {"moved_from_base",
       {{"translation_mm", Vec(moved.translation_mm)}, {"rotation_deg", Vec(moved.rotation_deg)}}},
      {"before", Metrics(before)},
      {"adjusted", Metrics(adjusted)},
      {"after", Metrics(after.evaluation)},
      {"convention",
       "moved_from_base: about the pivot at the base pose; result: about the pivot, relative to "
       "the "
       "pose as given"}};
  WriteReportFiles(out, files, {{"refine.json", refine.dump(2) + "\n"}});

  std::cout << std::fixed << std::setprecision(3) << config.name << ": refined from " << base_source
            << " + adjust t " << Triple(config.adjust.translation_mm, 3) << " mm r "
            << Triple(config.adjust.rotation_deg, 2) << " deg\n"
            << "  moved t " << Triple(moved.translation_mm, 3) << " mm r "
            << Triple(moved.rotation_deg, 2) << " deg from the base ("
            << planner::ToString(after.status) << ")\n"
            << "  contact " << std::setprecision(2) << before.contact_area_mm2 << " -> "
            << after.evaluation.contact_area_mm2 << " mm^2, max penetration "
            << std::setprecision(3) << before.max_penetration_mm << " -> "
            << after.evaluation.max_penetration_mm << " mm (constrained "
            << after.evaluation.constrained_penetration_mm << ", limit "
            << config.max_penetration_mm << ")\n"
            << "  report in " << (out / "report.html").string() << " (" << std::setprecision(2)
            << NowSeconds() - start << " s wall, " << ThreadCpuSeconds() - cpu_start
            << " s CPU of this thread)\n"
            << std::flush;
}

std::filesystem::file_time_type ModifiedAt(const std::filesystem::path& file) {
  std::error_code ec;
  const auto t = std::filesystem::last_write_time(file, ec);
  return ec ? std::filesystem::file_time_type::min() : t;
}

void RunRefine(const RefineArgs& args) {
  const CaseConfig config = WithCacheArgs(LoadCaseConfig(args.config), args.cache);
  PlanRequestFromConfig(config, Eigen::Isometry3d::Identity(),
                        Eigen::Vector3d::Zero());  // settings first
  const std::filesystem::path out = PrepareCaseOutput(config, args.out);
  auto session = std::make_unique<CaseSession>(config, args.memory_budget_mb);
  Eigen::Isometry3d base = session->ConfigStartPose();
  std::string source = "the config's [start] pose";
  const std::filesystem::path last = out / "pose.json";
  if (!args.from_config && std::filesystem::exists(last)) {
    base = ReadPoseFile(last);
    source = "the last result (" + last.string() + ")";
  }
  RefineOnce(*session, base, source, out);
  if (!args.watch) return;
  std::cerr << "occlude: watching " << config.file.string()
            << " (Ctrl-C to stop); every save refines from " << source << "\n";
  auto seen = ModifiedAt(config.file);
  for (int done = 1; args.max_refinements == 0 || done < args.max_refinements;) {
    std::this_thread::sleep_for(std::chrono::duration<double>(args.poll_seconds));
    const auto now = ModifiedAt(config.file);
    if (now == seen) continue;
    seen = now;
    ++done;
    try {
      const CaseConfig updated = WithCacheArgs(LoadCaseConfig(config.file), args.cache);
      if (session->Reusable(updated)) {
        session->UpdateSettings(updated);
      } else {
        std::cerr << "occlude: meshes or accuracy changed: rebuilding the models\n";
        session = std::make_unique<CaseSession>(updated, args.memory_budget_mb);
      }
      RefineOnce(*session, base, source, OutputFolder(updated, args.out));
    } catch (const UserError& e) {
      std::cerr << "occlude: error: " << e.what() << " (still watching)\n";
    }
  }
}

}  // namespace

void AddRefineCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "refine",
      "Apply the config's [adjust] to the last result, re-optimize locally, report what changed");
  auto args = std::make_shared<RefineArgs>();
  cmd->add_option("config", args->config, "Case config file (TOML; see examples/)")->required();
  cmd->add_option("--out", args->out, "Output folder; default: [output] folder of the config");
  AddMemoryBudgetOption(cmd, &args->memory_budget_mb);
  AddCacheOptions(cmd, &args->cache);
  cmd->add_flag("--from-config", args->from_config,
                "Start from the config's [start] pose, not the last result");
  cmd->add_flag("--watch", args->watch,
                "Keep the trees and refine again on every save of the config file");
  cmd->add_option("--max-refinements", args->max_refinements,
                  "With --watch: stop after this many (0 = never)")
      ->check(CLI::Range(0, 1000000))
      ->group("");  // for scripts and tests
  cmd->callback([args] { RunRefine(*args); });
}

}  // namespace occlude::app
