// RunTasks (base/tasks.h): every task runs once whatever the thread count, and the first failed
// task's exception (by position) comes back after all have run.
#include "base/tasks.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

namespace occlude::app {
namespace {

TEST(RunTasksTest, EveryTaskRunsOnceOnAnyNumberOfThreads) {
  for (const int threads : {1, 2, 4, 16}) {
    std::vector<std::atomic<int>> runs(9);
    std::vector<std::function<void()>> tasks;
    for (std::size_t i = 0; i < runs.size(); ++i) tasks.push_back([&runs, i] { ++runs[i]; });
    RunTasks(tasks, threads);
    for (std::size_t i = 0; i < runs.size(); ++i)
      EXPECT_EQ(runs[i].load(), 1) << threads << " " << i;
  }
  RunTasks({}, 2);  // nothing to do
}

TEST(RunTasksTest, RethrowsTheFirstFailureByPositionAfterAllRan) {
  std::atomic<int> ran{0};
  const std::vector<std::function<void()>> tasks = {[&] { ++ran; },
                                                    [&] {
                                                      ++ran;
                                                      throw std::runtime_error("second");
                                                    },
                                                    [&] { ++ran; },
                                                    [&] {
                                                      ++ran;
                                                      throw std::runtime_error("fourth");
                                                    }};
  try {
    RunTasks(tasks, 2);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "second");
  }
  EXPECT_EQ(ran.load(), 4);
}

}  // namespace
}  // namespace occlude::app
