// The planner request a case config asks for: [solver] (name, starts, seed, threads,
// proposals, max_seconds and the [solver.options] table), [contact], [bounds] with the locked
// degrees of freedom, and the pivot. Errors name the config file and the key:
//   [solver.options] keys (all optional; defaults as in planner::PlanRequest):
//     nlopt_local = "auglag-bobyqa" | "cobyla" | "auglag-sbplx"   global_samples = 16
//     max_evaluations = 600        penetration_measure = "outlier-area" | "max" | "percentile"
//     outlier_area_mm2 = 0.05      penetration_percentile = 99      spike_patch_max_mm2 = 5
//     bilateral_posterior_weight = 0   seat_window_mm = 1   seat_scale_mm = 0.3
//     seat_penetration_allowance_mm = 0.02   seat_min_facing = 0.6
//     distinct_translation_mm = 0.5   distinct_rotation_deg = 2
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "config/case_config.h"
#include "occlude/planner/request.h"

namespace occlude::app {

/// The request for a search from X_LU_start about pivot_L (mm, in L at the pose as given:
/// the pivot at X_LU_start is X_LU_start * pivot_L). Throws UserError naming the file and key.
planner::PlanRequest PlanRequestFromConfig(const CaseConfig& config,
                                           const Eigen::Isometry3d& X_LU_start,
                                           const Eigen::Vector3d& pivot_L);

/// The [solver.options] keys PlanRequestFromConfig understands.
const std::vector<std::string>& SolverOptionKeys();

/// The degrees of freedom `refine` holds at the adjusted pose (refine.hold): with "adjusted"
/// those [adjust] changes (a non-zero component), else the listed ones; bounds.locked ones
/// are held anyway and not repeated here.
std::array<bool, kNumDofs> RefineHeldDofs(const CaseConfig& config);

}  // namespace occlude::app
