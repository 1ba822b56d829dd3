// The threads a job of ParallelFor may spread its own loops over. ParallelFor (search_internal.h)
// hands each of its workers the threads the workers leave idle, so one start alone (refine, or
// the one seat a coarse-to-fine search refines) gets every thread and many starts get one each;
// outside any ParallelFor a thread has one. ForBlocks runs a loop of independent items on them.
//
// Determinism: ForBlocks' items write only their own slots, so a loop's results are the same
// for any thread count; callers then combine them in item order on the calling thread.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace occlude::planner::detail {

/// Thread CPU time in seconds.
double CpuSeconds();

/// What the calling thread may use for its own loops.
struct InnerBudget {
  int threads = 1;          ///< the calling thread and its helpers
  double helper_cpu = 0.0;  ///< CPU seconds its ForBlocks helpers have spent, summed
};

/// The calling thread's budget (thread-local; ParallelFor sets it for its workers).
InnerBudget& CurrentInnerBudget();

/// Gives the calling thread the budget of `threads` threads (no helper CPU yet) for its life,
/// then the budget it had (also when an exception unwinds it).
class InnerBudgetScope {
 public:
  explicit InnerBudgetScope(int threads) : outer_(CurrentInnerBudget()) {
    CurrentInnerBudget() = {threads, 0.0};
  }
  ~InnerBudgetScope() { CurrentInnerBudget() = outer_; }
  InnerBudgetScope(const InnerBudgetScope&) = delete;
  InnerBudgetScope& operator=(const InnerBudgetScope&) = delete;

 private:
  InnerBudget outer_;
};

/// CPU seconds of the calling thread and of its ForBlocks helpers so far (differences of it
/// time a job).
inline double JobCpuSeconds() { return CpuSeconds() + CurrentInnerBudget().helper_cpu; }

/// Calls body(begin, end) over [0, n) in consecutive blocks of `block` items, on up to
/// CurrentInnerBudget().threads threads (the caller among them); the helpers' CPU is added to
/// the budget. body must only write what belongs to its items. An exception from body stops
/// the blocks not yet started and is rethrown on the caller once every thread has stopped (the
/// first block's that failed, by block number).
template <typename Body>
void ForBlocks(std::size_t n, std::size_t block, Body body) {
  block = std::max<std::size_t>(1, block);
  const std::size_t blocks = (n + block - 1) / block;
  InnerBudget& budget = CurrentInnerBudget();
  const int threads =
      static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(budget.threads), blocks));
  if (threads <= 1) {
    if (n > 0) body(std::size_t{0}, n);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> failed(blocks);
  const auto run = [&] {
    for (std::size_t b = next++; b < blocks; b = next++) {
      try {
        body(b * block, std::min(n, (b + 1) * block));
      } catch (...) {
        failed[b] = std::current_exception();
        next = blocks;  // no new block starts
      }
    }
  };
  std::vector<double> cpu(static_cast<std::size_t>(threads - 1), 0.0);
  std::vector<std::thread> helpers;
  helpers.reserve(cpu.size());
  for (std::size_t h = 0; h < cpu.size(); ++h) {
    helpers.emplace_back([&, h] {
      const double t0 = CpuSeconds();
      run();
      cpu[h] = CpuSeconds() - t0;
    });
  }
  run();
  for (auto& t : helpers) t.join();
  for (const double c : cpu) budget.helper_cpu += c;
  for (const std::exception_ptr& e : failed) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace occlude::planner::detail
