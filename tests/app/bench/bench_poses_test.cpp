// The poses `occlude bench` replays: the jittered sweep is seeded, jittered within its bounds
// and the same for every method; the haptic trajectory descends into the bite and then slides
// at the contact height.
#include <gtest/gtest.h>

#include "bench/bench_poses_internal.h"
#include "occlude/angles.h"
#include "occlude/io/synthetic_jaws.h"
#include "test_common.h"

namespace occlude::test {
namespace {

app::BenchCase SyntheticCase() {
  app::BenchCase bc{app::SyntheticJawPair(5000, io::SyntheticJawOptions{}.seed)};
  bc.axis_L = *bc.occlusal_axis_L;
  return bc;
}

TEST(BenchPosesTest, SweepPosesAreSeededAndJitteredWithinBounds) {
  const app::BenchCase bc = SyntheticCase();
  const std::vector<double> offsets = {2.0, 0.0, -0.2};
  const auto a = app::SweepPoses(bc, offsets, 20, 0.2, 0.05, 7);
  const auto b = app::SweepPoses(bc, offsets, 20, 0.2, 0.05, 7);
  const auto c = app::SweepPoses(bc, offsets, 20, 0.2, 0.05, 8);
  ASSERT_EQ(a.size(), offsets.size());
  const Eigen::Vector3d pivot_L = app::SweepPivotL(bc);
  for (std::size_t k = 0; k < offsets.size(); ++k) {
    ASSERT_EQ(a[k].size(), 20u);
    const Eigen::Isometry3d exact = Eigen::Translation3d(offsets[k] * bc.axis_L) * bc.X_LU_ref;
    EXPECT_TRUE(a[k][0].isApprox(exact, 1e-12));
    for (std::size_t r = 0; r < 20; ++r) {
      EXPECT_TRUE(a[k][r].isApprox(b[k][r], 0.0));
      const Eigen::Isometry3d delta = a[k][r] * exact.inverse();  // jitter, in L
      const double angle_deg = DegreesFromRadians(Eigen::AngleAxisd(delta.linear()).angle());
      EXPECT_LE(angle_deg, 0.2 + 1e-9);
      // The centroid moves across the axis by the translation jitter only.
      const Eigen::Vector3d moved =
          delta * (pivot_L + offsets[k] * bc.axis_L) - (pivot_L + offsets[k] * bc.axis_L);
      EXPECT_LE(moved.norm(), 0.05 + 1e-9);
      EXPECT_NEAR(moved.dot(bc.axis_L), 0.0, 1e-9);
      if (r > 0) {
        EXPECT_FALSE(a[k][r].isApprox(c[k][r], 1e-12));
      }
    }
  }
}

TEST(BenchPosesTest, HapticTrajectoryDescendsThenSlidesAtTheContactHeight) {
  const app::BenchCase bc = SyntheticCase();
  int calls = 0;
  const app::HapticTrajectory trajectory(bc, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(),
                                         2.0, 3, [&](const Eigen::Isometry3d&) {
                                           ++calls;
                                           return 0.05;
                                         });
  EXPECT_EQ(calls, 48);
  const Eigen::Vector3d c0 = app::SweepPivotL(bc);
  auto height = [&](double t) {
    return (trajectory.At(t) * bc.X_LU_ref.inverse() * c0 - c0).dot(bc.axis_L);
  };
  EXPECT_NEAR(height(0.0), 2.0, 1e-9);
  EXPECT_NEAR(height(0.5), 0.05, 1e-6);
  EXPECT_NEAR(height(1.7), 0.05, 0.01);  // the wobble tilts about the pivot: no lift there
  // Continuous: at a 1 ms tick no point of the jaw jumps by more than 10 um.
  double worst = 0.0;
  for (double t = 0.0; t < 2.0; t += 1e-3) {
    const Eigen::Isometry3d step = trajectory.At(t + 1e-3) * trajectory.At(t).inverse();
    for (const auto& v : bc.upper_U->vertices) {
      const Eigen::Vector3d p = trajectory.At(t) * v;
      worst = std::max(worst, (step * p - p).norm());
      break;
    }
  }
  EXPECT_LT(worst, 0.01);
  // And it slides: lateral motion of at least 0.2 mm in the sliding phase.
  double lateral_min = 1e9, lateral_max = -1e9;
  for (double t = 0.5; t <= 2.0; t += 0.01) {
    const double x = (trajectory.At(t) * bc.X_LU_ref.inverse() * c0 - c0).x();
    lateral_min = std::min(lateral_min, x);
    lateral_max = std::max(lateral_max, x);
  }
  EXPECT_GT(lateral_max - lateral_min, 0.2);
}

}  // namespace
}  // namespace occlude::test
