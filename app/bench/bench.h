// `occlude bench`: the paper's experiment (Le Jeune et al., Fig. 10) on a jaw
// pair, with the general-purpose peer FCL and OpenVDB's sparse level sets timed on
// the same meshes and poses in the same run, and the haptic loop that makes the
// 1 kHz requirement measurable.
//
// Sweep: the lower jaw L is fixed; the upper jaw is moved along the occlusal axis
// from the reference bite (offset 0; offset > 0 opens it) with a small seeded
// rigid jitter per repetition. Every method sees exactly the same poses. Query
// times are thread CPU time (the machines are shared); build times are wall time.
#pragma once

#include <Eigen/Geometry>
#include <iosfwd>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "base/timing.h"
#include "occlude/collision/oracle.h"
#include "occlude/io/triangle_mesh.h"
#include "session/jaw_pair.h"

namespace occlude::app {

/// A jaw pair to benchmark (session/jaw_pair.h: lower in L, upper in U, the bite X_LU_ref) and
/// the occlusal axis the sweeps move the upper along.
struct BenchCase : JawPair {
  Eigen::Vector3d axis_L = Eigen::Vector3d::UnitY();  ///< occlusal axis, lower -> upper, unit
};

struct BenchOptions {
  std::vector<double> voxels_mm = {0.8, 0.4, 0.2, 0.1};
  std::vector<double> offsets_mm = {5.0, 3.0, 2.0,  1.5, 1.0,   0.75, 0.5,   0.3,
                                    0.2, 0.1, 0.05, 0.0, -0.05, -0.1, -0.15, -0.2};
  int reps = 15;  ///< poses per offset (each jittered); fewer for the slow queries
  /// Whole sweeps, each timing every pose once: a row keeps the smallest of the
  /// rounds' medians and the largest single query of all rounds (on a shared
  /// host, other tenants slow down whole stretches of a run; FCL and IST rows
  /// are treated alike, and the speedups come from the merged medians).
  int rounds = 3;
  std::uint32_t seed = 1;
  double delta_mm = 0.1;    ///< contact band of the pairs query and the oracle
  double jitter_deg = 0.2;  ///< rotation jitter about the upper's centroid, at most
  double jitter_mm = 0.05;  ///< translation jitter across the axis, at most
  bool fcl = true;          ///< also time FCL (when built with it)
  /// Also time OpenVDB (when built with it): per voxel size, a narrow-band level set of the
  /// lower jaw (OpenVdbBandVoxels wide) and its trilinear samples at the oracle's upper samples.
  bool openvdb = true;
  std::ostream* log = nullptr;  ///< progress lines
};

/// The sphere modes the benchmarks time, in their order.
inline constexpr collision::SphereMode kSphereModes[] = {collision::SphereMode::kSimple,
                                                         collision::SphereMode::kOptimized,
                                                         collision::SphereMode::kExplicit};

/// One CSV row. Build rows: median_us = max_us = wall build time, bytes = memory.
struct BenchRow {
  std::string method;     ///< "ist", "fcl" or "openvdb"
  std::string variant;    ///< simple, optimized, explicit, obb, obbrss, levelset
  std::string structure;  ///< build rows: "trees", "oracle" or "grid" (OpenVDB); query rows: ""
  double voxel_mm = std::numeric_limits<double>::quiet_NaN();  ///< NaN for FCL
  std::string query;  ///< build, boolean, pairs, oracle-voxel, oracle-subvoxel, oracle-exact,
                      ///< collide-all, distance (OpenVDB: build, oracle-subvoxel)
  double offset_mm = std::numeric_limits<double>::quiet_NaN();  ///< NaN for build rows
  int reps = 0;
  Summary us;  ///< median and max microseconds per query
  std::size_t pairs =
      0;  ///< voxel pairs, contact samples, contacts, overlaps (median rep's pose: first)
  std::size_t bytes = 0;
  double min_distance_mm = std::numeric_limits<double>::quiet_NaN();     ///< distance / oracle rows
  double max_penetration_mm = std::numeric_limits<double>::quiet_NaN();  ///< oracle rows
  /// Oracle rows (IST and OpenVDB), the median rep's pose (first): contact and penetration area.
  double contact_area_mm2 = std::numeric_limits<double>::quiet_NaN();
  double penetration_area_mm2 = std::numeric_limits<double>::quiet_NaN();
  std::string fcl_reference;  ///< the matching FCL query ("obb:boolean"), IST rows
  double speedup = std::numeric_limits<double>::quiet_NaN();  ///< FCL median / IST median
  /// The matching OpenVDB row at the same voxel size ("levelset:oracle-subvoxel", or
  /// "levelset:build" for the oracle's build), IST rows; speedup_openvdb = its median / ours
  /// (the same definition as `speedup`: the peer's time over the IST's).
  std::string openvdb_reference;
  double speedup_openvdb = std::numeric_limits<double>::quiet_NaN();
};

/// The oracle settings the benchmarks use at a voxel size (sample spacing
/// min(0.3, 1.5 * voxel) mm).
collision::OracleOptions OracleOptionsFor(double voxel_mm);

/// The half width, in voxels, of OpenVDB's level set beside an oracle built with `oracle` and
/// queried with `request`: as wide as the oracle's reach (the contact band or the penetration
/// search, whichever is larger; strictly wider, as OpenVDB's band is open), and never narrower
/// than the oracle's own field band (sdf_dilation_voxels), so that trilinear samples near the
/// reach read no clamped background value the oracle's field would not. 0.2 mm voxels, band
/// 0.1 mm, search 0.3 mm: max(ceil(1.5), 2) = 2 voxels (0.4 mm).
int OpenVdbBandVoxels(const collision::OracleOptions& oracle,
                      const collision::OracleRequest& request);

std::vector<BenchRow> RunBench(const BenchCase& bench_case, const BenchOptions& options);
std::string BenchCsv(const std::vector<BenchRow>& rows);
/// Charts (file name, PNG bytes): query rate against offset, one line per method.
std::vector<std::pair<std::string, std::string>> BenchCharts(const std::vector<BenchRow>& rows,
                                                             const std::string& subtitle);
/// A short text summary (worst case per method near the targets).
std::string BenchSummary(const std::vector<BenchRow>& rows);

// ---- Haptic loop ----------------------------------------------------------

struct HapticOptions {
  std::vector<double> voxels_mm = {0.2};
  std::vector<double> periods_us = {1000.0, 100.0};
  double seconds = 2.0;          ///< trajectory duration (descent, then sliding in contact)
  double max_wall_factor = 3.0;  ///< a method stops after this many times the duration
  std::uint32_t seed = 1;
  double delta_mm = 0.1;
  bool fcl = true;
  std::ostream* log = nullptr;
};

/// When tick k's answer would have come on a machine that never takes the loop's thread off the
/// CPU: its release or the previous tick's answer there (`unstalled_done_s`), whichever is
/// later, plus the thread CPU time its query took. A missed tick whose unstalled answer meets
/// the deadline (release + period) is a wall-clock stall of the machine; one whose unstalled
/// answer misses too is the query's (its own CPU time, with the backlog of the ticks before it).
double UnstalledDone(double unstalled_done_s, double release_s, double query_cpu_s);

struct HapticRow {
  std::string method, variant, query;
  double voxel_mm = std::numeric_limits<double>::quiet_NaN();
  double period_us = 0.0;
  std::size_t ticks_planned = 0, ticks = 0, misses = 0;
  /// Misses the unstalled schedule (UnstalledDone) meets: wall-clock stalls of the machine;
  /// misses - misses_stalled are the query's.
  std::size_t misses_stalled = 0;
  double p50_us = 0, p99_us = 0, p999_us = 0, max_us = 0;  ///< wall latency per tick
  double cpu_p50_us = 0;                                   ///< thread CPU per tick
  double off_cpu_max_us = 0;  ///< longest wall minus thread CPU time between two answers
};

std::vector<HapticRow> RunHaptic(const BenchCase& bench_case, const HapticOptions& options);
std::string HapticCsv(const std::vector<HapticRow>& rows);
std::vector<std::pair<std::string, std::string>> HapticCharts(const std::vector<HapticRow>& rows,
                                                              const std::string& subtitle);

}  // namespace occlude::app
