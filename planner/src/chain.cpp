// The solver chain per start that Plan and the global search share: the sample
// sets of the stages, one start through the request's solver (single-stage, or
// stage by stage), the final settle and evaluation, the coarse-then-fine
// selection of the starts worth refining, and the best distinct proposals.
#include <algorithm>
#include <numeric>

#include "occlude/assert.h"
#include "search_internal.h"

namespace occlude::planner::detail {

SearchContext MakeSearchContext(const OracleSchedule& schedule, const Problem& problem) {
  SearchContext c{&schedule, &problem, {}};
  for (const OracleStage& s : schedule) {
    const double spacing = StageSpacing(s);
    const SampleSet* same = nullptr;
    for (const auto& prior : c.sets) same = prior.spacing_mm == spacing ? &prior : same;
    c.sets.push_back(same ? *same
                          : OcclusalSamples(s.oracle->upper_tree().mesh(), problem.X_ref,
                                            problem.arch.occlusal_L, spacing));
  }
  return c;
}

namespace {

// nlopt-local and ceres: settle and solve on the last stage.
LocalResult LastStageSolve(const SearchContext& c, const Vector6d& start) {
  const PlanRequest& req = *c.problem->request;
  const std::size_t last = c.schedule->size() - 1;
  const OracleStage& stage = (*c.schedule)[last];
  int evals = 0;
  const Vector6d x = SettleOnSet(stage, c.sets[last], *c.problem, start, &evals);
  LocalResult r = req.solver == SolverKind::kNloptLocal
                      ? NloptLocal(stage, c.sets[last], *c.problem, x, req.max_evaluations)
                      : CeresLocal(stage, c.sets[last], *c.problem, x, 6, req.max_evaluations);
  r.evaluations += evals;
  return r;
}

// coarse-to-fine (Ceres on each stage; it settles on stage 0 when it runs it) and nlopt-global
// (its NLopt analogue; it settles on the first stage it runs), on stages [first, stop].
LocalResult StagedSolve(const SearchContext& c, const Vector6d& start, std::size_t first,
                        std::size_t stop) {
  const PlanRequest& req = *c.problem->request;
  const OracleSchedule& sch = *c.schedule;
  const bool ceres = req.solver == SolverKind::kCoarseToFine;
  Vector6d x = start;
  LocalResult stage_result;
  stage_result.x = x;
  int evals = 0;
  for (std::size_t s = first; s <= std::min(stop, sch.size() - 1); ++s) {
    if (ceres ? s == 0 : s == first) x = SettleOnSet(sch[s], c.sets[s], *c.problem, x, &evals);
    if (ceres) {
      const bool exact = sch[s].level == collision::AccuracyLevel::kExact;
      stage_result =
          CeresLocal(sch[s], c.sets[s], *c.problem, x, exact ? 2 : 4, req.max_evaluations);
    } else {
      stage_result = NloptLocal(sch[s], c.sets[s], *c.problem, x, req.max_evaluations);
    }
    evals += stage_result.evaluations;
    x = stage_result.x;
  }
  LocalResult r = stage_result;
  r.x = x;
  r.evaluations = evals;
  return r;
}

}  // namespace

LocalResult SafeChain(const SearchContext& c, const Vector6d& start, std::size_t first,
                      std::size_t stop) {
  LocalResult r;
  try {
    const SolverKind solver = c.problem->request->solver;
    const bool staged = solver == SolverKind::kCoarseToFine || solver == SolverKind::kNloptGlobal;
    r = staged ? StagedSolve(c, start, first, stop) : LastStageSolve(c, start);
    // The polish of a result whose chain ran the last stage (PlanRequest::polish).
    const std::size_t last = c.schedule->size() - 1;
    if (c.problem->request->polish && (!staged || (first <= last && stop >= last))) {
      r.x = Polish((*c.schedule)[last], c.sets[last], *c.problem, r.x, PolishSettings{},
                   &r.evaluations);
    }
  } catch (const std::exception& e) {
    r.x = start;
    r.status = SolveStatus::kFailed;
    r.message = std::string("solver threw: ") + e.what();
  }
  if (!Finite(r.x)) {
    r.x = start;
    r.status = SolveStatus::kFailed;
    r.message += "; non-finite pose replaced by the start";
  }
  return r;
}

Proposal Finish(const SearchContext& c, int index, const LocalResult& r) {
  const Problem& problem = *c.problem;
  const OracleStage& final_stage = c.schedule->back();
  Proposal p;
  p.start_index = index;
  int evals = 0;
  Vector6d x = SettleOnOracle(final_stage, problem, Clamp(problem, r.x), &evals);
  p.X_LU = PoseOf(problem, x);
  p.params = ToParameters(x);
  p.evaluation = EvaluatePose(final_stage, p.X_LU, *problem.request);
  p.score = p.evaluation.score;
  p.seat_cost = EvaluateSet(final_stage, c.sets.back(), p.X_LU, problem).seat_cost;
  p.status = r.status;
  p.message = r.message;
  if (!p.evaluation.feasible && p.status != SolveStatus::kFailed) {
    p.status = SolveStatus::kInfeasible;
    p.message += "; the penetration limit is not met within the bounds";
  }
  p.evaluations = r.evaluations + evals + 1;
  OCCLUDE_ASSERT(p.X_LU.matrix().allFinite(), "a finished proposal's pose is finite");
  return p;
}

bool Tracker::OutOfTime() const {
  return request->max_seconds > 0.0 &&
         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
             request->max_seconds;
}

void Tracker::Done() {
  const int n = ++done;
  if (report) {
    std::lock_guard<std::mutex> lock(mutex);
    report(n, total);
  }
}

Candidates EachStart(const SearchContext& c, const std::vector<Vector6d>& starts,
                     Tracker* tracker) {
  const std::size_t last = c.schedule->size() - 1;
  std::vector<Proposal> all(starts.size());
  std::vector<char> ran(starts.size(), 0);
  tracker->total = static_cast<int>(starts.size());
  Candidates out;
  out.worker_cpu = ParallelFor(starts.size(), c.problem->request->num_threads, [&](std::size_t i) {
    if (i > 0 && tracker->OutOfTime()) {  // the start pose itself always runs
      ++tracker->skipped;
      return;
    }
    const double t0 = JobCpuSeconds();
    all[i] = Finish(c, static_cast<int>(i), SafeChain(c, starts[i], 0, last));
    all[i].cpu_seconds = JobCpuSeconds() - t0;
    ran[i] = 1;
    tracker->Done();
  });
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (!ran[i]) continue;
    out.evaluations += all[i].evaluations;
    out.proposals.push_back(std::move(all[i]));
  }
  return out;
}

namespace {

// The coarse runs of CoarseThenFine, per start.
struct CoarseRuns {
  std::vector<LocalResult> result;
  std::vector<double> cost, cpu;
  std::vector<char> ran;
};

CoarseRuns RunCoarse(const SearchContext& c, const std::vector<Vector6d>& starts, Tracker* tracker,
                     double* worker_cpu) {
  const Problem& problem = *c.problem;
  CoarseRuns runs;
  runs.result.resize(starts.size());
  runs.cost.resize(starts.size());
  runs.cpu.resize(starts.size());
  runs.ran.assign(starts.size(), 0);
  *worker_cpu += ParallelFor(starts.size(), problem.request->num_threads, [&](std::size_t i) {
    if (i > 0 && tracker->OutOfTime()) {  // the start pose itself always runs
      ++tracker->skipped;
      return;
    }
    const double t0 = JobCpuSeconds();
    runs.result[i] = SafeChain(c, starts[i], 0, 0);
    runs.cost[i] =
        EvaluateSet(c.schedule->front(), c.sets.front(), PoseOf(problem, runs.result[i].x), problem)
            .seat_cost;
    runs.cpu[i] = JobCpuSeconds() - t0;
    runs.ran[i] = 1;
    tracker->Done();
  });
  return runs;
}

// The runs that ran, by coarse seat cost (ties by start), keeping `count` distinct poses.
std::vector<std::size_t> BestDistinctCoarse(const SearchContext& c, const CoarseRuns& runs,
                                            std::size_t count) {
  const Problem& problem = *c.problem;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < runs.ran.size(); ++i) {
    if (runs.ran[i]) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return runs.cost[a] < runs.cost[b]; });
  std::vector<std::size_t> kept;
  for (const std::size_t i : order) {
    if (kept.size() >= count) break;
    bool distinct = true;
    for (const std::size_t k : kept) {
      distinct = distinct &&
                 DistinctPoses(PoseOf(problem, runs.result[i].x), PoseOf(problem, runs.result[k].x),
                               problem.ref_points_U, *problem.request);
    }
    if (distinct) kept.push_back(i);
  }
  return kept;
}

}  // namespace

Candidates CoarseThenFine(const SearchContext& c, const std::vector<Vector6d>& starts,
                          std::size_t refine_count, Tracker* tracker) {
  const std::size_t last = c.schedule->size() - 1;
  const std::size_t refine = std::min(starts.size(), std::max<std::size_t>(1, refine_count));
  tracker->total = static_cast<int>(starts.size() + refine);
  Candidates out;
  const CoarseRuns coarse = RunCoarse(c, starts, tracker, &out.worker_cpu);
  const std::vector<std::size_t> kept = BestDistinctCoarse(c, coarse, refine);
  for (std::size_t i = 0; i < starts.size(); ++i) {
    if (!coarse.ran[i]) continue;
    out.evaluations += coarse.result[i].evaluations;
    out.coarse_cpu += coarse.cpu[i];
  }
  tracker->total = static_cast<int>(
      starts.size() - static_cast<std::size_t>(tracker->skipped.load()) + kept.size());
  out.proposals.resize(kept.size());
  out.worker_cpu += ParallelFor(kept.size(), c.problem->request->num_threads, [&](std::size_t k) {
    const std::size_t i = kept[k];
    const double t0 = JobCpuSeconds();
    LocalResult fine = SafeChain(c, coarse.result[i].x, 1, last);
    if (fine.status == SolveStatus::kFailed)
      fine.message = coarse.result[i].message + "; " + fine.message;
    Proposal& p = out.proposals[k];
    p = Finish(c, static_cast<int>(i), fine);
    p.evaluations += coarse.result[i].evaluations;
    p.cpu_seconds = coarse.cpu[i] + JobCpuSeconds() - t0;
    tracker->Done();
  });
  for (std::size_t k = 0; k < kept.size(); ++k) {
    out.evaluations += out.proposals[k].evaluations - coarse.result[kept[k]].evaluations;
    out.fine_cpu += out.proposals[k].cpu_seconds - coarse.cpu[kept[k]];
  }
  return out;
}

std::vector<Proposal> BestDistinct(const std::vector<Proposal>& candidates, const Problem& problem,
                                   int max_count) {
  // Best first: feasible before infeasible, then the seat cost (the contact area at the limit
  // is a hair trigger: at one seat it varied 14-54 mm^2 with 0.08 mm of closure on a-bite, so it
  // does not rank seats), then position (deterministic).
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const Proposal &pa = candidates[a], &pb = candidates[b];
    if (pa.evaluation.feasible != pb.evaluation.feasible) return pa.evaluation.feasible;
    if (pa.evaluation.feasible) return pa.seat_cost < pb.seat_cost;
    return pa.evaluation.constrained_penetration_mm < pb.evaluation.constrained_penetration_mm;
  });
  std::vector<Proposal> best;
  for (const std::size_t i : order) {
    if (static_cast<int>(best.size()) >= max_count) break;
    bool distinct = true;
    for (const Proposal& q : best) {
      distinct = distinct &&
                 DistinctPoses(candidates[i].X_LU, q.X_LU, problem.ref_points_U, *problem.request);
    }
    if (distinct) best.push_back(candidates[i]);
  }
  return best;
}

}  // namespace occlude::planner::detail
