// The nearest-rank percentile the benchmark and validation summaries use.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace occlude::app {

/// Nearest-rank percentile of values already sorted in increasing order, q in (0, 1]: the
/// smallest value with at least a share q of the sample at or below it (q = 0.5: the lower
/// median; q = 1: the maximum); `if_empty` for an empty sample. No copy: several percentiles of
/// one sample sort it once.
inline double NearestRankOfSorted(const std::vector<double>& sorted, double q, double if_empty) {
  if (sorted.empty()) return if_empty;
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::min(sorted.size(), std::max<std::size_t>(rank, 1)) - 1];
}

/// The same of values in any order.
inline double NearestRankPercentile(std::vector<double> values, double q, double if_empty) {
  std::sort(values.begin(), values.end());
  return NearestRankOfSorted(values, q, if_empty);
}

}  // namespace occlude::app
