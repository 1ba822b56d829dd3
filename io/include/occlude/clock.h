// The clocks of the project, defined once: thread CPU time (what a query or a search costs,
// independent of how many other jobs share the cores) and wall time (what a user waits for).
// In io because io is the bottom of the dependency chain: every target sees it.
#pragma once

#include <chrono>
#include <ctime>

namespace occlude {

/// CPU time of the calling thread, seconds.
inline double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Monotonic wall time, seconds (from an arbitrary origin: take differences).
inline double WallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace occlude
