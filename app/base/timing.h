// Wall-clock timing helpers for the commands (benchmarks report medians, since
// the machines are shared and noisy).
#pragma once

#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

#include "occlude/clock.h"

namespace occlude::app {

// The clocks are occlude::ThreadCpuSeconds (thread CPU time: what a query costs) and
// occlude::WallSeconds (occlude/clock.h); NowSeconds is the wall clock under the app's name.
inline double NowSeconds() { return WallSeconds(); }

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
