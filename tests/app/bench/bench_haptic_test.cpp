// The haptic loop's attribution of a missed deadline (app/bench/bench.h, MissIsAStall): a miss
// the thread's time off the CPU explains is the machine's, one it does not is the query's.
#include <gtest/gtest.h>

#include "bench/bench.h"

namespace occlude::app {
namespace {

constexpr double kPeriod = 1e-3;  // 1 kHz
constexpr double kRelease = 10.0;

TEST(HapticMissTest, AStallThatExplainsTheLatenessIsTheMachines) {
  // Answered 1.6 ms after release with 0.9 ms off the CPU: 0.7 ms of its own, in time.
  EXPECT_TRUE(app::MissIsAStall(kRelease, kPeriod, kRelease + 1.6e-3, 0.9e-3));
  // Exactly at the deadline once the stall is taken off.
  EXPECT_TRUE(app::MissIsAStall(kRelease, kPeriod, kRelease + 1.5e-3, 0.5e-3));
}

TEST(HapticMissTest, AQuerySlowerThanThePeriodIsTheQuerysEvenWithAStall) {
  // 1.6 ms late with only 0.2 ms off the CPU: 1.4 ms of its own.
  EXPECT_FALSE(app::MissIsAStall(kRelease, kPeriod, kRelease + 1.6e-3, 0.2e-3));
  // No time off the CPU at all.
  EXPECT_FALSE(app::MissIsAStall(kRelease, kPeriod, kRelease + 1.01e-3, 0.0));
}

}  // namespace
}  // namespace occlude::app
