// The growth fits of `occlude bench --paper`: a power law and a line are recovered exactly
// from exact data, and non-positive values are left out. (The command's figures:
// tests/app/cli/cmd_bench_test.cpp.)
#include "bench/bench_paper.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace occlude::test {
namespace {

TEST(PowerFitTest, RecoversTheExponentOfAPowerLaw) {
  const std::vector<double> s = {0.1, 0.2, 0.4, 0.8, 1.0};
  std::vector<double> y;
  for (const double v : s) y.push_back(3.0 * std::pow(v, -2.0));
  const app::PowerFit fit = app::FitPowerLaw(s, y, "test");
  EXPECT_NEAR(fit.exponent, -2.0, 1e-12);
  EXPECT_NEAR(fit.r2, 1.0, 1e-12);
  EXPECT_EQ(fit.points, 5u);
  // Non-positive values are left out, not fitted.
  const app::PowerFit partial = app::FitPowerLaw({1.0, 2.0, 0.0}, {1.0, 8.0, 5.0}, "cube");
  EXPECT_NEAR(partial.exponent, 3.0, 1e-12);
  EXPECT_EQ(partial.points, 2u);
}

TEST(AffineFitTest, RecoversInterceptAndSlopeOfALine) {
  const app::AffineFit fit = app::FitAffine({1, 2, 4, 8}, {5, 7, 11, 19}, "line");
  EXPECT_NEAR(fit.intercept, 3.0, 1e-12);
  EXPECT_NEAR(fit.slope, 2.0, 1e-12);
  EXPECT_NEAR(fit.r2, 1.0, 1e-12);
}

}  // namespace
}  // namespace occlude::test
