// Plan(): the starts (the start pose, global seeds or sampled starts), one
// solver chain per start on std::threads, the final settle and evaluation on
// the last stage, and the K best distinct proposals.
#include "occlude/planner/plan.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <thread>

#include "search_internal.h"

namespace occlude::planner {

const char* ToString(SolveStatus status) {
  switch (status) {
    case SolveStatus::kConverged: return "converged";
    case SolveStatus::kMaxEvaluations: return "max-evaluations";
    case SolveStatus::kInfeasible: return "infeasible";
    case SolveStatus::kFailed: return "failed";
  }
  return "?";
}

bool DistinctPoses(const Eigen::Isometry3d& X_LU_a, const Eigen::Isometry3d& X_LU_b,
                   const std::vector<Eigen::Vector3d>& points_U, const PlanRequest& request) {
  const PoseError e = ComparePoses(X_LU_a, X_LU_b, points_U);
  return e.translation_mm > request.distinct_translation_mm || e.rotation_deg > request.distinct_rotation_deg;
}

namespace {

using detail::Vector6d;

struct Context {
  const OracleSchedule* schedule;
  const detail::Problem* problem;
  std::vector<detail::SampleSet> sets;  // per stage
};

detail::LocalResult RunChain(const Context& c, const Vector6d& start) {
  const PlanRequest& req = *c.problem->request;
  const OracleSchedule& sch = *c.schedule;
  const std::size_t last = sch.size() - 1;
  detail::LocalResult r;
  r.x = start;
  int evals = 0;
  switch (req.solver) {
    case SolverKind::kNloptLocal:
    case SolverKind::kNloptGlobal: {
      const Vector6d x = detail::SettleOnSet(sch[last], c.sets[last], *c.problem, start, &evals);
      r = detail::NloptLocal(sch[last], c.sets[last], *c.problem, x, req.max_evaluations);
      break;
    }
    case SolverKind::kCeres: {
      const Vector6d x = detail::SettleOnSet(sch[last], c.sets[last], *c.problem, start, &evals);
      r = detail::CeresLocal(sch[last], c.sets[last], *c.problem, x, 6, req.max_evaluations);
      break;
    }
    case SolverKind::kCoarseToFine: {
      Vector6d x = start;
      detail::LocalResult stage_result;
      for (std::size_t s = 0; s <= last; ++s) {
        if (s == 0) x = detail::SettleOnSet(sch[s], c.sets[s], *c.problem, x, &evals);
        const bool exact = sch[s].level == collision::AccuracyLevel::kExact;
        stage_result = detail::CeresLocal(sch[s], c.sets[s], *c.problem, x, exact ? 2 : 4, req.max_evaluations);
        evals += stage_result.evaluations;
        x = stage_result.x;
      }
      r = stage_result;
      r.x = x;
      r.evaluations = 0;
      break;
    }
  }
  r.evaluations += evals;
  return r;
}

Proposal Finish(const Context& c, int index, const Vector6d& start) {
  const double cpu0 = detail::CpuSeconds();
  const detail::Problem& problem = *c.problem;
  const OracleStage& final_stage = c.schedule->back();
  Proposal p;
  p.start_index = index;
  detail::LocalResult r;
  try {
    r = RunChain(c, start);
  } catch (const std::exception& e) {
    r.x = start;
    r.status = SolveStatus::kFailed;
    r.message = std::string("solver threw: ") + e.what();
  }
  if (!detail::Finite(r.x)) {
    r.x = start;
    r.status = SolveStatus::kFailed;
    r.message += "; non-finite pose replaced by the start";
  }
  int evals = 0;
  Vector6d x = detail::SettleOnOracle(final_stage, problem, detail::Clamp(problem, r.x), &evals);
  p.X_LU = detail::PoseOf(problem, x);
  p.params = detail::ToParameters(x);
  p.evaluation = EvaluatePose(final_stage, p.X_LU, *problem.request);
  p.score = p.evaluation.score;
  p.status = r.status;
  p.message = r.message;
  if (!p.evaluation.feasible && p.status != SolveStatus::kFailed) {
    p.status = SolveStatus::kInfeasible;
    p.message += "; the penetration limit is not met within the bounds";
  }
  p.evaluations = r.evaluations + evals + 1;
  p.cpu_seconds = detail::CpuSeconds() - cpu0;
  return p;
}

std::vector<Vector6d> MakeStarts(const Context& c, int* evaluations) {
  const PlanRequest& req = *c.problem->request;
  const detail::Problem& problem = *c.problem;
  std::vector<Vector6d> starts{Vector6d::Zero()};
  if (req.solver == SolverKind::kNloptGlobal || req.solver == SolverKind::kCoarseToFine) {
    const auto seeds = detail::GlobalSeeds(c.schedule->front(), c.sets.front(), problem, req.num_global_samples,
                                           req.seed, evaluations);
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
      for (int i = 0; i < kNumDof; ++i) x[i] = problem.lower[i] + unit(rng) * (problem.upper[i] - problem.lower[i]);
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
  Context c{&schedule, &problem, {}};
  for (const OracleStage& s : schedule) {
    const double spacing = detail::StageSpacing(s);
    const detail::SampleSet* same = nullptr;
    for (const auto& prior : c.sets) same = prior.spacing_mm == spacing ? &prior : same;
    c.sets.push_back(same ? *same
                          : detail::OcclusalSamples(s.oracle->upper_tree().mesh(), problem.X_ref,
                                                    problem.arch.occlusal_L, spacing));
  }
  PlanResult result;
  result.solver = request.solver;
  result.pivot_L = problem.pivot_L;
  int global_evals = 0;
  const std::vector<Vector6d> starts = MakeStarts(c, &global_evals);
  std::vector<Proposal> candidates(starts.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&]() {
    for (std::size_t i = next++; i < starts.size(); i = next++) {
      candidates[i] = Finish(c, static_cast<int>(i), starts[i]);
    }
  };
  const int threads = std::min<int>(request.num_threads, static_cast<int>(starts.size()));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();

  result.starts_run = static_cast<int>(starts.size());
  result.total_evaluations = global_evals;
  result.cpu_seconds = detail::CpuSeconds() - cpu0;
  for (const Proposal& p : candidates) {
    result.total_evaluations += p.evaluations;
    if (threads > 1) result.cpu_seconds += p.cpu_seconds;  // worker threads' CPU time
  }
  // Best first: feasible before infeasible, then score, then start index (deterministic).
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const Proposal &pa = candidates[a], &pb = candidates[b];
    if (pa.evaluation.feasible != pb.evaluation.feasible) return pa.evaluation.feasible;
    if (pa.evaluation.feasible) return pa.score > pb.score;
    return pa.evaluation.constrained_penetration_mm < pb.evaluation.constrained_penetration_mm;
  });
  for (const std::size_t i : order) {
    if (static_cast<int>(result.proposals.size()) >= request.max_proposals) break;
    bool distinct = true;
    for (const Proposal& q : result.proposals) {
      distinct = distinct && DistinctPoses(candidates[i].X_LU, q.X_LU, problem.ref_points_U, request);
    }
    if (distinct) result.proposals.push_back(candidates[i]);
  }
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

}  // namespace occlude::planner
