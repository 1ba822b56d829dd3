// GlobalSearch(): the request checked (arches facing, jaws not upside down),
// the arches aligned, the problem about the aligned pose with the lower's arch
// frame, the scan (global_scan.cpp), the basins through the coarse-to-fine
// chain (chain.cpp) and the distinct seats with their shifts; and SeatOf().
#include "occlude/planner/global_search.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "global_scan.h"
#include "occlude/assert.h"
#include "occlude/planner/least_squares.h"

namespace occlude::planner {

const char* ToString(GlobalRequest::Phase phase) {
  switch (phase) {
    case GlobalRequest::Phase::kScan:
      return "scan";
    case GlobalRequest::Phase::kBasins:
      return "basins";
    case GlobalRequest::Phase::kRefine:
      return "refine";
  }
  return "?";
}

void ValidateGlobalRequest(const GlobalRequest& r) {
  ValidateRequest(r.local);
  ValidateJawArches(r.lower_L, r.upper_U);
  detail::ValidateScanSettings(r.scan);
  ValidateSeatRanking(r.ranking);
  if (!(std::isfinite(r.alignment.overjet_mm) && std::isfinite(r.alignment.overbite_mm) &&
        r.alignment.overjet_mm >= 0.0 && r.alignment.overbite_mm >= 0.0 &&
        r.alignment.overjet_mm <= 10.0 && r.alignment.overbite_mm <= 10.0)) {
    throw std::invalid_argument(
        "GlobalRequest.alignment: overjet_mm and overbite_mm must be in [0, 10] mm (default 2)");
  }
}

namespace {

using detail::Vector6d;

// The jaw lies on the far side of its crowns: its vertices' centroid is behind its arch curve
// along occlusal_J (which points out of the crowns). Throws naming the jaw otherwise.
void CheckCrownsFaceOut(const io::TriangleMesh& jaw, const JawArch& arch, const char* name) {
  Eigen::Vector3d body = Eigen::Vector3d::Zero(), crowns = Eigen::Vector3d::Zero();
  for (const auto& v : jaw.vertices) body += v;
  for (const auto& p : arch.curve_J) crowns += p;
  body /= static_cast<double>(std::max<std::size_t>(1, jaw.vertices.size()));
  crowns /= static_cast<double>(arch.curve_J.size());
  if ((body - crowns).dot(arch.occlusal_J) >= 0.0) {
    throw std::invalid_argument(
        std::string(name) +
        " arch: occlusal_J points into the jaw (its mesh lies on the crowns' occlusal side): "
        "the jaw is upside down or occlusal_J is reversed; it must point out of the crowns");
  }
}

// The local request of the search: the aligned pose as the reference, bounds wide enough for
// the scan plus each refinement's own reach, one start, no budget or progress of its own.
PlanRequest SearchRequest(const GlobalRequest& g, const Eigen::Isometry3d& X_LU_aligned) {
  PlanRequest r = g.local;
  r.X_LU_start = X_LU_aligned;
  const double reach_mm = std::max(g.scan.sagittal_range_mm, g.scan.lateral_range_mm) +
                          g.scan.open_mm +
                          std::max(g.local.upper_bound.translation_mm.maxCoeff(),
                                   -g.local.lower_bound.translation_mm.minCoeff());
  const double reach_deg =
      std::min(90.0, std::max(g.scan.yaw_range_deg, g.scan.pitch_range_deg) +
                         std::max(g.local.upper_bound.rotation_deg.maxCoeff(),
                                  -g.local.lower_bound.rotation_deg.minCoeff()));
  r.lower_bound = {Eigen::Vector3d::Constant(-reach_mm), Eigen::Vector3d::Constant(-reach_deg)};
  r.upper_bound = {Eigen::Vector3d::Constant(reach_mm), Eigen::Vector3d::Constant(reach_deg)};
  r.locked = {};
  r.pivot_L.reset();
  r.num_starts = 1;
  r.num_global_samples = 0;
  r.polish = true;
  r.max_seconds = 0.0;
  r.on_progress = nullptr;
  return r;
}

// The basins through the local search: coarse stage for all, the best distinct refined (staged
// solvers on several stages), else the best basins through the whole chain.
detail::Candidates RefineBasins(const detail::SearchContext& c, const GlobalRequest& g,
                                const std::vector<Vector6d>& starts) {
  detail::Tracker tracker;
  tracker.request = c.problem->request;
  const int n = static_cast<int>(starts.size());
  if (g.on_progress) {
    tracker.report = [&g, n](int done, int total) {
      if (done <= n) {
        g.on_progress(GlobalRequest::Phase::kBasins, done, n);
      } else {
        g.on_progress(GlobalRequest::Phase::kRefine, done - n, total - n);
      }
    };
  }
  const SolverKind solver = g.local.solver;
  const bool staged = solver == SolverKind::kCoarseToFine || solver == SolverKind::kNloptGlobal;
  const auto refine = static_cast<std::size_t>(g.scan.max_refined);
  if (staged && c.schedule->size() > 1) return detail::CoarseThenFine(c, starts, refine, &tracker);
  const std::vector<Vector6d> best(
      starts.begin(), starts.begin() + static_cast<long>(std::min(refine, starts.size())));
  detail::Candidates out = detail::EachStart(c, best, &tracker);
  for (const Proposal& p : out.proposals) out.fine_cpu += p.cpu_seconds;
  return out;
}

// The seat cost of the last stage's samples with the jaws apart: every sample beyond the
// attraction window (the ceiling of Proposal::seat_cost without penetration).
double OpenSeatCost(const detail::SearchContext& c) {
  const OracleStage& last = c.schedule->back();
  const detail::SampleSet& samples = c.sets.back();
  const ResidualSettings seat = detail::SeatSettings(last, *c.problem->request);
  double cost = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    cost += SeatSampleCost(seat.window_mm, samples.area_mm2[i],
                           samples.facing[i] >= seat.attraction_min_facing, seat);
  }
  return cost;
}

// The distinct seats of the candidates (feasible first, best seat cost first) with their shifts.
std::vector<GlobalProposal> DistinctSeats(const detail::SearchContext& c, const GlobalRequest& g,
                                          const detail::Candidates& candidates,
                                          const Eigen::Isometry3d& X_aligned) {
  const detail::Problem& problem = *c.problem;
  const int all = static_cast<int>(candidates.proposals.size());
  const double open_cost = OpenSeatCost(c);
  std::vector<GlobalProposal> seats;
  for (Proposal& p : detail::BestDistinct(candidates.proposals, problem, all)) {
    GlobalProposal gp;
    gp.seat_depth = std::max(0.0, open_cost - p.seat_cost);
    gp.from_aligned = ShiftBetween(X_aligned, p.X_LU, problem.pivot_L, g.lower_L);
    gp.from_given = ShiftBetween(g.local.X_LU_start, p.X_LU, problem.pivot_L, g.lower_L);
    gp.basin = p.start_index;
    gp.proposal = std::move(p);
    seats.push_back(std::move(gp));
  }
  return seats;
}

// The seats ranked by the request's ranking, and the warnings they call for.
void Report(const detail::SearchContext& c, const GlobalRequest& g,
            const detail::Candidates& candidates, GlobalResult* result) {
  std::vector<GlobalProposal> seats = DistinctSeats(c, g, candidates, result->alignment.X_LU);
  RankedSeats ranked = RankSeats(std::move(seats), g.ranking, g.local.max_proposals);
  result->proposals = std::move(ranked.proposals);
  result->excluded = std::move(ranked.excluded);
  if (result->proposals.empty() && !result->excluded.empty()) {
    result->warnings.push_back(
        "every seat found breaks a hard clinical constraint (see the excluded seats): relax "
        "the constraints or widen the scan");
    return;
  }
  if (result->proposals.empty() || !result->proposals.front().proposal.evaluation.feasible) {
    result->warnings.push_back(
        "no seat meets the penetration limit: the arches may not belong together, or the "
        "scan's ranges miss their occlusion");
    return;
  }
  const double edge = g.scan.sagittal_range_mm - g.scan.sagittal_step_mm;
  const double s = result->proposals.front().from_aligned.sagittal_mm;
  if (g.scan.sagittal_range_mm > 0.0 && std::abs(s) > edge) {
    char w[200];
    std::snprintf(w, sizeof w,
                  "the best seat lies %.1f mm along the arch from the aligned pose, at the edge "
                  "of the scan (+-%.1f mm): widen scan.sagittal_range_mm",
                  s, g.scan.sagittal_range_mm);
    result->warnings.push_back(w);
  }
}

}  // namespace

GlobalResult GlobalSearch(const OracleSchedule& schedule, const GlobalRequest& request) {
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = detail::CpuSeconds();
  ValidateGlobalRequest(request);
  if (schedule.empty())
    throw std::invalid_argument("schedule: empty; give at least one OracleStage");
  for (const OracleStage& s : schedule) {
    if (s.oracle == nullptr) throw std::invalid_argument("schedule: an OracleStage has no oracle");
  }
  CheckCrownsFaceOut(schedule.back().oracle->lower_tree().mesh(), request.lower_L, "lower");
  CheckCrownsFaceOut(schedule.back().oracle->upper_tree().mesh(), request.upper_U, "upper");
  GlobalResult result;
  result.alignment = AlignArches(request.lower_L, request.upper_U, request.alignment);
  result.warnings = result.alignment.warnings;
  const PlanRequest local = SearchRequest(request, result.alignment.X_LU);
  const collision::ArchFrame frame = FrameOf(request.lower_L);
  const detail::Problem problem = detail::MakeProblem(schedule, local, &frame);
  const detail::SearchContext c = detail::MakeSearchContext(schedule, problem);
  result.pivot_L = problem.pivot_L;
  const detail::ScanOutcome scan = detail::Scan(c, request);
  result.scan_poses = static_cast<int>(scan.grid.size());
  result.scan_cpu_seconds = scan.cpu_seconds;
  std::vector<Vector6d> starts;
  for (const detail::ScanBasinPose& b : scan.basins) {
    result.basins.push_back(b.basin);
    starts.push_back(b.x);
  }
  const detail::Candidates candidates = RefineBasins(c, request, starts);
  result.basins_cpu_seconds = candidates.coarse_cpu;
  result.refine_cpu_seconds = candidates.fine_cpu;
  result.total_evaluations = scan.evaluations + candidates.evaluations;
  Report(c, request, candidates, &result);
  result.cpu_seconds =
      detail::CpuSeconds() - cpu0 + scan.worker_cpu_seconds + candidates.worker_cpu;
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

Proposal SeatOf(const OracleSchedule& schedule, const Eigen::Isometry3d& X_LU,
                const PlanRequest& settings) {
  PlanRequest r = settings;
  r.X_LU_start = X_LU;
  r.num_starts = 1;
  r.num_global_samples = 0;
  r.max_proposals = 1;
  const PlanResult result = Plan(schedule, r);
  OCCLUDE_ASSERT(!result.proposals.empty(), "one start gives one proposal");
  return result.proposals.front();
}

}  // namespace occlude::planner
