// The 3D view of a report (viewer/viewer_page.h) from a case session: both jaws decimated for
// display, each pose's per-vertex distances of the report analysis carried to the display
// vertices, the contact scale of the config and the standard views along the arch frame. Used
// by report.html (report, propose, refine) and by the live page of `refine --watch --serve`.
//
// Frames and units: the display lower in L, the display upper in U (the session's frames at
// the reference), every pose X_LU; mm.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "occlude/io/display_decimation.h"
#include "occlude/planner/plan.h"
#include "report/report_analysis.h"
#include "session/oracle_cache.h"
#include "viewer/viewer_page.h"

namespace occlude::app {

/// Triangles per jaw in the 3D view at most (two jaws: a few hundred thousand in all).
inline constexpr std::size_t kViewerTrianglesPerJaw = 100000;

/// Both jaws of a session decimated for display (deterministic; a tenth of a second per
/// 150k-triangle jaw), kept in `cache` (entries "display-<key>.occo": io::DecimationKey, bit
/// for bit on a hit) unless it is null or off. The source meshes must outlive nothing: the
/// results own their meshes.
struct DisplayJaws {
  io::DecimationResult lower;  ///< in L
  io::DecimationResult upper;  ///< in U
};
inline constexpr char kDisplayEntryKind[] = "display";
DisplayJaws DecimateJawsForViewer(const JawPair& jaws, OracleCache* cache,
                                  std::size_t max_triangles = kViewerTrianglesPerJaw);

/// The view's meshes, axes and scale (no proposal yet); points into `display`.
ViewerInputs ReportViewerInputs(const CaseSession& session, const DisplayJaws& display);

/// The pose of `analysis` for the view: its X_LU and its vertex distances at the display
/// vertices; `numbers_json` a JSON object of what to list beside it (see ViewerProposal).
ViewerProposal ViewerProposalOf(const DisplayJaws& display, const ReportAnalysis& analysis,
                                std::string label, std::string numbers_json);

/// The numbers the view lists for an analysis: contact area, spots, maximum penetration, then
/// its clinical relationships (WithRelationships).
std::string AnalysisNumbersJson(const ReportAnalysis& analysis);

/// `numbers_json` (a JSON object) followed by one entry per clinical relationship, in
/// clinical.md's order (report/relationships_table.h): "overjet" -> "2.70 mm", a value outside
/// its normal range followed by "(outside 1 to 3 mm)", a missing one "not found". Throws
/// std::invalid_argument when numbers_json is not a JSON object.
std::string WithRelationships(const std::string& numbers_json, const analysis::Relationships& r);

/// The K proposals of a search for the view ("proposal 1".. in rank order), each with its
/// contact, penetration, seat cost, status and clinical relationships; `analyses` holds the
/// analysis of each proposal, in the same order (AnalyzePoses).
std::vector<ViewerProposal> ProposalsForViewer(const DisplayJaws& display,
                                               const planner::PlanResult& result,
                                               const std::vector<ReportAnalysis>& analyses);

}  // namespace occlude::app
