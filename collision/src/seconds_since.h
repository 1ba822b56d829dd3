// Wall seconds since a steady-clock time point, for the build statistics.
#pragma once

#include <chrono>

namespace occlude::collision::detail {

inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace occlude::collision::detail
