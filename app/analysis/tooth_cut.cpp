// Cuts between crowns (tooth_cut.h): a dynamic programme over a grid of (t, s) samples around
// the boundary, row by row across the arch, each sample's cost its height above the floor.
#include "tooth_cut.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace occlude::analysis {
namespace {

constexpr double kCutHalfSpanMm = 5.0;    // across the curve: a molar's crown and its embrasures
constexpr double kFloorBelowTopMm = 4.0;  // heights below the window's top by more count as this
constexpr double kTurnCostMm = 0.3;       // a turn by one cell costs this much height
// Each mm away from the segmentation's boundary costs this much height: among equally low paths
// (the flat floor of a gap between crowns) the one through the profile's minimum.
constexpr double kOffsetCostPerMm = 0.03;

// The height of g.top at curve coordinates (s, t), or NaN where it is empty.
double HeightAt(const ArchGeometry& g, double s, double t) {
  const int c = g.top.CellAt(g.curve.At(s) + t * g.curve.Normal(s));
  return c >= 0 && g.top.Filled(c) ? g.top.height[static_cast<std::size_t>(c)]
                                   : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

double ToothCut::At(double t) const {
  const long k = std::lround((t - t0) / step);
  return s[static_cast<std::size_t>(std::clamp(k, 0L, static_cast<long>(s.size()) - 1))];
}

ToothCut StraightCut(double s) {
  ToothCut cut;
  cut.s = {s};
  return cut;
}

ToothCut FindToothCut(const ArchGeometry& g, double s_mm, double reach_mm) {
  const double step = g.top.cell;
  const int rows = static_cast<int>(std::lround(2.0 * kCutHalfSpanMm / step)) + 1;
  const int half = static_cast<int>(std::lround(std::max(reach_mm, 0.0) / step));
  const int cols = 2 * half + 1;  // the boundary is the middle column
  const double s0 = s_mm - step * half, t0 = -kCutHalfSpanMm;
  std::vector<double> h(static_cast<std::size_t>(rows * cols));
  double top = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double v = HeightAt(g, s0 + j * step, t0 + i * step);
      h[static_cast<std::size_t>(i * cols + j)] = v;
      if (!std::isnan(v)) top = std::max(top, v);
    }
  }
  if (!std::isfinite(top)) return StraightCut(s_mm);
  // Each sample's cost: its height above the floor (empty cells on it) and its offset's.
  const double floor = top - kFloorBelowTopMm;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      double& v = h[static_cast<std::size_t>(i * cols + j)];
      v = (std::isnan(v) ? 0.0 : std::max(v, floor) - floor) +
          kOffsetCostPerMm * step * std::abs(j - half);
    }
  }
  // f[i][j]: the least cost of a path from row 0 to sample (i, j); from[i][j] its column in i-1.
  std::vector<double> f(h.size(), std::numeric_limits<double>::infinity());
  std::vector<int> from(h.size(), -1);
  for (int j = 0; j < cols; ++j) f[static_cast<std::size_t>(j)] = h[static_cast<std::size_t>(j)];
  for (int i = 1; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const auto k = static_cast<std::size_t>(i * cols + j);
      for (int jp = std::max(0, j - 1); jp <= std::min(cols - 1, j + 1); ++jp) {
        const double c = f[static_cast<std::size_t>((i - 1) * cols + jp)] + h[k] +
                         kTurnCostMm * std::abs(j - jp);
        if (c < f[k]) f[k] = c, from[k] = jp;
      }
    }
  }
  int best = 0;
  for (int j = 1; j < cols; ++j) {
    if (f[static_cast<std::size_t>((rows - 1) * cols + j)] <
        f[static_cast<std::size_t>((rows - 1) * cols + best)])
      best = j;
  }
  ToothCut cut;
  cut.t0 = t0;
  cut.step = step;
  cut.s.assign(static_cast<std::size_t>(rows), s_mm);
  for (int i = rows - 1, j = best; i >= 0; j = from[static_cast<std::size_t>(i * cols + j)], --i) {
    cut.s[static_cast<std::size_t>(i)] = s0 + j * step;
  }
  return cut;
}

}  // namespace occlude::analysis
