// Progress on stderr for the steps of a command: each finished step that took over a
// second is reported with its duration, and long loops (the planner's starts) draw a
// bar that redraws in place.
#pragma once

#include <mutex>
#include <string>

namespace occlude::app {

/// Reports each finished step that took over a second ("occlude: <step> (2.31 s)").
class StepClock {
 public:
  void Start(const std::string& step);
  void Finish();
  ~StepClock() { Finish(); }

 private:
  std::string step_;
  double t0_ = 0.0;
};

/// A one-line progress bar on stderr ("occlude: search [######....] 6/16"), drawn only once the
/// task has run for a second; thread-safe.
class ProgressBar {
 public:
  explicit ProgressBar(std::string task);
  ~ProgressBar();
  void Update(int done, int total);

 private:
  std::string task_;
  double t0_ = 0.0;
  bool drawn_ = false;
  std::mutex mutex_;
};

}  // namespace occlude::app
