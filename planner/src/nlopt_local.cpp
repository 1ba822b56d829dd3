// NLopt local search: maximize the smooth contact score of the sample set
// subject to the robust penetration measure <= limit, over the free DOFs
// (COBYLA, or the augmented Lagrangian around BOBYQA / Sbplx), keeping the
// best feasible point seen (COBYLA may end slightly outside the constraint).
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
  double score_scale = 1.0;
  int evaluations = 0;
  // Cache of the last evaluation (objective and constraint ask for the same point).
  std::vector<double> last_y;
  SetEvaluation last;
  // Best points.
  Vector6d best_feasible = Vector6d::Zero();
  double best_feasible_score = -std::numeric_limits<double>::infinity();
  Vector6d least_penetrating = Vector6d::Zero();
  double least_penetration = std::numeric_limits<double>::infinity();
};

double Scale(int dof) { return dof < 3 ? kTranslationScaleMm : kRotationScaleDeg; }

Vector6d ToX(const LocalState& s, const std::vector<double>& y) {
  Vector6d x = s.x0;
  for (std::size_t k = 0; k < s.free.size(); ++k) x[s.free[k]] = y[k] * Scale(s.free[k]);
  return x;
}

const SetEvaluation& Evaluate(LocalState& s, const std::vector<double>& y) {
  if (y == s.last_y) return s.last;
  const Vector6d x = ToX(s, y);
  ++s.evaluations;
  s.last_y = y;
  if (!Finite(x)) {
    s.last = SetEvaluation{};
    s.last.robust_penetration_mm = 1e3;
    return s.last;
  }
  s.last = EvaluateSet(*s.stage, *s.samples, PoseOf(*s.problem, x), *s.problem);
  if (s.last.feasible && s.last.smooth_score > s.best_feasible_score) {
    s.best_feasible_score = s.last.smooth_score;
    s.best_feasible = x;
  }
  if (s.last.robust_penetration_mm < s.least_penetration) {
    s.least_penetration = s.last.robust_penetration_mm;
    s.least_penetrating = x;
  }
  return s.last;
}

double Objective(const std::vector<double>& y, std::vector<double>& /*grad*/, void* data) {
  auto& s = *static_cast<LocalState*>(data);
  return -Evaluate(s, y).smooth_score / s.score_scale;
}

double Constraint(const std::vector<double>& y, std::vector<double>& /*grad*/, void* data) {
  auto& s = *static_cast<LocalState*>(data);
  const double limit = s.problem->request->max_penetration_mm;
  return (Evaluate(s, y).robust_penetration_mm - limit) / 0.05;
}

nlopt::opt MakeOptimizer(NloptLocalMethod method, unsigned n, int max_evaluations) {
  if (method == NloptLocalMethod::kCobyla) {
    nlopt::opt opt(nlopt::LN_COBYLA, n);
    opt.set_maxeval(max_evaluations);
    return opt;
  }
  nlopt::opt opt(nlopt::AUGLAG, n);
  nlopt::opt local(method == NloptLocalMethod::kAuglagBobyqa ? nlopt::LN_BOBYQA : nlopt::LN_SBPLX, n);
  local.set_xtol_abs(1e-3);
  local.set_ftol_rel(1e-6);
  local.set_maxeval(std::max(20, max_evaluations / 4));
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
  const SetEvaluation& start = Evaluate(s, y);
  s.score_scale = std::max(1.0, start.smooth_score);
  nlopt::opt opt = MakeOptimizer(problem.request->nlopt_local, n, max_evaluations);
  opt.set_lower_bounds(lb);
  opt.set_upper_bounds(ub);
  opt.set_initial_step(step);
  opt.set_xtol_abs(1e-3);
  opt.set_ftol_rel(1e-7);
  opt.set_min_objective(Objective, &s);
  opt.add_inequality_constraint(Constraint, &s, 1e-3);
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
  result.evaluations = s.evaluations;
  if (std::isfinite(s.best_feasible_score)) {
    result.x = s.best_feasible;
  } else {
    result.x = s.least_penetrating;
    result.status = SolveStatus::kInfeasible;
    result.message += "; no feasible point seen";
  }
  return result;
}

}  // namespace occlude::planner::detail
