// The global occlusion proposal as files (see global_proposal_report.h).
#include "report/global_proposal_report.h"

#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/json_values.h"
#include "base/output_files.h"
#include "base/progress.h"
#include "base/text_format.h"
#include "base/timing.h"
#include "base/user_error.h"
#include "config/case_output.h"
#include "config/plan_config.h"
#include "report/proposal_report.h"
#include "report/relationships_json_internal.h"
#include "report/report_analysis.h"
#include "report/report_writer.h"
#include "report/search_document.h"
#include "session/case_session.h"
#include "session/clinical_judge.h"
#include "session/global_request.h"
#include "viewer/html_text.h"

namespace occlude::app {
namespace {

using nlohmann::json;

json ShiftJson(const planner::ArchShift& s) {
  return {{"lateral_mm", s.lateral_mm},   {"sagittal_mm", s.sagittal_mm},
          {"vertical_mm", s.vertical_mm}, {"yaw_deg", s.yaw_deg},
          {"pitch_deg", s.pitch_deg},     {"roll_deg", s.roll_deg}};
}

// The label of one seat: rank (0 for an excluded one), shifts, relationships, targets.
json SeatJson(const planner::GlobalProposal& g, int rank, const CaseConfig& config,
              const CaseAnalysis& analysis) {
  const analysis::Relationships r = RelationshipsAt(analysis, g.proposal.X_LU);
  json targets = json::array();
  for (const TargetCheck& c : CheckTargets(config.clinical, r)) {
    targets.push_back({{"key", c.key},
                       {"wanted", c.wanted},
                       {"measured", c.measured},
                       {"met", c.has_value ? json(c.met) : json(nullptr)}});
  }
  return {{"rank", rank},
          {"contact_area_mm2", g.proposal.evaluation.contact_area_mm2},
          {"constrained_penetration_mm", g.proposal.evaluation.constrained_penetration_mm},
          {"max_penetration_mm", g.proposal.evaluation.max_penetration_mm},
          {"from_given", ShiftJson(g.from_given)},
          {"from_aligned", ShiftJson(g.from_aligned)},
          {"basin", g.basin},
          {"relationships", RelationshipsJson(r)},
          {"relationships_line", RelationshipsLine(r)},
          {"admissible", g.judgement.admissible},
          {"penalty", g.judgement.penalty},
          {"judgement", g.judgement.note},
          {"targets", targets}};
}

// The search JSON of the proposals with the global labels added.
std::string GlobalJson(const std::string& search_json, const planner::GlobalResult& result,
                       const CaseConfig& config, const CaseAnalysis& analysis) {
  json j = json::parse(search_json);
  j["scope"] = "global";
  j["clinical_mode"] = ToString(config.clinical.mode);
  j["clinical_targets"] = config.clinical.from_config ? "[clinical]" : "the default ranking";
  for (std::size_t k = 0; k < result.proposals.size(); ++k)
    j["proposals"][k]["global"] =
        SeatJson(result.proposals[k], static_cast<int>(k + 1), config, analysis);
  json excluded = json::array();
  for (const planner::GlobalProposal& g : result.excluded) {
    json e = SeatJson(g, 0, config, analysis);
    e["X_LU"] = Matrix(g.proposal.X_LU.matrix());
    excluded.push_back(e);
  }
  j["excluded"] = excluded;
  j["warnings"] = result.warnings;
  j["alignment"] = {{"fit_rms_mm", result.alignment.fit_rms_mm},
                    {"fit_rms_before_mm", result.alignment.fit_rms_before_mm}};
  return j.dump(2) + "\n";
}

std::string ShiftText(const planner::ArchShift& s) {
  return Fixed(s.sagittal_mm, 1) + " / " + Fixed(s.lateral_mm, 1) + " / " +
         Fixed(s.vertical_mm, 1) + " mm, yaw " + Fixed(s.yaw_deg, 1) + " pitch " +
         Fixed(s.pitch_deg, 1) + " roll " + Fixed(s.roll_deg, 1) + " deg";
}

void SeatRows(std::ostringstream& h, const std::vector<planner::GlobalProposal>& seats, bool ranked,
              const CaseAnalysis& analysis) {
  int rank = 0;
  for (const planner::GlobalProposal& g : seats) {
    const analysis::Relationships r = RelationshipsAt(analysis, g.proposal.X_LU);
    h << "<tr><td>" << (ranked ? std::to_string(++rank) : "excluded") << "</td><td>"
      << Fixed(g.proposal.evaluation.contact_area_mm2, 2) << "</td><td>"
      << Fixed(g.proposal.evaluation.constrained_penetration_mm, 3) << "</td><td>"
      << ShiftText(g.from_given) << "</td><td>" << HtmlEscape(RelationshipsLine(r)) << "</td><td>"
      << Fixed(g.judgement.penalty, 2) << "</td><td>" << HtmlEscape(g.judgement.note)
      << "</td></tr>\n";
  }
}

std::string GlobalHtml(const planner::GlobalResult& result, const CaseConfig& config,
                       const CaseAnalysis& analysis) {
  std::ostringstream h;
  h << "<h2>Global search: the ranked intercuspations</h2>\n<p class=\"note\">No start pose: "
       "the arches aligned, every intercuspation basin over the sagittal shift, lateral shift, "
       "yaw and pitch refined and ranked by "
    << (config.clinical.from_config ? "the [clinical] targets" : "the default clinical ranking")
    << " (mode " << ToString(config.clinical.mode)
    << ") among seats of comparable contact. Shift from the pose as given: sagittal / lateral / "
       "vertical in the lower's arch frame.</p>\n";
  for (const std::string& w : result.warnings)
    h << "<p class=\"note\">warning: " << HtmlEscape(w) << "</p>\n";
  h << "<table><tr><th>rank</th><th>contact (mm&sup2;)</th><th>penetration (mm)</th><th>from "
       "given</th><th>relationships (R/L)</th><th>penalty</th><th>judgement</th></tr>\n";
  SeatRows(h, result.proposals, true, analysis);
  SeatRows(h, result.excluded, false, analysis);
  h << "</table>\n";
  return h.str();
}

// Progress of the search's phases: one bar per phase.
struct PhaseProgress {
  std::unique_ptr<ProgressBar> bar;
  planner::GlobalRequest::Phase phase = planner::GlobalRequest::Phase::kScan;
  void Update(planner::GlobalRequest::Phase p, int done, int total) {
    if (!bar || p != phase) {
      bar.reset();
      bar = std::make_unique<ProgressBar>(std::string("global search: ") + planner::ToString(p));
      phase = p;
    }
    bar->Update(done, total);
  }
};

planner::GlobalResult RunGlobalSearch(const CaseConfig& config, CaseSession& session,
                                      const CaseAnalysis& analysis) {
  const planner::PlanRequest local =
      PlanRequestFromConfig(config, session.ConfigStartPose(), session.pivot_L());
  planner::GlobalRequest g = GlobalRequestFromConfig(config, analysis, local);
  session.UseArchFrame(planner::FrameOf(g.lower_L));
  const planner::OracleSchedule& schedule = session.Schedule();
  PhaseProgress progress;
  g.on_progress = [&progress](planner::GlobalRequest::Phase p, int done, int total) {
    progress.Update(p, done, total);
  };
  try {
    return planner::GlobalSearch(schedule, g);
  } catch (const std::invalid_argument& e) {
    throw UserError(config.file.string() + ": the global search: " + e.what());
  }
}

void PrintSeats(const CaseConfig& config, const planner::GlobalResult& result,
                const CaseAnalysis& analysis) {
  std::cout << config.name << ": " << result.proposals.size()
            << " ranked intercuspation(s) of the global search (" << result.basins.size()
            << " basins, " << std::fixed << std::setprecision(1) << result.wall_seconds << " s, "
            << result.cpu_seconds << " s CPU)\n";
  int rank = 0;
  for (const planner::GlobalProposal& g : result.proposals) {
    std::cout << "  #" << ++rank << "  contact " << Fixed(g.proposal.evaluation.contact_area_mm2, 2)
              << " mm^2  penetration " << Fixed(g.proposal.evaluation.constrained_penetration_mm, 3)
              << " mm  from given " << ShiftText(g.from_given) << "  "
              << RelationshipsLine(RelationshipsAt(analysis, g.proposal.X_LU)) << "  penalty "
              << Fixed(g.judgement.penalty, 2) << "  " << planner::ToString(g.proposal.status)
              << "\n";
  }
  for (const planner::GlobalProposal& g : result.excluded)
    std::cout << "  excluded by [clinical] constraints: " << g.judgement.note << "\n";
  for (const std::string& w : result.warnings) std::cout << "  warning: " << w << "\n";
}

}  // namespace

TargetsReport ReportTargets(const CaseConfig& config, const CaseAnalysis& analysis,
                            const Eigen::Isometry3d& X_LU) {
  TargetsReport r;
  const analysis::Relationships rel = RelationshipsAt(analysis, X_LU);
  r.text = "  clinical targets (" + std::string(ToString(config.clinical.mode)) +
           "): " + RelationshipsLine(rel) + "\n";
  r.html = "<h2>Clinical targets</h2>\n<p class=\"note\">" + HtmlEscape(RelationshipsLine(rel)) +
           "</p>\n<table><tr><th>target</th><th>wanted</th><th>measured</th><th>met</th></tr>\n";
  for (const TargetCheck& c : CheckTargets(config.clinical, rel)) {
    const std::string met = !c.has_value ? "not measured" : c.met ? "met" : "missed";
    r.text += "    " + c.key + " " + c.wanted + ": " + met + " (" + c.measured + ")\n";
    r.html += "<tr><td>" + c.key + "</td><td>" + HtmlEscape(c.wanted) + "</td><td>" +
              HtmlEscape(c.measured) + "</td><td>" + met + "</td></tr>\n";
  }
  r.html += "</table>\n";
  return r;
}

namespace {

// The report of #1, proposals.json and the pose files of every proposal, written into `out`.
void WriteGlobalOutputs(CaseSession& session, const CaseConfig& config,
                        const CaseAnalysis& analysis, const planner::GlobalResult& result,
                        planner::SolverKind solver, const std::filesystem::path& out) {
  planner::PlanResult plan;
  plan.solver = solver;
  for (const planner::GlobalProposal& g : result.proposals) plan.proposals.push_back(g.proposal);
  plan.total_evaluations = result.total_evaluations;
  plan.cpu_seconds = result.cpu_seconds;
  plan.wall_seconds = result.wall_seconds;
  SearchSummary summary{"propose", "no start pose (global search)", &plan, session.pivot_L(),
                        session.jaws().upper_U.get()};
  ReportAnalysis report = AnalyzePose(session, plan.proposals.front().X_LU);
  report.timings_s.emplace_back("global search (wall)", result.wall_seconds);
  StepClock clock;
  clock.Start("rendered the maps and views");
  const std::string html = GlobalHtml(result, config, analysis) + SearchHtml(summary);
  const ReportFiles files =
      MakeReportFiles(session, report, "proposal 1 of `occlude propose --global`",
                      GlobalJson(SearchJson(summary, false), result, config, analysis), html);
  clock.Finish();
  std::vector<std::pair<std::string, std::string>> extra = {
      {"proposals.json", GlobalJson(SearchJson(summary, true), result, config, analysis)}};
  PrepareOutputDir(out / "proposals");
  for (std::size_t k = 0; k < plan.proposals.size(); ++k) {
    extra.emplace_back("proposals/proposal-" + std::to_string(k + 1) + ".json",
                       ProposalPoseJson(plan.proposals[k].X_LU, static_cast<int>(k + 1)));
  }
  WriteReportFiles(out, files, extra);
}

}  // namespace

Eigen::Isometry3d GlobalProposeAndReport(const CaseConfig& config_in, const std::string& out_option,
                                         double memory_budget_mb) {
  const double start = NowSeconds();
  CaseConfig config = config_in;
  config.region_of_interest = false;  // the global search reaches anywhere
  const planner::SolverKind solver =
      PlanRequestFromConfig(config, Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero())
          .solver;  // settings first
  const std::filesystem::path out = PrepareCaseOutput(config, out_option);
  CaseSession session(config, memory_budget_mb);
  const CaseAnalysis& analysis = session.Analysis();  // given landmarks ([landmarks]) applied
  const planner::GlobalResult result = RunGlobalSearch(config, session, analysis);
  session.ReleaseCoarseOracles();  // the report reads the finest only
  PrintSeats(config, result, analysis);
  if (result.proposals.empty()) {
    throw UserError(config.file.string() + ": clinical: no seat of the " +
                    std::to_string(result.excluded.size()) +
                    " found meets the targets (mode = \"constraint\"); relax them or give mode "
                    "= \"rank\"");
  }
  WriteGlobalOutputs(session, config, analysis, result, solver, out);
  std::cout << "report of #1 in " << (out / "report.html").string() << "; all proposals in "
            << (out / "proposals.json").string() << " (" << std::setprecision(1)
            << NowSeconds() - start << " s)\n";
  return result.proposals.front().proposal.X_LU;
}

}  // namespace occlude::app
