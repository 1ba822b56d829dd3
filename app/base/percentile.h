// The nearest-rank percentile the benchmark and validation summaries use.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace occlude::app {

/// Nearest-rank percentile, q in (0, 1]: the smallest value with at least a
/// share q of the sample at or below it (q = 0.5: the lower median; q = 1: the
/// maximum); `if_empty` for an empty sample.
inline double NearestRankPercentile(std::vector<double> values, double q, double if_empty) {
  if (values.empty()) return if_empty;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  return values[std::min(values.size(), std::max<std::size_t>(rank, 1)) - 1];
}

}  // namespace occlude::app
