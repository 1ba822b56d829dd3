// The automated occlusion proposal as files (see proposal_report.h).
#include "report/proposal_report.h"

#include <iomanip>
#include <iostream>

#include "base/output_files.h"
#include "base/progress.h"
#include "base/tasks.h"
#include "base/timing.h"
#include "base/user_error.h"
#include "config/case_output.h"
#include "config/plan_config.h"
#include "report/global_proposal_report.h"
#include "report/report_analysis.h"
#include "report/report_writer.h"
#include "report/search_document.h"
#include "session/case_session.h"

namespace occlude::app {

std::string ProposalPoseJson(const Eigen::Isometry3d& X_LU, int rank) {
  return "{\n  \"proposal\": " + std::to_string(rank) +
         ",\n  \"X_LU\": " + MatrixJson(X_LU.matrix()) + "\n}\n";
}

Eigen::Isometry3d ProposeAndReport(const CaseConfig& config, const std::string& out_option,
                                   double memory_budget_mb) {
  if (config.solver.scope == "global")
    return GlobalProposeAndReport(config, out_option, memory_budget_mb);
  const double start = NowSeconds();
  PlanRequestFromConfig(config, Eigen::Isometry3d::Identity(),
                        Eigen::Vector3d::Zero());  // settings first
  const std::filesystem::path out = PrepareCaseOutput(config, out_option);
  CaseSession session(config, memory_budget_mb);
  const Eigen::Isometry3d X_start = session.ConfigStartPose();
  planner::PlanRequest request = PlanRequestFromConfig(config, X_start, session.pivot_L());
  const planner::OracleSchedule& schedule = session.Schedule();
  // The arch analysis and a map field while the search runs, when the oracles were read from
  // the cache. After builds the search holds every oracle at the run's peak memory (a-bite: the
  // map field beside them took one cold run to 417 MB): they wait for the coarse ones' release.
  if (!session.BuiltOracles()) session.Prefetch();
  planner::PlanResult result;
  {
    ProgressBar bar("search (" + std::string(planner::ToString(request.solver)) + ")");
    request.on_progress = [&bar](int done, int total) { bar.Update(done, total); };
    try {
      result = planner::Plan(schedule, request);
    } catch (const std::invalid_argument& e) {
      throw UserError(config.file.string() + ": " + e.what());
    }
  }
  session.ReleaseCoarseOracles();  // the report reads the finest only
  const planner::Proposal& best = result.proposals.front();
  SearchSummary summary{"propose", "the config's [start] pose", &result, session.pivot_L(),
                        session.jaws().upper_U.get()};
  summary.analysis = &session.Analysis();
  // The 3D view's display meshes (the meshes alone) are decimated while the proposals are
  // analysed (the best for the report, every one for the view).
  DisplayJaws display;
  std::vector<Eigen::Isometry3d> poses;
  for (const planner::Proposal& p : result.proposals) poses.push_back(p.X_LU);
  std::vector<ReportAnalysis> analyses;
  RunTasks({[&] { analyses = AnalyzePoses(session, poses); },
            [&] { display = DecimateJawsForViewer(session.jaws(), session.cache().get()); }});
  ReportAnalysis& analysis = analyses.front();
  analysis.timings_s.emplace_back("search (wall)", result.wall_seconds);
  StepClock clock;
  clock.Start("rendered the maps and views");
  const ReportView view{&display, ProposalsForViewer(display, result, analyses)};
  const ReportFiles files = MakeReportFiles(session, analysis, "proposal 1 of `occlude propose`",
                                            SearchJson(summary, false), SearchHtml(summary), view);
  clock.Finish();
  std::vector<std::pair<std::string, std::string>> extra = {
      {"proposals.json", SearchJson(summary, true)}};
  PrepareOutputDir(out / "proposals");
  for (std::size_t k = 0; k < result.proposals.size(); ++k) {
    extra.emplace_back("proposals/proposal-" + std::to_string(k + 1) + ".json",
                       ProposalPoseJson(result.proposals[k].X_LU, static_cast<int>(k + 1)));
  }
  WriteReportFiles(out, files, extra);

  std::cout << config.name << ": " << result.proposals.size() << " proposal(s) from "
            << result.starts_run << " local solves (" << planner::ToString(request.solver) << ", "
            << std::fixed << std::setprecision(1) << result.wall_seconds << " s)\n";
  int rank = 0;
  for (const planner::Proposal& p : result.proposals) {
    const planner::PoseParameters q =
        planner::DecomposePose(p.X_LU, session.pivot_L(), Eigen::Isometry3d::Identity());
    std::cout << "  #" << ++rank << std::setprecision(3) << "  t (" << q.translation_mm.x() << ", "
              << q.translation_mm.y() << ", " << q.translation_mm.z() << ") mm  r ("
              << std::setprecision(2) << q.rotation_deg.x() << ", " << q.rotation_deg.y() << ", "
              << q.rotation_deg.z() << ") deg  contact " << p.evaluation.contact_area_mm2
              << " mm^2  max penetration " << std::setprecision(3)
              << p.evaluation.max_penetration_mm << " mm (constrained "
              << p.evaluation.constrained_penetration_mm << ", " << p.evaluation.outliers.size()
              << " outlier samples)  " << planner::ToString(p.status) << "\n";
  }
  if (best.status != planner::SolveStatus::kConverged &&
      best.status != planner::SolveStatus::kMaxEvaluations &&
      best.status != planner::SolveStatus::kMaxIterations) {
    std::cout << "  note: the best proposal's status is " << planner::ToString(best.status) << ": "
              << best.message << "; it is the best feasible pose found\n";
  }
  if (result.starts_skipped > 0) {
    std::cout << "  note: solver.max_seconds stopped the search: " << result.starts_skipped
              << " starts skipped\n";
  }
  std::cout << "report of #1 in " << (out / "report.html").string() << "; all proposals in "
            << (out / "proposals.json").string() << " (" << std::setprecision(1)
            << NowSeconds() - start << " s)\n";
  return best.X_LU;
}

}  // namespace occlude::app
