// Pose parameterization: round trips and the pivot's meaning.
#include "occlude/planner/pose.h"

#include <gtest/gtest.h>

#include <random>

#include "occlude/angles.h"

namespace occlude::planner {
namespace {

TEST(PoseTest, RotationAboutPivotKeepsPivotFixed) {
  const Eigen::Vector3d pivot(10, -3, 25);
  PoseParameters params;
  params.rotation_deg = Eigen::Vector3d(0, 30, 0);
  const Eigen::Isometry3d X = ComposePose(params, pivot, Eigen::Isometry3d::Identity());
  EXPECT_LT((X * pivot - pivot).norm(), 1e-12);
  // A point 10 mm from the pivot along x swings on a 10 mm circle by 30 degrees.
  const Eigen::Vector3d q = pivot + Eigen::Vector3d(10, 0, 0);
  EXPECT_NEAR((X * q - q).norm(), 2 * 10 * std::sin(RadiansFromDegrees(15.0)), 1e-12);
}

TEST(PoseTest, ComposeDecomposeRoundTrip) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i) {
    PoseParameters p;
    p.translation_mm = 5 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    p.rotation_deg = 60 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const Eigen::Vector3d pivot = 30 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    Eigen::Isometry3d ref = Eigen::Isometry3d::Identity();
    ref.linear() = RotationFromVectorDeg(Eigen::Vector3d(10 * u(rng), 10 * u(rng), 0));
    ref.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
    const PoseParameters back = DecomposePose(ComposePose(p, pivot, ref), pivot, ref);
    EXPECT_LT((back.translation_mm - p.translation_mm).norm(), 1e-9) << i;
    EXPECT_LT((back.rotation_deg - p.rotation_deg).norm(), 1e-7) << i;
  }
}

TEST(PoseTest, ZeroParametersGiveReference) {
  Eigen::Isometry3d ref = Eigen::Isometry3d::Identity();
  ref.translation() = Eigen::Vector3d(1, 2, 3);
  const Eigen::Isometry3d X = ComposePose(PoseParameters{}, Eigen::Vector3d(4, 5, 6), ref);
  EXPECT_TRUE(X.isApprox(ref, 1e-15));
}

}  // namespace
}  // namespace occlude::planner
