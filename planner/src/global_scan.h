// The global search's scan (internal): the grid of arch shifts about the
// aligned pose, each pose settled along the occlusal axis on the coarse stage
// and scored by the seat cost of a sparse sample set, and the grid's local
// optima (the basins), best first.
#pragma once

#include <vector>

#include "occlude/planner/global_search.h"
#include "search_internal.h"

namespace occlude::planner::detail {

/// Throws std::invalid_argument naming the first invalid field of the scan settings.
void ValidateScanSettings(const GlobalScanSettings& s);

/// The values k * step, |k * step| <= range (one value 0 for a zero range or a step over it).
std::vector<double> ScanAxis(double range, double step);

/// The grid: per pose its indices along (sagittal, lateral, yaw, pitch) and the shift.
struct ScanGrid {
  std::vector<double> sagittal, lateral, yaw, pitch;
  std::size_t size() const { return sagittal.size() * lateral.size() * yaw.size() * pitch.size(); }
  /// The shift of pose `index` (sagittal fastest-varying last: index = ((s L + l) Y + y) P + p).
  ArchShift Shift(std::size_t index) const;
  /// Indices of the grid's axis neighbours of `index` (up to 8).
  std::vector<std::size_t> Neighbours(std::size_t index) const;
};

struct ScanBasinPose {
  ScanBasin basin;
  Vector6d x = Vector6d::Zero();  ///< the settled grid pose (problem parameters)
};

struct ScanOutcome {
  ScanGrid grid;
  std::vector<ScanBasinPose> basins;  ///< local optima, lowest seat cost first, at most max_basins
  int evaluations = 0;
  double cpu_seconds = 0.0;         ///< thread CPU of the scan (all threads)
  double worker_cpu_seconds = 0.0;  ///< of the threads other than the caller
};

/// Runs the scan of `request` on the first stage of the context's schedule; the context's
/// problem is about the aligned pose with the lower's arch frame.
ScanOutcome Scan(const SearchContext& c, const GlobalRequest& request);

}  // namespace occlude::planner::detail
