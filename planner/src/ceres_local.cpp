// Ceres solver: least squares on the samples' signed distances (the seat
// objective of least_squares.h: Huber penetration hinge beyond a small
// allowance + Cauchy-robust attraction of every gap within the seat window,
// Chang et al. 2010) with analytic Jacobians, on
// a pose manifold whose update is a rigid motion about the pivot applied on
// the left (translation, then rotation vector). An outer loop re-collects the
// samples near the lower surface and settles the pose on the constraint; a
// round is kept only when it lowers the seat cost of the settled pose (else
// its half step, else the rounds stop): the rounds' least-squares optimum is
// not that cost's, and unguarded they wander along flat seats.
#include <ceres/ceres.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "least_squares_internal.h"

namespace occlude::planner::detail {
namespace {

Eigen::Vector3d Log(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.axis() * aa.angle();
}

// Ambient z = (t mm, w rad) as in pose.h (relative to the reference, about the pivot).
// Plus(z, delta): the rigid motion [translate delta_t] * [rotate Exp(delta_w) about the pivot]
// applied on the left: t' = delta_t + Exp(delta_w) t, R' = Exp(delta_w) R(w).
class PivotPoseManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 6; }
  int TangentSize() const override { return 6; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    const Eigen::Map<const Vector6d> z(x), d(delta);
    Eigen::Map<Vector6d> out(x_plus_delta);
    const Eigen::Matrix3d E = Exp(d.tail<3>());
    out.head<3>() = d.head<3>() + E * z.head<3>();
    out.tail<3>() = Log(E * Exp(z.tail<3>()));
    return true;
  }
  bool PlusJacobian(const double* x, double* jacobian) const override {
    const Eigen::Map<const Vector6d> z(x);
    Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> J(jacobian);
    J.setZero();
    J.topLeftCorner<3, 3>().setIdentity();
    J.topRightCorner<3, 3>() = -Hat(z.head<3>());
    J.bottomRightCorner<3, 3>() = LeftJacobianInverse(z.tail<3>());
    return true;
  }
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    const Eigen::Map<const Vector6d> zy(y), zx(x);
    Eigen::Map<Vector6d> out(y_minus_x);
    const Eigen::Matrix3d E = Exp(zy.tail<3>()) * Exp(zx.tail<3>()).transpose();
    out.tail<3>() = Log(E);
    out.head<3>() = zy.head<3>() - E * zx.head<3>();
    return true;
  }
  bool MinusJacobian(const double* x, double* jacobian) const override {
    const Eigen::Map<const Vector6d> z(x);
    Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> J(jacobian);
    const Eigen::Matrix3d Jl = LeftJacobian(z.tail<3>());
    J.setZero();
    J.topLeftCorner<3, 3>().setIdentity();
    J.topRightCorner<3, 3>() = Hat(z.head<3>()) * Jl;
    J.bottomRightCorner<3, 3>() = Jl;
    return true;
  }
};

// One residual of one sample: the hinge (kind 0) or the attraction (kind 1), through the round's
// memo (a sample's two blocks share one distance, every block one rotation).
class SampleCost final : public ceres::SizedCostFunction<1, 6> {
 public:
  SampleCost(ResidualMemo* memo, std::size_t sample, int kind)
      : memo_(memo), sample_(sample), kind_(kind) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const bool want = jacobians != nullptr && jacobians[0] != nullptr;
    const ResidualMemo::Sample& s = memo_->At(sample_, parameters[0], want);
    residuals[0] = kind_ == 0 ? s.hinge : s.attraction;
    if (want) {
      Eigen::Map<Row6d> jacobian(jacobians[0]);
      jacobian = kind_ == 0 ? s.j_hinge : s.j_attraction;
    }
    return true;
  }

 private:
  ResidualMemo* memo_;
  std::size_t sample_;
  int kind_;
};

// Closure along the occlusal axis u, as a nearly constant force: r = c (u . t + L) with a long
// lever L, so r^2 ~ c^2 L^2 + 2 c^2 L (u . t): the jaw is pushed closed with force 2 c^2 L
// (the deepest seat wins among poses of similar contact).
class ClosureCost final : public ceres::SizedCostFunction<1, 6> {
 public:
  ClosureCost(const Eigen::Vector3d& u, double force)
      : u_(u), c_(std::sqrt(force / (2.0 * kLeverMm))) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::Map<const Vector6d> z(parameters[0]);
    residuals[0] = c_ * (u_.dot(z.head<3>()) + kLeverMm);
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<Row6d> jacobian(jacobians[0]);
      jacobian << c_ * u_.transpose(), 0.0, 0.0, 0.0;
    }
    return true;
  }

 private:
  static constexpr double kLeverMm = 100.0;
  Eigen::Vector3d u_;
  double c_;
};

// The free DOFs' complement: indices whose bounds are equal (locked).
std::vector<int> LockedDofs(const Problem& problem) {
  std::vector<int> locked;
  for (int i = 0; i < kNumDof; ++i) {
    if (problem.upper[i] <= problem.lower[i]) locked.push_back(i);
  }
  return locked;
}

// The least-squares problem of one round on the ambient parameters z: a hinge and an
// attraction residual per sample of `model`, the optional closure, the manifold and the bounds.
void AddSeatProblem(const SurfaceResiduals::Impl& model, ResidualMemo* memo,
                    const ResidualSettings& settings, const Problem& problem,
                    const std::vector<int>& locked, Vector6d* z, ceres::Problem* lsq) {
  for (std::size_t i = 0; i < model.area.size(); ++i) {
    lsq->AddResidualBlock(
        new SampleCost(memo, i, 0),
        new ceres::HuberLoss(settings.penetration_weight * std::sqrt(model.area[i]) *
                             settings.penetration_huber_mm),
        z->data());
    lsq->AddResidualBlock(
        new SampleCost(memo, i, 1),
        new ceres::CauchyLoss(settings.attraction_scale_mm * std::sqrt(model.area[i])), z->data());
  }
  if (settings.closure_weight > 0.0 && problem.settle_dir.squaredNorm() > 0.0) {
    double total_area = 0.0;
    for (const double a : model.area) total_area += a;
    lsq->AddResidualBlock(new ClosureCost(problem.settle_dir, settings.closure_weight * total_area),
                          nullptr, z->data());
  }
  if (!locked.empty()) {
    lsq->SetManifold(z->data(), new ceres::SubsetManifold(6, locked));
  } else {
    lsq->SetManifold(z->data(), new PivotPoseManifold);
  }
  const Vector6d lo = AmbientFromX(problem.lower), hi = AmbientFromX(problem.upper);
  for (int i = 0; i < kNumDof; ++i) {
    if (problem.upper[i] > problem.lower[i]) {
      lsq->SetParameterLowerBound(z->data(), i, lo[i]);
      lsq->SetParameterUpperBound(z->data(), i, hi[i]);
    }
  }
}

ceres::Solver::Options RoundOptions() {
  ceres::Solver::Options opts;
  opts.linear_solver_type = ceres::DENSE_QR;
  opts.max_num_iterations = 25;
  opts.num_threads = 1;
  opts.function_tolerance = 1e-7;
  opts.parameter_tolerance = 1e-7;
  opts.logging_type = ceres::SILENT;
  return opts;
}

// One round of solve and settle from *x: the samples near the lower at *x, Ceres on them, the
// clamped result settled along the occlusal axis. Updates *x, the result's evaluations and
// message; returns false (with the result's status and message set) when the round failed.
bool SolveAndSettle(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                    const ResidualSettings& settings, const std::vector<int>& locked, Vector6d* x,
                    LocalResult* result) {
  const Eigen::Isometry3d X_base = PoseOf(problem, *x);
  const std::vector<bool> spikes = SpikeSamples(stage, samples, X_base, problem);
  const SurfaceResiduals::Impl model(stage, samples, X_base, problem.X_ref, problem.pivot_L,
                                     settings, 4000, &spikes);
  if (model.area.empty()) {
    result->status = SolveStatus::kFailed;  // nothing within reach to seat on
    result->message = "ceres: no samples within " + std::to_string(settings.range_mm) + " mm";
    return false;
  }
  ceres::Problem::Options popts;
  ceres::Problem lsq(popts);
  Vector6d z = AmbientFromX(*x);
  ResidualMemo memo(model);
  AddSeatProblem(model, &memo, settings, problem, locked, &z, &lsq);
  ceres::Solver::Summary summary;
  ceres::Solve(RoundOptions(), &lsq, &summary);
  result->evaluations += summary.num_residual_evaluations;
  if (!z.allFinite() || summary.termination_type == ceres::FAILURE) {
    result->status = SolveStatus::kFailed;
    result->message = "ceres: " + summary.message;
    return false;
  }
  const Vector6d moved = Clamp(problem, XFromAmbient(z));
  int settle_evals = 0;
  *x = SettleOnSet(stage, samples, problem, moved, &settle_evals);
  result->evaluations += settle_evals;
  result->message = "ceres: " + summary.BriefReport();
  return true;
}

// The seat cost of the set at a settled pose x (settled poses are compared on it: each sits at
// the penetration limit), counted as one evaluation.
double SettledCost(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                   const Vector6d& x, LocalResult* result) {
  ++result->evaluations;
  return EvaluateSet(stage, samples, PoseOf(problem, x), problem).seat_cost;
}

}  // namespace

// The rounds of solve-and-settle stop when a round moves no parameter by more than this
// (mm for translations, degrees for rotations).
constexpr double kOuterTolerance = 0.005;

LocalResult CeresLocal(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                       const Vector6d& x0, int max_outer, int max_evaluations) {
  const ResidualSettings settings = SeatSettings(stage, *problem.request);
  LocalResult result;
  result.x = x0;
  result.status = SolveStatus::kMaxIterations;
  const std::vector<int> locked = LockedDofs(problem);
  if (locked.size() == static_cast<std::size_t>(kNumDof)) {
    result.status = SolveStatus::kConverged;
    result.message = "all DOFs locked";
    return result;
  }
  Vector6d x = x0;
  double cost = std::numeric_limits<double>::infinity();  // of x once a round has settled it
  double change = 0.0;
  int rounds = 0;
  for (int outer = 0; outer < max_outer; ++outer) {
    if (result.evaluations >= max_evaluations) {
      result.status = SolveStatus::kMaxEvaluations;
      break;
    }
    ++rounds;
    Vector6d trial = x;
    if (!SolveAndSettle(stage, samples, problem, settings, locked, &trial, &result)) break;
    double trial_cost = SettledCost(stage, samples, problem, trial, &result);
    if (!(trial_cost < cost)) {
      const Vector6d half = SettleOnSet(stage, samples, problem,
                                        Clamp(problem, x + 0.5 * (trial - x)), &result.evaluations);
      const double half_cost = SettledCost(stage, samples, problem, half, &result);
      if (!(half_cost < cost)) {
        result.status = SolveStatus::kConverged;
        result.message += "; no further descent of the settled seat cost";
        break;
      }
      trial = half;
      trial_cost = half_cost;
    }
    change = (trial - x).cwiseAbs().maxCoeff();
    x = trial;
    cost = trial_cost;
    if (change < kOuterTolerance) {
      result.status = SolveStatus::kConverged;
      break;
    }
  }
  if (result.status == SolveStatus::kMaxIterations ||
      result.status == SolveStatus::kMaxEvaluations) {
    char last[160];
    std::snprintf(last, sizeof last,
                  "; %d rounds of solve and settle, the last moved the pose by %.4f (mm or deg; "
                  "tolerance %.3f)",
                  rounds, change, kOuterTolerance);
    result.message += last;
  }
  result.x = x;
  return result;
}

}  // namespace occlude::planner::detail
