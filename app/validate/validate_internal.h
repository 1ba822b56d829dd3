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

/// The perturbed starts per magnitude ([magnitude][start]), seeded per (magnitude, start),
/// shared by all solvers.
std::vector<std::vector<planner::PoseParameters>> Perturbations(const ValidateOptions& options);

}  // namespace occlude::app
