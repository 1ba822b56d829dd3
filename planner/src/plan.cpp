// Plan(): the starts (the start pose, global seeds or sampled starts), one
// solver chain per start on std::threads, the final settle and evaluation on
// the last stage, and the K best distinct proposals.
#include "occlude/planner/plan.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <numeric>
#include <thread>

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

struct Context {
  const OracleSchedule* schedule;
  const detail::Problem* problem;
  std::vector<detail::SampleSet> sets;  // per stage
};

// Stages [first, stop] of the chain for one start (coarse-to-fine; the others ignore them).
// Coarse-to-fine settles on the first stage it runs when that is stage 0 and runs Ceres on each;
// the single-stage solvers run on the last stage only.
detail::LocalResult RunChain(const Context& c, const Vector6d& start, std::size_t first,
                             std::size_t stop) {
  const PlanRequest& req = *c.problem->request;
  const OracleSchedule& sch = *c.schedule;
  const std::size_t last = sch.size() - 1;
  detail::LocalResult r;
  r.x = start;
  int evals = 0;
  switch (req.solver) {
    case SolverKind::kNloptLocal: {
      const Vector6d x = detail::SettleOnSet(sch[last], c.sets[last], *c.problem, start, &evals);
      r = detail::NloptLocal(sch[last], c.sets[last], *c.problem, x, req.max_evaluations);
      break;
    }
    case SolverKind::kNloptGlobal: {  // the NLopt analogue of coarse-to-fine
      Vector6d x = start;
      detail::LocalResult stage_result;
      stage_result.x = x;
      for (std::size_t s = first; s <= std::min(stop, last); ++s) {
        if (s == first) x = detail::SettleOnSet(sch[s], c.sets[s], *c.problem, x, &evals);
        stage_result = detail::NloptLocal(sch[s], c.sets[s], *c.problem, x, req.max_evaluations);
        evals += stage_result.evaluations;
        x = stage_result.x;
      }
      r = stage_result;
      r.x = x;
      r.evaluations = 0;
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
      stage_result.x = x;
      for (std::size_t s = first; s <= std::min(stop, last); ++s) {
        if (s == 0) x = detail::SettleOnSet(sch[s], c.sets[s], *c.problem, x, &evals);
        const bool exact = sch[s].level == collision::AccuracyLevel::kExact;
        stage_result = detail::CeresLocal(sch[s], c.sets[s], *c.problem, x, exact ? 2 : 4,
                                          req.max_evaluations);
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

// RunChain with the failures turned into a status (never throws, never non-finite).
detail::LocalResult SafeChain(const Context& c, const Vector6d& start, std::size_t first,
                              std::size_t stop) {
  detail::LocalResult r;
  try {
    r = RunChain(c, start, first, stop);
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
  return r;
}

// The final settle on the last stage's oracle and the evaluation of the result.
Proposal Finish(const Context& c, int index, const detail::LocalResult& r) {
  const detail::Problem& problem = *c.problem;
  const OracleStage& final_stage = c.schedule->back();
  Proposal p;
  p.start_index = index;
  int evals = 0;
  Vector6d x = detail::SettleOnOracle(final_stage, problem, detail::Clamp(problem, r.x), &evals);
  p.X_LU = detail::PoseOf(problem, x);
  p.params = detail::ToParameters(x);
  p.evaluation = EvaluatePose(final_stage, p.X_LU, *problem.request);
  p.score = p.evaluation.score;
  p.seat_cost = detail::EvaluateSet(final_stage, c.sets.back(), p.X_LU, problem).seat_cost;
  p.status = r.status;
  p.message = r.message;
  if (!p.evaluation.feasible && p.status != SolveStatus::kFailed) {
    p.status = SolveStatus::kInfeasible;
    p.message += "; the penetration limit is not met within the bounds";
  }
  p.evaluations = r.evaluations + evals + 1;
  return p;
}

// Progress and the wall-clock budget of the local solves.
struct Tracker {
  const PlanRequest* request = nullptr;
  std::chrono::steady_clock::time_point start;
  int total = 0;
  std::atomic<int> done{0}, skipped{0};
  std::mutex mutex;
  bool OutOfTime() const {
    return request->max_seconds > 0.0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
               request->max_seconds;
  }
  void Done() {
    const int n = ++done;
    if (request->on_progress) {
      std::lock_guard<std::mutex> lock(mutex);
      request->on_progress(n, total);
    }
  }
};

// Runs job(i) for i in [0, n) on up to `threads` std::threads; the results land in slots
// indexed by i, so they do not depend on the thread count. Returns the CPU seconds of the
// threads other than the caller (the caller's own are on its clock).
template <typename Job>
double ParallelFor(std::size_t n, int threads, Job job) {
  std::atomic<std::size_t> next{0};
  std::vector<double> cpu(static_cast<std::size_t>(std::max(1, threads)), 0.0);
  auto worker = [&](int slot) {
    const double t0 = detail::CpuSeconds();
    for (std::size_t i = next++; i < n; i = next++) job(i);
    cpu[static_cast<std::size_t>(slot)] = detail::CpuSeconds() - t0;
  };
  const int count = std::max(1, std::min<int>(threads, static_cast<int>(n)));
  std::vector<std::thread> pool;
  for (int t = 1; t < count; ++t) pool.emplace_back(worker, t);
  worker(0);
  for (auto& t : pool) t.join();
  double others = 0.0;
  for (std::size_t t = 1; t < cpu.size(); ++t) others += cpu[t];
  return others;
}

std::vector<Vector6d> MakeStarts(const Context& c, int* evaluations) {
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
  result.total_evaluations = global_evals;
  const std::size_t last = schedule.size() - 1;
  std::vector<Proposal> candidates;
  double worker_cpu = 0.0;
  Tracker tracker;
  tracker.request = &request;
  tracker.start = std::chrono::steady_clock::now();
  const bool staged =
      request.solver == SolverKind::kCoarseToFine || request.solver == SolverKind::kNloptGlobal;
  if (staged && last > 0 && starts.size() > 1) {
    // Every start on the coarse stage; only the best distinct coarse seats (by the coarse
    // seat cost) go on to the finer stages: the fine models see only seats that can win.
    std::vector<detail::LocalResult> coarse(starts.size());
    std::vector<double> coarse_cost(starts.size()), coarse_cpu(starts.size());
    std::vector<char> ran(starts.size(), 0);
    const std::size_t refine = std::min<std::size_t>(
        starts.size(), static_cast<std::size_t>(std::max(1, request.max_proposals)));
    tracker.total = static_cast<int>(starts.size() + refine);
    worker_cpu += ParallelFor(starts.size(), request.num_threads, [&](std::size_t i) {
      if (i > 0 && tracker.OutOfTime()) {  // the start pose itself always runs
        ++tracker.skipped;
        return;
      }
      const double t0 = detail::CpuSeconds();
      coarse[i] = SafeChain(c, starts[i], 0, 0);
      coarse_cost[i] = detail::EvaluateSet(schedule.front(), c.sets.front(),
                                           detail::PoseOf(problem, coarse[i].x), problem)
                           .seat_cost;
      coarse_cpu[i] = detail::CpuSeconds() - t0;
      ran[i] = 1;
      tracker.Done();
    });
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < starts.size(); ++i) {
      if (ran[i]) order.push_back(i);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return coarse_cost[a] < coarse_cost[b]; });
    std::vector<std::size_t> kept;
    for (const std::size_t i : order) {
      if (static_cast<int>(kept.size()) >= std::max(1, request.max_proposals)) break;
      bool distinct = true;
      for (const std::size_t k : kept) {
        distinct = distinct && DistinctPoses(detail::PoseOf(problem, coarse[i].x),
                                             detail::PoseOf(problem, coarse[k].x),
                                             problem.ref_points_U, request);
      }
      if (distinct) kept.push_back(i);
    }
    for (std::size_t i = 0; i < starts.size(); ++i) {
      if (ran[i]) result.total_evaluations += coarse[i].evaluations;
    }
    tracker.total = static_cast<int>(
        starts.size() - static_cast<std::size_t>(tracker.skipped.load()) + kept.size());
    candidates.resize(kept.size());
    worker_cpu += ParallelFor(kept.size(), request.num_threads, [&](std::size_t k) {
      const std::size_t i = kept[k];
      const double t0 = detail::CpuSeconds();
      detail::LocalResult fine = SafeChain(c, coarse[i].x, 1, last);
      if (fine.status == SolveStatus::kFailed)
        fine.message = coarse[i].message + "; " + fine.message;
      candidates[k] = Finish(c, static_cast<int>(i), fine);
      candidates[k].evaluations += coarse[i].evaluations;
      candidates[k].cpu_seconds = coarse_cpu[i] + detail::CpuSeconds() - t0;
      tracker.Done();
    });
  } else {
    candidates.resize(starts.size());
    std::vector<char> ran(starts.size(), 0);
    tracker.total = static_cast<int>(starts.size());
    worker_cpu += ParallelFor(starts.size(), request.num_threads, [&](std::size_t i) {
      if (i > 0 && tracker.OutOfTime()) {
        ++tracker.skipped;
        return;
      }
      const double t0 = detail::CpuSeconds();
      candidates[i] = Finish(c, static_cast<int>(i), SafeChain(c, starts[i], 0, last));
      candidates[i].cpu_seconds = detail::CpuSeconds() - t0;
      ran[i] = 1;
      tracker.Done();
    });
    std::vector<Proposal> kept;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (ran[i]) kept.push_back(std::move(candidates[i]));
    }
    candidates = std::move(kept);
  }
  result.starts_skipped = tracker.skipped.load();
  result.starts_run = static_cast<int>(starts.size()) - result.starts_skipped;
  for (const Proposal& p : candidates) result.total_evaluations += p.evaluations;
  result.cpu_seconds = detail::CpuSeconds() - cpu0 + worker_cpu;
  // Best first: feasible before infeasible, then the seat cost (the contact area at the limit
  // is a hair trigger: at one seat it varied 14-54 mm^2 with 0.08 mm of closure on a-bite, so it
  // does not rank seats), then start index (deterministic).
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const Proposal &pa = candidates[a], &pb = candidates[b];
    if (pa.evaluation.feasible != pb.evaluation.feasible) return pa.evaluation.feasible;
    if (pa.evaluation.feasible) return pa.seat_cost < pb.seat_cost;
    return pa.evaluation.constrained_penetration_mm < pb.evaluation.constrained_penetration_mm;
  });
  for (const std::size_t i : order) {
    if (static_cast<int>(result.proposals.size()) >= request.max_proposals) break;
    bool distinct = true;
    for (const Proposal& q : result.proposals) {
      distinct =
          distinct && DistinctPoses(candidates[i].X_LU, q.X_LU, problem.ref_points_U, request);
    }
    if (distinct) result.proposals.push_back(candidates[i]);
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

}  // namespace occlude::planner
