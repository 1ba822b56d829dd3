// The 3D view of a report from a case session (see report_viewer.h).
#include "report/report_viewer.h"

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "base/tasks.h"
#include "report/relationships_table.h"

namespace occlude::app {

namespace {

io::DecimationResult DecimateForViewer(const io::TriangleMesh& mesh, OracleCache* cache,
                                       std::size_t max_triangles) {
  const io::DecimationRequest request{max_triangles};
  // A mesh within the budget is returned as it is: nothing worth keeping.
  if (mesh.num_triangles() <= max_triangles) cache = nullptr;
  return MadeOrCached(
      cache, kDisplayEntryKind, [&] { return io::DecimationKey(mesh, request); },
      [&] { return io::DecimateForDisplay(mesh, request); }, io::EncodeDecimation,
      [&](std::string_view bytes) { return io::DecodeDecimation(bytes, mesh); });
}

}  // namespace

DisplayJaws DecimateJawsForViewer(const JawPair& jaws, OracleCache* cache,
                                  std::size_t max_triangles) {
  DisplayJaws out;  // both jaws at once (a cold decimation is about 0.1 s a jaw, on one thread)
  RunTasks({[&] { out.lower = DecimateForViewer(*jaws.lower_L, cache, max_triangles); },
            [&] { out.upper = DecimateForViewer(*jaws.upper_U, cache, max_triangles); }});
  return out;
}

ViewerInputs ReportViewerInputs(const CaseSession& session, const DisplayJaws& display) {
  const CaseConfig& config = session.config();
  const collision::ArchFrame& arch = session.arch();
  ViewerInputs in;
  in.lower_L = &display.lower.mesh;
  in.upper_U = &display.upper.mesh;
  in.axes = {arch.occlusal_L, arch.anterior_L, arch.lateral_L};
  in.scale = {config.report.map_max_mm, config.contact_band_mm,
              config.report.map_penetration_from_mm};
  in.title = "3D view: " + config.name;
  return in;
}

ViewerProposal ViewerProposalOf(const DisplayJaws& display, const ReportAnalysis& analysis,
                                std::string label, std::string numbers_json) {
  ViewerProposal p;
  p.label = std::move(label);
  p.X_LU = analysis.X_LU;
  p.numbers_json = std::move(numbers_json);
  p.lower_distance_mm = io::ValuesAtKeptVertices(display.lower, analysis.lower_vertex_mm);
  p.upper_distance_mm = io::ValuesAtKeptVertices(display.upper, analysis.upper_vertex_mm);
  return p;
}

std::string AnalysisNumbersJson(const ReportAnalysis& analysis) {
  const nlohmann::ordered_json numbers = {
      {"contact area (mm\u00b2)", analysis.oracle.contact_area_mm2},
      {"contact spots", analysis.spots.size()},
      {"max penetration (mm)", analysis.oracle.max_penetration_mm}};
  return WithRelationships(numbers.dump(), analysis.relationships);
}

std::string WithRelationships(const std::string& numbers_json, const analysis::Relationships& r) {
  nlohmann::ordered_json numbers =
      nlohmann::ordered_json::parse(numbers_json, nullptr, /*allow_exceptions=*/false);
  if (!numbers.is_object()) {
    throw std::invalid_argument("WithRelationships: the numbers are not a JSON object");
  }
  for (const RelationshipRow& row : RelationshipRows(r)) {
    numbers[row.name] = row.value + (row.outside ? " (outside " + row.normal + ")" : "");
  }
  return numbers.dump();
}

std::vector<ViewerProposal> ProposalsForViewer(const DisplayJaws& display,
                                               const planner::PlanResult& result,
                                               const std::vector<ReportAnalysis>& analyses) {
  if (analyses.size() != result.proposals.size()) {
    throw std::invalid_argument("ProposalsForViewer: " + std::to_string(analyses.size()) +
                                " analyses for " + std::to_string(result.proposals.size()) +
                                " proposals");
  }
  std::vector<ViewerProposal> out;
  for (std::size_t k = 0; k < result.proposals.size(); ++k) {
    const planner::Proposal& p = result.proposals[k];
    const nlohmann::ordered_json numbers = {
        {"contact area (mm\u00b2)", p.evaluation.contact_area_mm2},
        {"max penetration (mm)", p.evaluation.max_penetration_mm},
        {"constrained penetration (mm)", p.evaluation.constrained_penetration_mm},
        {"seat cost", p.seat_cost},
        {"status", planner::ToString(p.status)}};
    out.push_back(ViewerProposalOf(display, analyses[k], "proposal " + std::to_string(k + 1),
                                   WithRelationships(numbers.dump(), analyses[k].relationships)));
  }
  return out;
}

}  // namespace occlude::app
