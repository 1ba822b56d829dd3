// Plan(): the starts (the start pose, global seeds or sampled starts), one
// solver chain per start on std::threads (chain.cpp), and the K best distinct
// proposals.
#include "occlude/planner/plan.h"

#include <algorithm>
#include <chrono>

#include "search_internal.h"

namespace occlude::planner {

const char* ToString(SolveStatus status) {
  switch (status) {
    case SolveStatus::kConverged:
      return "converged";
    case SolveStatus::kMaxEvaluations:
      return "max-evaluations";
    case SolveStatus::kMaxIterations:
      return "max-iterations";
    case SolveStatus::kInfeasible:
      return "infeasible";
    case SolveStatus::kFailed:
      return "failed";
  }
  return "?";
}

bool DistinctPoses(const Eigen::Isometry3d& X_LU_a, const Eigen::Isometry3d& X_LU_b,
                   const std::vector<Eigen::Vector3d>& points_U, const PlanRequest& request) {
  const PoseError e = ComparePoses(X_LU_a, X_LU_b, points_U);
  return e.translation_mm > request.distinct_translation_mm ||
         e.rotation_deg > request.distinct_rotation_deg;
}

namespace {

using detail::Vector6d;

// The start pose, then the global stage's distinct seeds (nlopt-global, coarse-to-fine) or
// poses sampled uniformly in the bounds (the local solvers), up to num_starts.
std::vector<Vector6d> MakeStarts(const detail::SearchContext& c, int* evaluations) {
  const PlanRequest& req = *c.problem->request;
  const detail::Problem& problem = *c.problem;
  std::vector<Vector6d> starts{Vector6d::Zero()};
  if (req.solver == SolverKind::kNloptGlobal || req.solver == SolverKind::kCoarseToFine) {
    const auto seeds = detail::GlobalSeeds(c.schedule->front(), c.sets.front(), problem,
                                           req.num_global_samples, req.seed, evaluations);
    for (const Vector6d& s : seeds) {
      if (static_cast<int>(starts.size()) >= req.num_starts) break;
      bool distinct = true;
      for (const Vector6d& t : starts) {
        distinct = distinct && DistinctPoses(detail::PoseOf(problem, s), detail::PoseOf(problem, t),
                                             problem.ref_points_U, req);
      }
      if (distinct) starts.push_back(s);
    }
  } else {
    std::mt19937 rng(req.seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    while (static_cast<int>(starts.size()) < req.num_starts) {
      Vector6d x;
      for (int i = 0; i < kNumDof; ++i)
        x[i] = problem.lower[i] + unit(rng) * (problem.upper[i] - problem.lower[i]);
      starts.push_back(x);
    }
  }
  return starts;
}

}  // namespace

PlanResult Plan(const OracleSchedule& schedule, const PlanRequest& request) {
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = detail::CpuSeconds();
  const detail::Problem problem = detail::MakeProblem(schedule, request);
  const detail::SearchContext c = detail::MakeSearchContext(schedule, problem);
  PlanResult result;
  result.solver = request.solver;
  result.pivot_L = problem.pivot_L;
  int global_evals = 0;
  const std::vector<Vector6d> starts = MakeStarts(c, &global_evals);
  detail::Tracker tracker;
  tracker.request = &request;
  tracker.report = request.on_progress;
  tracker.start = std::chrono::steady_clock::now();
  const bool staged =
      request.solver == SolverKind::kCoarseToFine || request.solver == SolverKind::kNloptGlobal;
  const detail::Candidates candidates =
      staged && schedule.size() > 1 && starts.size() > 1
          ? detail::CoarseThenFine(
                c, starts, static_cast<std::size_t>(std::max(1, request.max_proposals)), &tracker)
          : detail::EachStart(c, starts, &tracker);
  result.starts_skipped = tracker.skipped.load();
  result.starts_run = static_cast<int>(starts.size()) - result.starts_skipped;
  result.total_evaluations = global_evals + candidates.evaluations;
  result.cpu_seconds = detail::CpuSeconds() - cpu0 + candidates.worker_cpu;
  result.proposals = detail::BestDistinct(candidates.proposals, problem, request.max_proposals);
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

}  // namespace occlude::planner
