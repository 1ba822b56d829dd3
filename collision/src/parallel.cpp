// ParallelFor and RunConcurrently on std::thread: workers claim item numbers from one atomic
// counter; the lowest-numbered failure is rethrown after every worker has joined.
#include "parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>

namespace occlude::collision::detail {
namespace {

// The first failure by item number, kept across workers.
class FirstFailure {
 public:
  void Record(std::size_t item, std::exception_ptr error) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (item < item_) {
      item_ = item;
      error_ = std::move(error);
    }
    failed_.store(true, std::memory_order_relaxed);
  }
  bool failed() const { return failed_.load(std::memory_order_relaxed); }
  void RethrowIfAny() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::mutex mutex_;
  std::size_t item_ = std::numeric_limits<std::size_t>::max();
  std::exception_ptr error_;
  std::atomic<bool> failed_{false};
};

}  // namespace

int ResolveThreads(int requested) {
  if (requested < 0) {
    throw std::invalid_argument("thread count must be >= 0 (0 = every core), got " +
                                std::to_string(requested));
  }
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

void ParallelFor(std::size_t count, int threads,
                 const std::function<void(std::size_t item, int worker)>& body) {
  if (count == 0) return;
  const int workers = static_cast<int>(
      std::min<std::size_t>(count, static_cast<std::size_t>(std::max(1, threads))));
  std::atomic<std::size_t> next{0};
  FirstFailure failure;
  auto work = [&](int worker) {
    for (std::size_t item; !failure.failed() && (item = next.fetch_add(1)) < count;) {
      try {
        body(item, worker);
      } catch (...) {
        failure.Record(item, std::current_exception());
      }
    }
  };
  std::vector<std::thread> helpers;
  helpers.reserve(static_cast<std::size_t>(workers - 1));
  for (int w = 1; w < workers; ++w) {
    try {
      helpers.emplace_back(work, w);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the workers running share the items
    }
  }
  work(0);
  for (std::thread& t : helpers) t.join();
  failure.RethrowIfAny();
}

void RunConcurrently(int threads, const std::vector<std::function<void()>>& tasks) {
  ParallelFor(tasks.size(), threads, [&](std::size_t item, int) { tasks[item](); });
}

}  // namespace occlude::collision::detail
