// The global search's scan: every pose of the grid about the aligned pose
// started open, settled along the occlusal axis on the coarse stage and scored
// by the seat cost of a sparse occlusal sample set; the local optima of the
// grid (no axis neighbour scores better) are the basins.
#include "global_scan.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace occlude::planner::detail {

void ValidateScanSettings(const GlobalScanSettings& s) {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("GlobalRequest.scan." + what);
  };
  // Names the field: e.g. "sagittal" with unit "mm" is sagittal_range_mm / sagittal_step_mm.
  auto axis = [&](double range, double step, const std::string& name, const std::string& unit,
                  double max) {
    if (!(std::isfinite(range) && range >= 0.0 && range <= max))
      fail(name + "_range_" + unit + ": must be in [0, " + std::to_string(max) + "] " + unit);
    if (!(std::isfinite(step) && step > 0.0))
      fail(name + "_step_" + unit + ": must be finite and > 0");
    if (range / step > 200.0)
      fail(name + "_step_" + unit + ": gives over 400 values along the axis; use a larger step");
  };
  axis(s.sagittal_range_mm, s.sagittal_step_mm, "sagittal", "mm", 30.0);
  axis(s.lateral_range_mm, s.lateral_step_mm, "lateral", "mm", 10.0);
  axis(s.yaw_range_deg, s.yaw_step_deg, "yaw", "deg", 30.0);
  axis(s.pitch_range_deg, s.pitch_step_deg, "pitch", "deg", 30.0);
  if (!(std::isfinite(s.open_mm) && s.open_mm >= 0.0 && s.open_mm <= 10.0))
    fail("open_mm: must be in [0, 10] mm (default 2)");
  if (!(std::isfinite(s.sample_spacing_mm) && s.sample_spacing_mm >= 0.2 &&
        s.sample_spacing_mm <= 5.0))
    fail("sample_spacing_mm: must be in [0.2, 5] mm (default 1)");
  if (s.max_basins < 1 || s.max_basins > 1000) fail("max_basins: must be in [1, 1000]");
  if (s.max_refined < 1 || s.max_refined > s.max_basins)
    fail("max_refined: must be in [1, max_basins]");
}

std::vector<double> ScanAxis(double range, double step) {
  const int n = static_cast<int>(std::floor(range / step + 1e-9));
  std::vector<double> v;
  for (int k = -n; k <= n; ++k) v.push_back(k * step);
  return v;
}

ArchShift ScanGrid::Shift(std::size_t index) const {
  ArchShift s;
  s.pitch_deg = pitch[index % pitch.size()];
  index /= pitch.size();
  s.yaw_deg = yaw[index % yaw.size()];
  index /= yaw.size();
  s.lateral_mm = lateral[index % lateral.size()];
  s.sagittal_mm = sagittal[index / lateral.size()];
  return s;
}

std::vector<std::size_t> ScanGrid::Neighbours(std::size_t index) const {
  const std::size_t dims[4] = {sagittal.size(), lateral.size(), yaw.size(), pitch.size()};
  std::size_t stride[4];
  stride[3] = 1;
  for (int d = 2; d >= 0; --d) stride[d] = stride[d + 1] * dims[d + 1];
  std::vector<std::size_t> out;
  for (int d = 0; d < 4; ++d) {
    const std::size_t k = index / stride[d] % dims[d];
    if (k > 0) out.push_back(index - stride[d]);
    if (k + 1 < dims[d]) out.push_back(index + stride[d]);
  }
  return out;
}

namespace {

// Problem parameters of a grid pose: its shift in the lower's arch frame about the pivot,
// started `open_mm` open.
Vector6d GridPose(const Problem& problem, const ArchShift& s, double open_mm) {
  const collision::ArchFrame& a = problem.arch;
  Vector6d x;
  x.head<3>() = s.lateral_mm * a.lateral_L + s.sagittal_mm * a.anterior_L + open_mm * a.occlusal_L;
  x.tail<3>() = s.yaw_deg * a.occlusal_L + s.pitch_deg * a.lateral_L;
  return x;
}

struct ScanPoint {
  Vector6d x = Vector6d::Zero();
  SetEvaluation e;
  int evaluations = 0;
};

// The local optima of the scan (strictly better than every axis neighbour, ties to the lower
// index), lowest seat cost first, at most `count`.
std::vector<std::size_t> LocalOptima(const ScanGrid& grid, const std::vector<ScanPoint>& points,
                                     std::size_t count) {
  auto better = [&](std::size_t a, std::size_t b) {
    return points[a].e.seat_cost < points[b].e.seat_cost ||
           (points[a].e.seat_cost == points[b].e.seat_cost && a < b);
  };
  std::vector<std::size_t> optima;
  for (std::size_t i = 0; i < points.size(); ++i) {
    bool best = true;
    for (const std::size_t j : grid.Neighbours(i)) best = best && better(i, j);
    if (best) optima.push_back(i);
  }
  std::sort(optima.begin(), optima.end(), better);
  if (optima.size() > count) optima.resize(count);
  return optima;
}

}  // namespace

ScanOutcome Scan(const SearchContext& c, const GlobalRequest& request) {
  const double cpu0 = CpuSeconds();
  const Problem& problem = *c.problem;
  const GlobalScanSettings& s = request.scan;
  ScanOutcome out;
  out.grid = {ScanAxis(s.sagittal_range_mm, s.sagittal_step_mm),
              ScanAxis(s.lateral_range_mm, s.lateral_step_mm),
              ScanAxis(s.yaw_range_deg, s.yaw_step_deg),
              ScanAxis(s.pitch_range_deg, s.pitch_step_deg)};
  const OracleStage& stage = c.schedule->front();
  const SampleSet samples = OcclusalSamples(stage.oracle->upper_tree().mesh(), problem.X_ref,
                                            problem.arch.occlusal_L, s.sample_spacing_mm);
  std::vector<ScanPoint> points(out.grid.size());
  std::atomic<int> done{0};
  std::mutex mutex;
  int reported = 0;  // under the mutex: progress is reported in increasing order
  const int total = static_cast<int>(points.size());
  out.worker_cpu_seconds =
      ParallelFor(points.size(), problem.request->num_threads, [&](std::size_t i) {
        ScanPoint& p = points[i];
        const Vector6d x0 = Clamp(problem, GridPose(problem, out.grid.Shift(i), s.open_mm));
        p.x = SettleOnSet(stage, samples, problem, x0, &p.evaluations);
        p.e = EvaluateSet(stage, samples, PoseOf(problem, p.x), problem);
        ++p.evaluations;
        const int n = ++done;
        if (request.on_progress && (n % 32 == 0 || n == total)) {
          std::lock_guard<std::mutex> lock(mutex);
          if (n > reported) request.on_progress(GlobalRequest::Phase::kScan, n, total);
          reported = std::max(reported, n);
        }
      });
  for (const ScanPoint& p : points) out.evaluations += p.evaluations;
  for (const std::size_t i :
       LocalOptima(out.grid, points, static_cast<std::size_t>(s.max_basins))) {
    ScanBasinPose b;
    b.x = points[i].x;
    b.basin.shift = out.grid.Shift(i);
    b.basin.shift.vertical_mm = points[i].x.head<3>().dot(problem.arch.occlusal_L);
    b.basin.seat_cost = points[i].e.seat_cost;
    b.basin.contact_area_mm2 = points[i].e.contact_area_mm2;
    out.basins.push_back(b);
  }
  out.cpu_seconds = CpuSeconds() - cpu0 + out.worker_cpu_seconds;
  return out;
}

}  // namespace occlude::planner::detail
