// The clinical targets of a case (config/clinical_targets.h) checked against the relationships
// at a pose (session/case_analysis.h), and the planner::SeatJudge the global search ranks its
// seats with: a target's miss is a ranking penalty (mode "rank": 1 per side of a class not
// met, the mm outside an interval or over the midline limit) or makes the seat inadmissible
// (mode "constraint"). A target whose measure the landmarks do not give is "not measured":
// it neither counts against a seat nor excludes it.
#pragma once

#include <string>
#include <vector>

#include "analysis/relationships.h"
#include "config/clinical_targets.h"
#include "occlude/planner/seat_ranking.h"
#include "session/case_analysis.h"

namespace occlude::app {

/// One target at one pose.
struct TargetCheck {
  std::string key;       ///< the [clinical] key, e.g. "molar_class_right", "overjet_mm"
  std::string wanted;    ///< e.g. "I", "[1, 3] mm", "<= 2 mm"
  std::string measured;  ///< e.g. "II (+3.6 mm)", "2.4 mm"; "not measured: <why>"
  bool has_value = false;
  bool met = false;
  double miss = 0.0;  ///< the ranking penalty (0 when met or not measured)
};

/// Every target of `targets` at the relationships `r`, in key order (molar right, left,
/// canine right, left, overjet, overbite, midline).
std::vector<TargetCheck> CheckTargets(const ClinicalTargets& targets,
                                      const analysis::Relationships& r);

/// The judgement of relationships `r`: penalty the sum of the misses; in constraint mode
/// inadmissible when a measured target is missed; the note the relationships and the misses.
planner::SeatJudgement JudgeRelationships(const ClinicalTargets& targets,
                                          const analysis::Relationships& r);

/// One line of the relationships: "molar I/II, canine I/I, overjet 2.4 mm, overbite 1.8 mm,
/// midline 0.3 mm" (right/left; "?" for a measure not given).
std::string RelationshipsLine(const analysis::Relationships& r);

/// The targets in one line: "molar I/I, canine I/I, overjet [1.0, 3.0] mm, overbite [1.0, 3.0]
/// mm, midline <= 2.0 mm; rank" (right/left; "-" for a side without a target; a measure without
/// a target left out).
std::string TargetsLine(const ClinicalTargets& targets);

/// The judge of the global search: JudgeRelationships at each seat's X_LU (U in L).
/// `analysis` must outlive the judge.
planner::SeatJudge ClinicalJudge(const ClinicalTargets& targets, const CaseAnalysis& analysis);

}  // namespace occlude::app
