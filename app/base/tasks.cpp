// RunTasks (tasks.h): workers claim task numbers from one atomic counter.
#include "base/tasks.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>

namespace occlude::app {

void RunTasks(const std::vector<std::function<void()>>& tasks, int threads) {
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> failed(tasks.size());
  auto worker = [&] {
    for (std::size_t i = next++; i < tasks.size(); i = next++) {
      try {
        tasks[i]();
      } catch (...) {
        failed[i] = std::current_exception();
      }
    }
  };
  const auto helpers = static_cast<std::size_t>(std::max(1, threads) - 1);
  std::vector<std::thread> pool;
  for (std::size_t k = 0; k < std::min(helpers, tasks.size()); ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : failed) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace occlude::app
