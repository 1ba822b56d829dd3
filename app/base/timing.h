// Wall-clock timing helpers for the commands (benchmarks report medians, since
// the machines are shared and noisy).
#pragma once

#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

namespace occlude::app {

/// CPU time of the calling thread, seconds: what a query costs, independent of
/// how many other jobs share the machine's cores (wall time is not).
inline double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

inline double NowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Median and maximum of a sample (sorted in place); zeros for an empty sample.
struct Summary {
  double median = 0.0;
  double max = 0.0;
};
inline Summary Summarize(std::vector<double>* sample) {
  if (sample->empty()) return {};
  std::sort(sample->begin(), sample->end());
  return {(*sample)[sample->size() / 2], sample->back()};
}

/// Runs f() `reps` times and returns median and max microseconds of thread CPU
/// time per call (the machines are shared: wall time measures the neighbours).
template <class F>
Summary TimeMicros(F&& f, int reps) {
  std::vector<double> us;
  us.reserve(static_cast<std::size_t>(reps));
  for (int i = 0; i < reps; ++i) {
    const double t0 = ThreadCpuSeconds();
    f();
    us.push_back(1e6 * (ThreadCpuSeconds() - t0));
  }
  return Summarize(&us);
}

}  // namespace occlude::app
