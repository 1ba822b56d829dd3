// The occlusion search: from a start pose, the K best distinct poses of the
// upper jaw with maximal contact under the penetration constraint.
//
// Every solver first settles the start along the occlusal axis (the jaws
// brought together until the penetration measure reaches its limit, or opened
// when they start nested), optimizes, and settles again on the final stage so
// that every returned pose is feasible when any feasible pose was seen.
// Multi-start runs spread the starts over `num_threads` std::threads; the
// result depends only on the request (seed), not on the thread count.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "occlude/planner/evaluation.h"
#include "occlude/planner/pose.h"
#include "occlude/planner/request.h"

namespace occlude::planner {

enum class SolveStatus {
  kConverged,       ///< the local solver met its tolerance
  kMaxEvaluations,  ///< stopped by the evaluation budget; best feasible pose returned
  kMaxIterations,   ///< stopped by its iteration limit before its tolerance was met (the
                    ///< message says by how much); its last pose returned
  kInfeasible,      ///< no pose met the penetration limit; the least penetrating one returned
  kFailed,          ///< the solver failed (message says why); best feasible pose returned
};
const char* ToString(SolveStatus status);

struct Proposal {
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();
  PoseParameters params;      ///< relative to the request's start pose, about the pivot
  PoseEvaluation evaluation;  ///< on the last stage of the schedule
  double score = 0.0;         ///< evaluation.score
  /// The seat objective (robust sum of the occlusal gaps plus the penetration penalty) on the
  /// last stage's occlusal samples at X_LU: the ranking of the proposals (lower is better).
  double seat_cost = 0.0;
  SolveStatus status = SolveStatus::kFailed;
  std::string message;       ///< solver detail (NLopt/Ceres termination)
  int start_index = 0;       ///< which start produced it (0 = the start pose)
  int evaluations = 0;       ///< objective/residual evaluations of this start
  double cpu_seconds = 0.0;  ///< thread CPU time of this start
};

struct PlanResult {
  std::vector<Proposal>
      proposals;  ///< at most max_proposals, distinct, feasible first, then lowest seat_cost
  Eigen::Vector3d pivot_L = Eigen::Vector3d::Zero();  ///< pivot used (L, at the start pose)
  SolverKind solver = SolverKind::kCoarseToFine;
  int starts_run = 0;      ///< local solves run (fewer than planned when max_seconds ran out)
  int starts_skipped = 0;  ///< local solves skipped by max_seconds
  int total_evaluations = 0;
  double cpu_seconds = 0.0;  ///< sum of thread CPU time of all starts and the global stage
  double wall_seconds = 0.0;
};

/// Runs the search. The schedule holds at least one stage (coarse first); all its oracles
/// are built on the same jaw pair. Throws std::invalid_argument for an invalid request or
/// schedule (naming the field). Never returns a non-finite pose.
PlanResult Plan(const OracleSchedule& schedule, const PlanRequest& request);

/// True when the two poses differ by more than the request's distinct thresholds (largest
/// displacement of `points_U`, or relative rotation).
bool DistinctPoses(const Eigen::Isometry3d& X_LU_a, const Eigen::Isometry3d& X_LU_b,
                   const std::vector<Eigen::Vector3d>& points_U, const PlanRequest& request);

}  // namespace occlude::planner
