// The Ceres model's analytic Jacobian against central differences of its own
// residuals, at the bite and away from the reference (rotation vector not 0).
#include "occlude/planner/least_squares.h"

#include <gtest/gtest.h>

#include "planner_fixture.h"

namespace occlude::planner {
namespace {

// Central differences of trilinear distances with steps of 1e-4 mm / deg: the difference is
// exact away from voxel faces and hinge kinks; rows that cross one are skipped by comparing
// against both one-sided differences.
constexpr double kStep = 1e-4;
constexpr double kJacobianTolerance = 2e-3;  // per mm or per deg, relative to a unit gradient

void CheckJacobian(const SurfaceResiduals& model, const PoseParameters& at) {
  ASSERT_GT(model.size(), 10);
  Eigen::VectorXd r0;
  Eigen::MatrixXd J;
  model.Evaluate(at, &r0, &J);
  ASSERT_TRUE(J.allFinite());
  int checked = 0, nonzero = 0;
  for (int k = 0; k < 6; ++k) {
    PoseParameters plus = at, minus = at;
    if (k < 3) {
      plus.translation_mm[k] += kStep;
      minus.translation_mm[k] -= kStep;
    } else {
      plus.rotation_deg[k - 3] += kStep;
      minus.rotation_deg[k - 3] -= kStep;
    }
    Eigen::VectorXd rp, rm;
    model.Evaluate(plus, &rp);
    model.Evaluate(minus, &rm);
    for (Eigen::Index i = 0; i < r0.size(); ++i) {
      const double fwd = (rp[i] - r0[i]) / kStep, bwd = (r0[i] - rm[i]) / kStep;
      if (std::abs(fwd - bwd) > kJacobianTolerance)
        continue;  // a kink or voxel face inside the step
      ++checked;
      if (std::abs(J(i, k)) > 1e-6) ++nonzero;
      EXPECT_NEAR(J(i, k), 0.5 * (fwd + bwd), kJacobianTolerance)
          << "residual " << i << " dof " << k;
    }
  }
  EXPECT_GT(checked, 6 * model.size() / 2);
  EXPECT_GT(nonzero, 20);
}

TEST(LeastSquaresTest, AnalyticJacobianMatchesNumericAtTheBite) {
  const auto& c = test::Synthetic();
  const OracleStage& stage = c.schedule.stages.back();
  Eigen::Isometry3d base = Eigen::Translation3d(-0.05 * c.pair.occlusal_axis_L) * c.pair.X_LU;
  const SurfaceResiduals model(stage, base, base, c.pivot_L, ResidualSettings{}, 400);
  CheckJacobian(model, PoseParameters{});
}

TEST(LeastSquaresTest, AnalyticJacobianMatchesNumericAwayFromReference) {
  const auto& c = test::Synthetic();
  const OracleStage& stage = c.schedule.stages.back();
  PoseParameters offset;
  offset.translation_mm = Eigen::Vector3d(0.4, -0.3, 0.2);
  offset.rotation_deg = Eigen::Vector3d(1.5, -2.0, 1.0);
  // Reference displaced so that the bite is reached at non-zero parameters.
  const Eigen::Isometry3d bite = Eigen::Translation3d(-0.05 * c.pair.occlusal_axis_L) * c.pair.X_LU;
  const Eigen::Isometry3d X_ref =
      ComposePose(offset, c.pivot_L, Eigen::Isometry3d::Identity()).inverse() * bite;
  const Eigen::Vector3d pivot_ref = c.pivot_L;
  const SurfaceResiduals model(stage, bite, X_ref, pivot_ref, ResidualSettings{}, 400);
  const PoseParameters at = DecomposePose(bite, pivot_ref, X_ref);
  CheckJacobian(model, at);
}

}  // namespace
}  // namespace occlude::planner
