// What the local validation (validate.cpp) and the global one (validate_global.cpp) share.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "validate/validate.h"

namespace occlude::app {

/// run(j) for j in [0, count) on options.threads threads (0 = all cores), every tenth
/// finished run logged on options.log.
void RunInParallel(std::size_t count, const ValidateOptions& options,
                   const std::function<void(std::size_t)>& run);

/// The request every run starts from: band, penetration, one thread, one proposal, the global
/// samples and the NLopt method of the options.
planner::PlanRequest BaseRequest(const ValidateOptions& options);

/// A run of `solver` from X_LU_start within the magnitude plus the bound margins of the
/// options (about the pivot): BaseRequest with those bounds, the solver, and the options'
/// internal starts for the multi-start solvers (coarse-to-fine, nlopt-global), else one.
planner::PlanRequest BoundedRequest(const ValidateOptions& options, const Magnitude& magnitude,
                                    planner::SolverKind solver,
                                    const Eigen::Isometry3d& X_LU_start);

/// The perturbed starts per magnitude ([magnitude][start]), seeded per (magnitude, start),
/// shared by all solvers.
std::vector<std::vector<planner::PoseParameters>> Perturbations(const ValidateOptions& options);

}  // namespace occlude::app
