// OCCLUDE_ASSERT: aborts with the file, condition and message when its invariant fails (in
// builds without NDEBUG, as CI's sanitizer lane), and is not evaluated in Release.
#include "occlude/assert.h"

#include <gtest/gtest.h>

namespace {

TEST(AssertTest, HoldingInvariantDoesNothing) {
  int evaluated = 0;
  OCCLUDE_ASSERT(++evaluated == 1, "counts once");
#ifdef NDEBUG
  EXPECT_EQ(evaluated, 0);  // compiled out: the condition is not evaluated
#else
  EXPECT_EQ(evaluated, 1);
#endif
}

#ifndef NDEBUG
TEST(AssertDeathTest, FailedInvariantAbortsNamingConditionAndMessage) {
  const int nodes = 3;
  EXPECT_DEATH(OCCLUDE_ASSERT(nodes == 4, "a full octree node has four children"),
               "internal error: .*assert_test.cpp:[0-9]+: assertion `nodes == 4` failed: a full "
               "octree node has four children");
}
#endif

}  // namespace
