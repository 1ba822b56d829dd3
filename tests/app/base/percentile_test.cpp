// The nearest-rank percentile (base/percentile.h) against its definition: the smallest value with
// at least a share q of the sample at or below it, by counting, on random samples with ties
// (fixed seed); the sorted variant gives the same on the sorted sample; the edges.
#include "base/percentile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace occlude::app {
namespace {

// The definition, by brute force: the smallest value v of the sample with count(x <= v) >= q * n.
double PercentileByCounting(const std::vector<double>& values, double q) {
  double best = 0.0;
  bool found = false;
  for (const double v : values) {
    const auto at_or_below =
        std::count_if(values.begin(), values.end(), [&](double x) { return x <= v; });
    if (static_cast<double>(at_or_below) >= q * static_cast<double>(values.size()) &&
        (!found || v < best)) {
      best = v;
      found = true;
    }
  }
  return best;
}

TEST(NearestRankPercentile, IsTheSmallestValueWithAShareQAtOrBelowIt) {
  std::mt19937 rng(23);
  std::uniform_int_distribution<int> size(1, 40), value(0, 12);  // small range: many ties
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<double> sample(static_cast<std::size_t>(size(rng)));
    for (double& v : sample) v = value(rng);
    std::vector<double> sorted = sample;
    std::sort(sorted.begin(), sorted.end());
    for (const double q : {0.01, 0.25, 0.5, 0.9, 0.99, 0.999, 1.0}) {
      const double expected = PercentileByCounting(sample, q);
      EXPECT_EQ(NearestRankPercentile(sample, q, -1.0), expected)
          << "trial " << trial << " q " << q;
      EXPECT_EQ(NearestRankOfSorted(sorted, q, -1.0), expected) << "trial " << trial << " q " << q;
    }
  }
}

TEST(NearestRankPercentile, EmptySampleGivesTheFallbackAndQOneTheMaximum) {
  EXPECT_EQ(NearestRankPercentile({}, 0.5, 7.0), 7.0);
  EXPECT_EQ(NearestRankOfSorted({}, 0.5, 7.0), 7.0);
  EXPECT_EQ(NearestRankPercentile({3.0, 1.0, 2.0}, 1.0, 0.0), 3.0);
  EXPECT_EQ(NearestRankPercentile({3.0, 1.0, 2.0}, 0.5, 0.0), 2.0);
  EXPECT_EQ(NearestRankPercentile({4.0, 1.0, 3.0, 2.0}, 0.5, 0.0), 2.0);  // the lower median
}

}  // namespace
}  // namespace occlude::app
