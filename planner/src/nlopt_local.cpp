// NLopt local search: minimize the seat cost of the sample set (the same
// objective as the Ceres residuals: robust attraction of all gaps within the
// seat window plus the penetration penalty) over the free DOFs with COBYLA,
// BOBYQA or Sbplx, then settle the best point along the occlusal axis.
#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
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
  std::vector<int> free;  // indices of free DOFs
  Vector6d x0 = Vector6d::Zero();  // values of the locked DOFs
  double cost_scale = 1.0;
  int evaluations = 0;
  Vector6d best = Vector6d::Zero();
  double best_cost = std::numeric_limits<double>::infinity();
};

double Scale(int dof) { return dof < 3 ? kTranslationScaleMm : kRotationScaleDeg; }

Vector6d ToX(const LocalState& s, const std::vector<double>& y) {
  Vector6d x = s.x0;
  for (std::size_t k = 0; k < s.free.size(); ++k) x[s.free[k]] = y[k] * Scale(s.free[k]);
  return x;
}

double Cost(LocalState& s, const std::vector<double>& y) {
  const Vector6d x = ToX(s, y);
  ++s.evaluations;
  if (!Finite(x)) return std::numeric_limits<double>::max();
  const double cost = EvaluateSet(*s.stage, *s.samples, PoseOf(*s.problem, x), *s.problem).seat_cost;
  if (cost < s.best_cost) {
    s.best_cost = cost;
    s.best = x;
  }
  return cost;
}

double Objective(const std::vector<double>& y, std::vector<double>& /*grad*/, void* data) {
  auto& s = *static_cast<LocalState*>(data);
  return Cost(s, y) / s.cost_scale;
}

nlopt::opt MakeOptimizer(NloptLocalMethod method, unsigned n, int max_evaluations) {
  // The penetration is a penalty of the seat cost (no constraint), so the AUGLAG variants
  // reduce to their subsidiary methods.
  const nlopt::algorithm a = method == NloptLocalMethod::kCobyla        ? nlopt::LN_COBYLA
                             : method == NloptLocalMethod::kAuglagBobyqa ? nlopt::LN_BOBYQA
                                                                         : nlopt::LN_SBPLX;
  nlopt::opt opt(a, n);
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
  s.cost_scale = std::max(1e-6, Cost(s, y));
  nlopt::opt opt = MakeOptimizer(problem.request->nlopt_local, n, max_evaluations);
  opt.set_lower_bounds(lb);
  opt.set_upper_bounds(ub);
  opt.set_initial_step(step);
  opt.set_xtol_abs(3e-3);  // 3 um / 0.006 deg
  opt.set_ftol_rel(1e-5);
  opt.set_min_objective(Objective, &s);
  double f = 0.0;
  try {
    const nlopt::result r = opt.optimize(y, f);
    result.status = r == nlopt::MAXEVAL_REACHED ? SolveStatus::kMaxEvaluations : SolveStatus::kConverged;
    result.message = std::string("nlopt ") + ToString(problem.request->nlopt_local) + ": result " + std::to_string(static_cast<int>(r));
  } catch (const nlopt::roundoff_limited&) {
    result.status = SolveStatus::kConverged;
    result.message = "nlopt: roundoff limited";
  } catch (const std::exception& e) {
    result.status = SolveStatus::kFailed;
    result.message = std::string("nlopt failed: ") + e.what();
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
