// The global occlusion proposal as files (`occlude propose` with solver.scope = "global" or
// --global): no start pose; the arch analysis of both jaws (session/case_analysis.h) gives the
// arches of the global search (planner/global_search.h) and the clinical relationships its
// judge ranks the distinct intercuspations by ([clinical], session/clinical_judge.h). Writes
// what the local proposal writes (proposals.json, proposals/proposal-K.json, the report of
// #1), each proposal labelled: contact, penetration, rank, the shift from the pose as given
// (`from_given`, in the lower's arch frame) and from the aligned arches, the relationships
// (molar and canine class per side, overjet, overbite, midline), the targets met; and the
// seats the [clinical] constraints excluded, with the reason. Progress (phase, done/total) on
// stderr.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "config/case_config.h"
#include "session/case_analysis.h"

namespace occlude::app {

/// The [clinical] targets of `config` at X_LU (U in L), for `refine`: `text` one line per
/// target for the console ("  molar_class_right I: met (I (+0.2 mm))"), `html` a section of
/// report.html.
struct TargetsReport {
  std::string text, html;
};
TargetsReport ReportTargets(const CaseConfig& config, const CaseAnalysis& analysis,
                            const Eigen::Isometry3d& X_LU);

/// As ProposeAndReport (proposal_report.h) in global scope; returns the best pose X_LU.
/// Throws UserError naming the config for a jaw without teeth, arches that cannot face each
/// other, or no seat left by the [clinical] constraints.
Eigen::Isometry3d GlobalProposeAndReport(const CaseConfig& config, const std::string& out_option,
                                         double memory_budget_mb);

}  // namespace occlude::app
