// The automated occlusion proposal as files (what `occlude propose` and `occlude demo` run):
// loads the meshes of a case config, builds the oracles (progress on stderr for every step
// over a second), searches from the config's start pose with the config's solver, and writes
// the K proposals (proposals.json, proposals/proposal-K.json pose files) and the full report
// of the best (report.html, maps, metrics.json with the search, pose.json,
// upper_at_pose.stl), printing one line per proposal.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "config/case_config.h"

namespace occlude::app {

/// The pose file of proposal `rank` (proposals/proposal-K.json): {"proposal": K, "X_LU": ...}.
std::string ProposalPoseJson(const Eigen::Isometry3d& X_LU, int rank);

/// Searches (in global scope, global_proposal_report.h, when config.solver.scope is
/// "global"), writes the proposals and the report of the best to OutputFolder(config,
/// out_option) and prints them; returns the best pose X_LU. `memory_budget_mb` > 0 is the
/// command's --memory-budget-mb (session/memory_guard.h).
Eigen::Isometry3d ProposeAndReport(const CaseConfig& config, const std::string& out_option,
                                   double memory_budget_mb);

}  // namespace occlude::app
