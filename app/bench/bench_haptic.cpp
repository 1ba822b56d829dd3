// The haptic loop of `occlude bench --haptic` (see bench.h): one query per tick
// at a fixed period, wall-clock deadlines, latency percentiles.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <ostream>
#include <sstream>

#include "base/percentile.h"
#include "base/text_format.h"
#include "bench/bench.h"
#include "bench/bench_poses_internal.h"
#include "bench/fcl_peer.h"
#include "chart/chart.h"
#include "occlude/collision/collide.h"
#include "occlude/collision/oracle.h"

namespace occlude::app {
namespace {

// Replays the trajectory with one `query` per tick. Tick k is released at
// t0 + k * period (busy-waiting, as a haptic servo loop does); it misses its
// deadline when the answer comes later than its release plus one period, and the
// miss is a wall-clock stall when the unstalled schedule (UnstalledDone) meets it.
// The loop busy-waits, so its thread always wants the CPU: wall minus thread CPU
// time between two answers is time the machine took it off. A slow method is
// stopped after max_wall_factor times the trajectory.
HapticRow Replay(const HapticTrajectory& trajectory, double period_us, double max_wall_factor,
                 const std::function<void(const Eigen::Isometry3d&)>& query) {
  HapticRow row;
  row.period_us = period_us;
  const double period = 1e-6 * period_us;
  row.ticks_planned = static_cast<std::size_t>(std::floor(trajectory.seconds() / period)) + 1;
  std::vector<double> latency_us, cpu_us;
  latency_us.reserve(row.ticks_planned);
  cpu_us.reserve(row.ticks_planned);
  query(trajectory.At(0.0));  // warm-up
  const double t0 = NowSeconds() + 1e-3;
  const double stop = t0 + max_wall_factor * trajectory.seconds();
  double unstalled_done = t0, last_wall = NowSeconds(), last_cpu = ThreadCpuSeconds();
  for (std::size_t k = 0; k < row.ticks_planned; ++k) {
    const double release = t0 + static_cast<double>(k) * period;
    const Eigen::Isometry3d X_LU = trajectory.At(static_cast<double>(k) * period);
    double now = NowSeconds();
    while (now < release) now = NowSeconds();
    const double cpu0 = ThreadCpuSeconds();
    query(X_LU);
    const double done = NowSeconds(), cpu1 = ThreadCpuSeconds();
    cpu_us.push_back(1e6 * (cpu1 - cpu0));
    latency_us.push_back(1e6 * (done - now));
    row.off_cpu_max_us =
        std::max(row.off_cpu_max_us, 1e6 * ((done - last_wall) - (cpu1 - last_cpu)));
    last_wall = done;
    last_cpu = cpu1;
    unstalled_done = UnstalledDone(unstalled_done, release, cpu1 - cpu0);
    if (done > release + period) {
      ++row.misses;
      if (unstalled_done <= release + period) ++row.misses_stalled;
    }
    ++row.ticks;
    if (done > stop) break;
  }
  std::sort(latency_us.begin(), latency_us.end());
  std::sort(cpu_us.begin(), cpu_us.end());
  row.p50_us = NearestRankOfSorted(latency_us, 0.5, 0.0);
  row.p99_us = NearestRankOfSorted(latency_us, 0.99, 0.0);
  row.p999_us = NearestRankOfSorted(latency_us, 0.999, 0.0);
  row.max_us = NearestRankOfSorted(latency_us, 1.0, 0.0);
  row.cpu_p50_us = NearestRankOfSorted(cpu_us, 0.5, 0.0);
  return row;
}

void Log(const HapticOptions& options, const std::string& line) {
  if (options.log) *options.log << "bench --haptic: " << line << std::endl;
}

// The trajectory at the contact height: the smallest offset along the axis at which the
// sub-voxel oracle measures at most 0.02 mm of penetration (bisection), per keyframe.
std::unique_ptr<HapticTrajectory> ContactTrajectory(const BenchCase& bc,
                                                    const collision::JawOracle& oracle,
                                                    const HapticOptions& options) {
  collision::OracleRequest probe;
  probe.keep_points = false;
  auto contact_offset = [&](const Eigen::Isometry3d& X_slid) {
    collision::OracleResult r;
    double lo = -0.5, hi = 2.0;
    for (int i = 0; i < 16; ++i) {
      const double mid = 0.5 * (lo + hi);
      oracle.Query(Eigen::Translation3d(mid * bc.axis_L) * X_slid, probe, &r);
      (r.max_penetration_mm > 0.02 || r.deep_samples > 0 ? lo : hi) = mid;
    }
    return hi;
  };
  Log(options, "finding the contact height along the trajectory");
  return std::make_unique<HapticTrajectory>(bc, oracle.arch().lateral_L, oracle.arch().anterior_L,
                                            options.seconds, options.seed, contact_offset);
}

// The oracle at each accuracy level and the explicit boolean query, at one period.
void AddOracleTickRows(const HapticTrajectory& trajectory, const collision::JawOracle& oracle,
                       double voxel, double period_us, const HapticOptions& options,
                       std::vector<HapticRow>* rows) {
  const std::pair<collision::AccuracyLevel, const char*> levels[] = {
      {collision::AccuracyLevel::kVoxel, "oracle-voxel"},
      {collision::AccuracyLevel::kSubVoxel, "oracle-subvoxel"},
      {collision::AccuracyLevel::kExact, "oracle-exact"}};
  for (const auto& [level, name] : levels) {
    collision::OracleRequest request;
    request.level = level;
    request.contact_band_mm = options.delta_mm;
    collision::OracleResult result;
    HapticRow row = Replay(trajectory, period_us, options.max_wall_factor,
                           [&](const Eigen::Isometry3d& X) { oracle.Query(X, request, &result); });
    row.method = "ist";
    row.variant = "explicit";
    row.query = name;
    row.voxel_mm = voxel;
    Log(options, std::string(name) + " at " + Fixed(period_us, 0) + " us: p99 " +
                     Fixed(row.p99_us, 1) + " us, " + std::to_string(row.misses) + " misses of " +
                     std::to_string(row.ticks) + " (" + std::to_string(row.misses_stalled) +
                     " wall-clock stalls)");
    rows->push_back(row);
  }
  collision::CollisionRequest request;
  request.first_only = true;
  collision::CollisionResult result;
  HapticRow row =
      Replay(trajectory, period_us, options.max_wall_factor, [&](const Eigen::Isometry3d& X) {
        collision::Collide(oracle.lower_tree(), oracle.upper_tree(), X, request, &result);
      });
  row.method = "ist";
  row.variant = "explicit";
  row.query = "boolean";
  row.voxel_mm = voxel;
  rows->push_back(row);
}

// FCL's boolean (OBB), all-contacts and distance (OBBRSS) queries at every period.
void AddFclTickRows(const BenchCase& bc, const HapticTrajectory& trajectory,
                    const HapticOptions& options, std::vector<HapticRow>* rows) {
  Log(options, "FCL: building OBB and OBBRSS models");
  const FclPeer obb(*bc.lower_L, *bc.upper_U, FclBv::kOBB);
  const FclPeer obbrss(*bc.lower_L, *bc.upper_U, FclBv::kOBBRSS);
  struct Spec {
    const FclPeer* peer;
    const char* variant;
    const char* query;
  };
  for (const double period_us : options.periods_us) {
    for (const Spec& spec : {Spec{&obb, "obb", "boolean"}, Spec{&obbrss, "obbrss", "collide-all"},
                             Spec{&obbrss, "obbrss", "distance"}}) {
      const std::string query = spec.query;
      HapticRow row =
          Replay(trajectory, period_us, options.max_wall_factor, [&](const Eigen::Isometry3d& X) {
            if (query == "boolean") {
              (void)spec.peer->Collide(X);
            } else if (query == "collide-all") {
              (void)spec.peer->CollideAll(X);
            } else {
              (void)spec.peer->Distance(X);
            }
          });
      row.method = "fcl";
      row.variant = spec.variant;
      row.query = query;
      Log(options, "FCL " + row.variant + " " + query + " at " + Fixed(period_us, 0) + " us: p99 " +
                       Fixed(row.p99_us, 1) + " us, " + std::to_string(row.misses) + " misses of " +
                       std::to_string(row.ticks));
      rows->push_back(row);
    }
  }
}

}  // namespace

double UnstalledDone(double unstalled_done_s, double release_s, double query_cpu_s) {
  return std::max(unstalled_done_s, release_s) + query_cpu_s;
}

std::vector<HapticRow> RunHaptic(const BenchCase& bc, const HapticOptions& options) {
  std::vector<HapticRow> rows;
  std::unique_ptr<HapticTrajectory> trajectory;
  for (const double voxel : options.voxels_mm) {
    Log(options, "building the oracle at " + Fixed(voxel, 2) + " mm");
    const collision::JawOracle oracle(bc.lower_L, bc.upper_U, OracleOptionsFor(voxel));
    if (!trajectory) trajectory = ContactTrajectory(bc, oracle, options);
    for (const double period_us : options.periods_us) {
      AddOracleTickRows(*trajectory, oracle, voxel, period_us, options, &rows);
    }
  }
  if (options.fcl && FclPeer::Available() && trajectory)
    AddFclTickRows(bc, *trajectory, options, &rows);
  return rows;
}

std::string HapticCsv(const std::vector<HapticRow>& rows) {
  std::ostringstream csv;
  csv << "method,variant,voxel_mm,query,period_us,ticks_planned,ticks,misses,miss_rate,p50_us,p99_"
         "us,p999_us,max_us,cpu_p50_us,misses_stalled,misses_query,off_cpu_max_us\n";
  for (const HapticRow& r : rows) {
    csv << r.method << ',' << r.variant << ','
        << (std::isfinite(r.voxel_mm) ? Fixed(r.voxel_mm, 3) : "") << ',' << r.query << ','
        << Fixed(r.period_us, 0) << ',' << r.ticks_planned << ',' << r.ticks << ',' << r.misses
        << ','
        << Fixed(r.ticks ? static_cast<double>(r.misses) / static_cast<double>(r.ticks) : 0.0, 5)
        << ',' << Fixed(r.p50_us, 2) << ',' << Fixed(r.p99_us, 2) << ',' << Fixed(r.p999_us, 2)
        << ',' << Fixed(r.max_us, 2) << ',' << Fixed(r.cpu_p50_us, 2) << ',' << r.misses_stalled
        << ',' << r.misses - r.misses_stalled << ',' << Fixed(r.off_cpu_max_us, 1) << '\n';
  }
  return csv.str();
}

std::vector<std::pair<std::string, std::string>> HapticCharts(const std::vector<HapticRow>& rows,
                                                              const std::string& subtitle) {
  std::vector<std::pair<std::string, std::string>> files;
  std::vector<double> periods;
  for (const HapticRow& r : rows) {
    if (std::find(periods.begin(), periods.end(), r.period_us) == periods.end())
      periods.push_back(r.period_us);
  }
  for (const double period : periods) {
    LineChart c;
    c.title = "Haptic loop at " + Fixed(period, 0) + " us per tick: latency percentiles per method";
    c.subtitle = subtitle;
    c.x_label = "percentile of the per-tick latency (wall clock)";
    c.y_label = "latency, us (log)";
    c.log_y = true;
    c.x_categories = {"p50", "p99", "p99.9", "max"};
    c.references = {{period, "deadline " + Fixed(period, 0) + " us"}};
    int color = 0;
    for (const HapticRow& r : rows) {
      if (r.period_us != period) continue;
      ChartSeries s;
      s.name =
          (r.method == "fcl" ? "FCL " + r.variant + " " : "IST " + Fixed(r.voxel_mm, 2) + " ") +
          r.query + " (" + std::to_string(r.misses) + " miss, " +
          std::to_string(r.misses - r.misses_stalled) + " not stalls)";
      s.dashed = r.method == "fcl";
      s.color = color++;
      s.x = {0, 1, 2, 3};
      s.y = {r.p50_us, r.p99_us, r.p999_us, r.max_us};
      c.series.push_back(s);
    }
    if (!c.series.empty())
      files.emplace_back("haptic-" + Fixed(period, 0) + "us.png", RenderLineChartPng(c));
  }
  return files;
}

}  // namespace occlude::app
