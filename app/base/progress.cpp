// Progress lines and bars on stderr (see progress.h).
#include "base/progress.h"

#include <iomanip>
#include <iostream>
#include <sstream>

#include "base/timing.h"

namespace occlude::app {

void StepClock::Start(const std::string& step) {
  Finish();
  step_ = step;
  t0_ = NowSeconds();
}

void StepClock::Finish() {
  if (!step_.empty() && NowSeconds() - t0_ > 1.0) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(2) << "occlude: " << step_ << " (" << NowSeconds() - t0_
      << " s)\n";
    std::cerr << s.str() << std::flush;
  }
  step_.clear();
}

ProgressBar::ProgressBar(std::string task) : task_(std::move(task)), t0_(NowSeconds()) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::cerr << "\n" << std::flush;
}

void ProgressBar::Update(int done, int total) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (NowSeconds() - t0_ < 1.0 && done < total) return;
  if (!drawn_ && done >= total && NowSeconds() - t0_ < 1.0) return;  // finished quickly: no bar
  constexpr int kWidth = 30;
  const int filled = total > 0 ? kWidth * done / total : kWidth;
  std::ostringstream s;
  s << "\rocclude: " << task_ << " [" << std::string(static_cast<std::size_t>(filled), '#')
    << std::string(static_cast<std::size_t>(kWidth - filled), '.') << "] " << done << "/" << total
    << " (" << std::fixed << std::setprecision(1) << NowSeconds() - t0_ << " s)";
  std::cerr << s.str() << std::flush;
  drawn_ = true;
}

}  // namespace occlude::app
