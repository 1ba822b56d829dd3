// The build's thread helpers (collision/src/parallel.h): every item runs exactly once on a
// worker below the count, the lowest-numbered failure is the one rethrown, and thread counts
// resolve as documented.
#include "parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace occlude::collision::detail {
namespace {

TEST(ParallelTest, EveryItemRunsOnceOnAWorkerBelowTheCount) {
  for (const int threads : {1, 2, 3, 5}) {
    for (const std::size_t count :
         {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{100}}) {
      std::vector<std::atomic<int>> runs(count);
      std::atomic<bool> worker_in_range{true};
      ParallelFor(count, threads, [&](std::size_t item, int worker) {
        runs[item].fetch_add(1);
        if (worker < 0 || worker >= threads) worker_in_range = false;
      });
      for (std::size_t i = 0; i < count; ++i)
        EXPECT_EQ(runs[i].load(), 1) << "item " << i << ", " << threads << " threads";
      EXPECT_TRUE(worker_in_range.load());
    }
  }
}

TEST(ParallelTest, TheLowestNumberedFailureIsRethrown) {
  for (const int threads : {1, 2, 4}) {
    try {
      ParallelFor(50, threads, [](std::size_t item, int) {
        if (item == 9 || item == 3 || item == 30) throw std::runtime_error(std::to_string(item));
      });
      FAIL() << "nothing thrown";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "3") << threads << " threads";
    }
  }
}

TEST(ParallelTest, RunConcurrentlyRunsEveryTask) {
  std::atomic<int> sum{0};
  std::vector<std::function<void()>> tasks;
  for (int i = 1; i <= 5; ++i) tasks.push_back([&sum, i] { sum += i; });
  RunConcurrently(2, tasks);
  EXPECT_EQ(sum.load(), 15);
}

TEST(ParallelTest, ThreadCountsResolve) {
  EXPECT_GE(ResolveThreads(0), 1);
  EXPECT_EQ(ResolveThreads(3), 3);
  EXPECT_THROW(ResolveThreads(-1), std::invalid_argument);
}

}  // namespace
}  // namespace occlude::collision::detail
