// The global search (planner/global_search.h) of a case: the planner's JawArch of each jaw from
// the case's arch analysis (session/case_analysis.h), and the GlobalRequest of a case config
// (the local settings each basin is refined with, the clinical judge of its [clinical]
// targets). Errors are UserErrors naming the config file: a jaw without teeth or arch curve,
// arches that cannot face each other (the same jaw twice, one mirrored or upside down).
#pragma once

#include <string>

#include "analysis/arch_analysis.h"
#include "config/case_config.h"
#include "occlude/planner/global_search.h"
#include "session/case_analysis.h"

namespace occlude::app {

/// The JawArch of an analysed jaw in its own frame J: the analysis's arch frame, the incisal
/// point its dental midline point projected onto the occlusal plane, its arch curve. Throws
/// UserError "<source>: the <jaw> jaw: ..." when the analysis failed or found under 4 curve points.
planner::JawArch JawArchOf(const analysis::ArchAnalysis& a, const std::string& source);

/// The global search of `config`: both arches from `analysis` (lower in L, upper in U),
/// `local` the refinement settings (PlanRequestFromConfig at the pose as given), the ranking
/// by ClinicalJudge(config.clinical, analysis) (`analysis` must outlive the request). Checks
/// the request: throws UserError naming the config for arches that cannot face each other.
planner::GlobalRequest GlobalRequestFromConfig(const CaseConfig& config,
                                               const CaseAnalysis& analysis,
                                               const planner::PlanRequest& local);

}  // namespace occlude::app
