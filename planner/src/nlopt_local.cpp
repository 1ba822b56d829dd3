// NLopt local search: minimize the seat cost of the sample set (the same
// objective as the Ceres residuals: robust attraction of all gaps within the
// seat window plus the penetration penalty) over the free DOFs subject to the
// penetration excess <= 0 (see Constraint): COBYLA with the constraint, or the
// augmented Lagrangian around BOBYQA (default) / Sbplx; then settle the best
// point along the occlusal axis on the outlier-robust measure.
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlopt.hpp>
#include <vector>

#include "search_internal.h"

namespace occlude::planner::detail {
namespace {

constexpr double kTranslationScaleMm = 1.0;  // one optimizer unit
constexpr double kRotationScaleDeg = 2.0;    // ~0.9 mm at a 25 mm lever

struct LocalState {
  const OracleStage* stage = nullptr;
  const SampleSet* samples = nullptr;
  const Problem* problem = nullptr;
  std::vector<int> free;           // indices of free DOFs
  Vector6d x0 = Vector6d::Zero();  // values of the locked DOFs
  double cost_scale = 1.0;
  int evaluations = 0;
  Vector6d best = Vector6d::Zero();
  double best_cost = std::numeric_limits<double>::infinity();
  std::vector<double> cache_y;
  SetEvaluation cache;
  bool have_cache = false;
};

double Scale(int dof) { return dof < 3 ? kTranslationScaleMm : kRotationScaleDeg; }

Vector6d ToX(const LocalState& s, const std::vector<double>& y) {
  Vector6d x = s.x0;
  for (std::size_t k = 0; k < s.free.size(); ++k) x[s.free[k]] = y[k] * Scale(s.free[k]);
  return x;
}

// The set evaluation at y (objective and constraint ask for the same point: cached).
const SetEvaluation& At(LocalState& s, const std::vector<double>& y) {
  if (s.have_cache && y == s.cache_y) return s.cache;
  const Vector6d x = ToX(s, y);
  ++s.evaluations;
  s.cache_y = y;
  s.have_cache = true;
  if (!Finite(x)) {
    s.cache = SetEvaluation{};
    s.cache.seat_cost = std::numeric_limits<double>::max();
    s.cache.robust_penetration_mm = std::numeric_limits<double>::max();
    return s.cache;
  }
  s.cache = EvaluateSet(*s.stage, *s.samples, PoseOf(*s.problem, x), *s.problem);
  // Best point: the lowest seat cost (its penalty already weighs the penetration; preferring
  // feasible points would prefer jaws held open). The final settle makes it feasible.
  if (s.cache.seat_cost < s.best_cost) {
    s.best_cost = s.cache.seat_cost;
    s.best = x;
  }
  return s.cache;
}

double Objective(const std::vector<double>& y, std::vector<double>& /*grad*/, void* data) {
  auto& s = *static_cast<LocalState*>(data);
  return At(s, y).seat_cost / s.cost_scale;
}

// Inequality constraint: the smooth penetration excess (RMS depth beyond the limit, mm) <= 0.
// (The outlier-robust maximum itself is a hair trigger, flat then jumping: measured on the
// synthetic pair, COBYLA and AUGLAG stopped 1-1.4 mm short with it; the final settle applies it.)
double Constraint(const std::vector<double>& y, std::vector<double>& /*grad*/, void* data) {
  auto& s = *static_cast<LocalState*>(data);
  return At(s, y).excess_rms_mm;
}

// COBYLA takes the constraint itself; BOBYQA and Sbplx (unconstrained) run inside the
// augmented Lagrangian (AUGLAG), which adds the constraint's multiplier to their objective.
nlopt::opt MakeOptimizer(NloptLocalMethod method, unsigned n, int max_evaluations) {
  if (method == NloptLocalMethod::kCobyla) {
    nlopt::opt opt(nlopt::LN_COBYLA, n);
    opt.set_maxeval(max_evaluations);
    return opt;
  }
  nlopt::opt opt(nlopt::AUGLAG, n);
  nlopt::opt local(method == NloptLocalMethod::kAuglagBobyqa ? nlopt::LN_BOBYQA : nlopt::LN_SBPLX,
                   n);
  local.set_xtol_abs(3e-3);
  local.set_ftol_rel(1e-5);
  opt.set_local_optimizer(local);
  opt.set_maxeval(max_evaluations);
  return opt;
}

}  // namespace

LocalResult NloptLocal(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                       const Vector6d& x0, int max_evaluations) {
  LocalState s;
  s.stage = &stage;
  s.samples = &samples;
  s.problem = &problem;
  s.x0 = x0;
  for (int i = 0; i < kNumDof; ++i) {
    if (problem.upper[i] > problem.lower[i]) s.free.push_back(i);
  }
  LocalResult result;
  result.x = x0;
  if (s.free.empty()) {
    result.status = SolveStatus::kConverged;
    result.message = "all DOFs locked";
    return result;
  }
  const auto n = static_cast<unsigned>(s.free.size());
  std::vector<double> y(n), lb(n), ub(n), step(n);
  for (unsigned k = 0; k < n; ++k) {
    const int i = s.free[k];
    lb[k] = problem.lower[i] / Scale(i);
    ub[k] = problem.upper[i] / Scale(i);
    y[k] = std::clamp(x0[i] / Scale(i), lb[k], ub[k]);
    step[k] = 0.3;
  }
  s.cost_scale = std::max(1e-6, At(s, y).seat_cost);
  // Two rounds: the second restarts from the best point with a third of the step (COBYLA's
  // trust region only shrinks, and a restart often leaves a premature stop).
  for (int round = 0; round < 2 && s.evaluations < max_evaluations; ++round) {
    nlopt::opt opt =
        MakeOptimizer(problem.request->nlopt_local, n, max_evaluations - s.evaluations);
    opt.set_lower_bounds(lb);
    opt.set_upper_bounds(ub);
    std::vector<double> round_step = step;
    for (double& v : round_step) v /= round == 0 ? 1.0 : 3.0;
    opt.set_initial_step(round_step);
    opt.set_xtol_abs(3e-3);  // 3 um / 0.006 deg
    opt.set_ftol_rel(1e-5);
    opt.set_min_objective(Objective, &s);
    opt.add_inequality_constraint(Constraint, &s, 1e-4);
    if (round > 0) {
      for (unsigned k = 0; k < n; ++k)
        y[k] = std::clamp(s.best[s.free[k]] / Scale(s.free[k]), lb[k], ub[k]);
    }
    double f = 0.0;
    try {
      const nlopt::result r = opt.optimize(y, f);
      result.status =
          r == nlopt::MAXEVAL_REACHED ? SolveStatus::kMaxEvaluations : SolveStatus::kConverged;
      result.message = std::string("nlopt ") + ToString(problem.request->nlopt_local) +
                       ": result " + std::to_string(static_cast<int>(r));
    } catch (const nlopt::roundoff_limited&) {
      result.status = SolveStatus::kConverged;
      result.message = "nlopt: roundoff limited";
    } catch (const std::exception& e) {
      result.status = SolveStatus::kFailed;
      result.message = std::string("nlopt failed: ") + e.what();
      break;
    }
  }
  // Seat the best point along the occlusal axis on the penetration measure.
  int settle_evals = 0;
  result.x = SettleOnSet(stage, samples, problem, s.best, &settle_evals);
  result.evaluations = s.evaluations + settle_evals;
  if (!EvaluateSet(stage, samples, PoseOf(problem, result.x), problem).feasible) {
    result.status = SolveStatus::kInfeasible;
    result.message += "; no feasible point within the bounds";
  }
  return result;
}

}  // namespace occlude::planner::detail
