// What propose and refine add to a report: the proposals of a search (poses, contact,
// penetration, per-tooth contact, score and seat cost, status) and the points the
// penetration constraint treated as scan artefacts, as JSON (proposals.json and the
// "search" object of metrics.json) and as an HTML fragment of report.html.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "occlude/io/triangle_mesh.h"
#include "occlude/planner/plan.h"
#include "session/case_analysis.h"

namespace occlude::app {

struct SearchSummary {
  std::string command;       ///< "propose" or "refine"
  std::string start_source;  ///< where the search started
  const planner::PlanResult* result = nullptr;
  Eigen::Vector3d pivot_L = Eigen::Vector3d::Zero();  ///< pivot at the pose as given (U = L)
  const io::TriangleMesh* upper_U = nullptr;          ///< for tooth numbers of parts
  const CaseAnalysis* analysis = nullptr;  ///< when set, each proposal's clinical relationships
};

/// JSON object text: settings used, starts run, evaluations, times, and one entry per
/// proposal with X_LU, translation/rotation about the pivot relative to the pose as given,
/// contact, penetration (true maximum and the constrained measure), per-tooth contact, the
/// outliers (position, depth, area, tooth, spike or budget), score, seat cost and status.
/// `with_timings` false leaves out the run-time fields (for byte-identical reruns).
std::string SearchJson(const SearchSummary& s, bool with_timings);
/// The HTML section: the proposals table and the best proposal's outliers.
std::string SearchHtml(const SearchSummary& s);

}  // namespace occlude::app
