// floor() of a double to an int by truncation, for the grids' hot index computations (libm's
// floor is a call, or a long emulation without SSE4.1, on the baseline x86-64 target).
#pragma once

#include <cstdint>

namespace occlude::collision::detail {

/// floor(x) for |x| < 2^31 (the same value as std::floor; no libm call).
inline int FloorInt(double x) {
  const int t = static_cast<int>(x);  // truncation towards zero
  return t - (x < static_cast<double>(t) ? 1 : 0);
}

/// floor(x) for |x| < 2^63 (the same value as std::floor; no libm call).
inline std::int64_t FloorInt64(double x) {
  const auto t = static_cast<std::int64_t>(x);  // truncation towards zero
  return t - (x < static_cast<double>(t) ? 1 : 0);
}

}  // namespace occlude::collision::detail
