// The Ceres model's analytic Jacobian against central differences of its own
// residuals, at the bite and away from the reference (rotation vector not 0); the
// solver's residual memo against the model itself.
#include "occlude/planner/least_squares.h"

#include <gtest/gtest.h>

#include <cstring>

#include "least_squares_internal.h"
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

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool SameBits(const Row6d& a, const Row6d& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 6) == 0;
}

// The memo serves each sample's residuals at a point from one computation; whatever the order
// of the questions (cost-only then with Jacobians, points revisited, samples out of order) its
// answers are the model's own, bit for bit.
TEST(LeastSquaresTest, ResidualMemoAnswersBitIdenticallyToTheModel) {
  const auto& c = test::Synthetic();
  const OracleStage& stage = c.schedule.stages.back();
  const Eigen::Isometry3d base = Eigen::Translation3d(-0.05 * c.pair.occlusal_axis_L) * c.pair.X_LU;
  const SurfaceResiduals model(stage, base, base, c.pivot_L, ResidualSettings{}, 400);
  const SurfaceResiduals::Impl& impl = model.impl();
  ASSERT_GT(impl.area.size(), 50u);
  Vector6d a = Vector6d::Zero(), b;
  b << 0.03, -0.02, 0.05, 0.004, -0.006, 0.002;  // mm, rad
  struct Question {
    const Vector6d* z;
    bool jacobians;
  };
  const Question questions[] = {{&a, false}, {&a, true}, {&b, true}, {&a, true}, {&b, false}};
  detail::ResidualMemo memo(impl);
  int nonzero = 0;
  for (const Question& q : questions) {
    const SurfaceResiduals::Impl::PoseAt pose(*q.z);
    for (std::size_t k = 0; k < impl.area.size(); ++k) {
      const std::size_t i = (k * 7) % impl.area.size();  // out of order, every sample once
      for (int repeat = 0; repeat < 2; ++repeat) {       // the hinge block, then the attraction
        const detail::ResidualMemo::Sample& got = memo.At(i, q.z->data(), q.jacobians);
        double hinge = 0.0, attraction = 0.0;
        Row6d jh, ja;
        impl.Residuals(i, pose, &hinge, &attraction, &jh, &ja);
        ASSERT_TRUE(SameBits(got.hinge, hinge)) << "sample " << i;
        ASSERT_TRUE(SameBits(got.attraction, attraction)) << "sample " << i;
        if (q.jacobians) {
          ASSERT_TRUE(SameBits(got.j_hinge, jh)) << "sample " << i;
          ASSERT_TRUE(SameBits(got.j_attraction, ja)) << "sample " << i;
        }
        nonzero += (hinge != 0.0 || attraction != 0.0) ? 1 : 0;
      }
    }
  }
  EXPECT_GT(nonzero, 50);  // the samples seat: the comparison is not of zeros only
}

}  // namespace
}  // namespace occlude::planner
