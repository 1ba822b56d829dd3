// The threads a ParallelFor job may use for its own loops (planner/src/inner_threads.h): each
// worker gets the threads the workers leave idle, ForBlocks covers every item once in blocks
// fixed by the count alone, and its helpers' CPU reaches the enclosing ParallelFor's total.
#include "inner_threads.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "search_internal.h"

namespace occlude::planner::detail {
namespace {

TEST(InnerThreadsTest, OutsideAnyParallelForAThreadHasOne) {
  EXPECT_EQ(CurrentInnerBudget().threads, 1);
}

TEST(InnerThreadsTest, WorkersGetTheThreadsTheyLeaveIdle) {
  // (jobs, threads) -> the budget each job sees.
  for (const auto& [jobs, threads, expected] : std::vector<std::tuple<std::size_t, int, int>>{
           {1, 2, 2}, {1, 4, 4}, {2, 2, 1}, {3, 2, 1}, {2, 4, 2}, {5, 1, 1}}) {
    std::vector<int> seen(jobs, 0);
    ParallelFor(jobs, threads, [&](std::size_t i) { seen[i] = CurrentInnerBudget().threads; });
    for (std::size_t i = 0; i < jobs; ++i)
      EXPECT_EQ(seen[i], expected) << jobs << " jobs on " << threads << " threads";
  }
  EXPECT_EQ(CurrentInnerBudget().threads, 1);  // restored on the calling thread
}

TEST(InnerThreadsTest, ForBlocksCoversEveryItemOnceInFixedBlocks) {
  for (const int threads : {1, 2, 3}) {
    for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{511}, std::size_t{512},
                                std::size_t{513}, std::size_t{5000}}) {
      std::vector<int> hits(n, 0);
      std::set<std::pair<std::size_t, std::size_t>> blocks;
      std::mutex mutex;
      ParallelFor(1, threads, [&](std::size_t) {
        ForBlocks(n, 512, [&](std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) ++hits[i];
          const std::lock_guard<std::mutex> lock(mutex);
          blocks.emplace(begin, end);
        });
      });
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(hits[i], 1) << n << " items, item " << i;
      if (threads > 1) {
        // Blocks of 512 from 0 whatever the thread count (one block of everything when serial).
        for (const auto& [begin, end] : blocks) {
          EXPECT_EQ(begin % 512, 0u);
          EXPECT_EQ(end, std::min(n, begin + 512));
        }
      }
    }
  }
}

// A failing block reaches the caller as its exception, on one thread or two; no thread is left
// running and the caller's budget is restored.
TEST(InnerThreadsTest, ForBlocksRethrowsAFailureOnTheCaller) {
  for (const int threads : {1, 2}) {
    std::atomic<int> ran{0};
    try {
      ParallelFor(1, threads, [&](std::size_t) {
        ForBlocks(4096, 64, [&](std::size_t begin, std::size_t end) {
          ++ran;
          if (begin <= 320 && 320 < end) throw std::runtime_error("item 320");
        });
      });
      ADD_FAILURE() << "no exception on " << threads << " thread(s)";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "item 320");
    }
    EXPECT_GE(ran.load(), 1);
    EXPECT_EQ(CurrentInnerBudget().threads, 1);
  }
}

// A failing job of several on two workers reaches the caller (no thread left joinable, which
// would end the process), and the jobs after it do not start.
TEST(InnerThreadsTest, ParallelForRethrowsAJobsFailureOnTheCaller) {
  std::atomic<int> ran{0};
  EXPECT_THROW(ParallelFor(1000, 2,
                           [&](std::size_t i) {
                             ++ran;
                             if (i == 3) throw std::runtime_error("job 3");
                           }),
               std::runtime_error);
  EXPECT_LT(ran.load(), 1000);
  EXPECT_EQ(CurrentInnerBudget().threads, 1);
}

TEST(InnerThreadsTest, HelpersCpuCountsInTheParallelForTotal) {
  // One job on two threads: its ForBlocks runs two blocks, one on the caller and one on a
  // helper (each waits until both have started), each burning 20 ms of CPU; the helper's is
  // not on the caller's clock, so ParallelFor returns it.
  std::atomic<int> started{0};
  std::atomic<double> sink{0.0};
  const double others = ParallelFor(1, 2, [&](std::size_t) {
    ForBlocks(2, 1, [&](std::size_t begin, std::size_t) {
      ++started;
      while (started.load() < 2) std::this_thread::yield();
      const double t0 = CpuSeconds();
      double x = static_cast<double>(begin);
      while (CpuSeconds() - t0 < 0.02) x = x * 1.0000001 + 1e-9;
      sink = sink + x;
    });
  });
  EXPECT_GT(others, 0.015);
  EXPECT_EQ(CurrentInnerBudget().helper_cpu, 0.0);  // restored: nothing left over
}

}  // namespace
}  // namespace occlude::planner::detail
