// The haptic loop's attribution of a missed deadline (app/bench/bench.h, UnstalledDone): a miss
// the unstalled schedule meets is a wall-clock stall of the machine; one it misses too is the
// query's, its own CPU time or the backlog of the queries before it.
#include <gtest/gtest.h>

#include "bench/bench.h"

namespace occlude::app {
namespace {

constexpr double kPeriod = 1e-3;  // 1 kHz

double Release(int k) { return 10.0 + k * kPeriod; }

TEST(HapticMissTest, AQueryShorterThanThePeriodMeetsEveryUnstalledDeadline) {
  // 0.4 ms per query: each unstalled answer 0.4 ms after its release, whatever a stall did.
  double done = Release(0);
  for (int k = 0; k < 5; ++k) {
    done = app::UnstalledDone(done, Release(k), 0.4e-3);
    EXPECT_NEAR(done, Release(k) + 0.4e-3, 1e-12) << k;
    EXPECT_LE(done, Release(k) + kPeriod) << k;
  }
}

TEST(HapticMissTest, AQueryLongerThanThePeriodAndItsBacklogAreTheQuerys) {
  // One 1.8 ms query misses its own deadline, and the 0.3 ms one after it, started 0.8 ms late,
  // misses its deadline too (its backlog); the next one, started 0.1 ms late, meets its own.
  double done = app::UnstalledDone(Release(0), Release(0), 1.8e-3);
  EXPECT_GT(done, Release(0) + kPeriod);
  done = app::UnstalledDone(done, Release(1), 0.3e-3);
  EXPECT_NEAR(done, Release(0) + 2.1e-3, 1e-12);
  EXPECT_GT(done, Release(1) + kPeriod);
  done = app::UnstalledDone(done, Release(2), 0.3e-3);
  EXPECT_NEAR(done, Release(2) + 0.4e-3, 1e-12);
  EXPECT_LE(done, Release(2) + kPeriod);
}

}  // namespace
}  // namespace occlude::app
