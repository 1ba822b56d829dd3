// ClosestPointOnTriangle and ClosestPointsSegmentSegment against dense sampling
// and analytic answers.
#include "occlude/collision/closest_point.h"

#include <gtest/gtest.h>

#include <random>

#include "test_common.h"

namespace occlude::collision {
namespace {

TEST(ClosestPointTest, AnalyticRegions) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_NEAR(ClosestPointOnTriangle({0.2, 0.2, 3}, a, b, c).squared_distance, 9.0, 1e-15);
  EXPECT_NEAR(ClosestPointOnTriangle({-1, -1, 0}, a, b, c).squared_distance, 2.0, 1e-15);
  EXPECT_NEAR(ClosestPointOnTriangle({0.5, -2, 0}, a, b, c).squared_distance, 4.0, 1e-15);
  EXPECT_NEAR(ClosestPointOnTriangle({1, 1, 0}, a, b, c).squared_distance, 0.5, 1e-15);
}

TEST(ClosestPointTest, NeverFartherThanSampledPoints) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-2, 2);
  std::uniform_real_distribution<double> w(0, 1);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)),
        c(u(rng), u(rng), u(rng)), p(u(rng), u(rng), u(rng));
    const TrianglePoint cp = ClosestPointOnTriangle(p, a, b, c);
    EXPECT_NEAR(cp.barycentric.sum(), 1.0, 1e-12);
    EXPECT_GE(cp.barycentric.minCoeff(), -1e-12);
    for (int s = 0; s < 200; ++s) {
      double x = w(rng), y = w(rng);
      if (x + y > 1) {
        x = 1 - x;
        y = 1 - y;
      }
      const Eigen::Vector3d q = a + x * (b - a) + y * (c - a);
      ASSERT_LE(cp.squared_distance, (p - q).squaredNorm() + 1e-12);
    }
  }
}

TEST(ClosestPointTest, DegenerateTriangleIsASegment) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(1, 0, 0);
  const TrianglePoint cp = ClosestPointOnTriangle({1.5, 1, 0}, a, b, c);
  EXPECT_NEAR(cp.squared_distance, 1.0, 1e-12);
}

TEST(ClosestPointTest, SegmentSegment) {
  double s = 0, t = 0;
  EXPECT_NEAR(ClosestPointsSegmentSegment({0, 0, 0}, {1, 0, 0}, {0.5, -1, 1}, {0.5, 1, 1}, &s, &t),
              1.0, 1e-15);
  EXPECT_NEAR(s, 0.5, 1e-15);
  EXPECT_NEAR(t, 0.5, 1e-15);
  // Parallel segments.
  EXPECT_NEAR(ClosestPointsSegmentSegment({0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 1, 0}, &s, &t), 2.0,
              1e-15);
}

}  // namespace
}  // namespace occlude::collision
