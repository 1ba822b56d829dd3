// The occlusal-axis benchmark of `occlude bench` (see bench.h).
#include "bench/bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <random>
#include <set>
#include <sstream>

#include "base/text_format.h"
#include "base/user_error.h"
#include "bench/bench_poses_internal.h"
#include "bench/fcl_peer.h"
#include "bench/openvdb_peer.h"
#include "chart/chart.h"
#include "occlude/collision/collide.h"
#include "occlude/collision/oracle.h"

namespace occlude::app {
namespace {

using collision::SphereMode;

void Log(const BenchOptions& options, const std::string& line) {
  if (options.log) *options.log << "bench: " << line << std::endl;
}

constexpr std::size_t kWarmUpQueries = 3;

// Times `query(pose)` once per pose (thread CPU, microseconds); `record` sees
// the result of the first pose.
template <class Query>
Summary TimePoses(const std::vector<Eigen::Isometry3d>& poses, std::size_t count, Query&& query) {
  std::vector<double> us;
  count = std::min(count, poses.size());
  // Warm-up: the first queries after another kind of query (a 35 ms pair query
  // sweeps the caches) run several times slower; a few untimed ones first.
  for (std::size_t i = 0; i < std::min(kWarmUpQueries, count); ++i) query(poses[i]);
  for (std::size_t i = 0; i < count; ++i) {
    const double t0 = ThreadCpuSeconds();
    query(poses[i]);
    us.push_back(1e6 * (ThreadCpuSeconds() - t0));
  }
  return Summarize(&us);
}

BenchRow MakeRow(const std::string& method, const std::string& variant,
                 const std::string& structure) {
  BenchRow row;
  row.method = method;
  row.variant = variant;
  row.structure = structure;
  return row;
}

}  // namespace

collision::OracleOptions OracleOptionsFor(double voxel_mm) {
  collision::OracleOptions options;
  options.voxel_size_mm = voxel_mm;
  // Samples no sparser than the default spacing, and no denser than needed to
  // give every voxel a few samples.
  options.sample_spacing_mm = std::min(0.3, 1.5 * voxel_mm);
  return options;
}

int OpenVdbBandVoxels(const collision::OracleOptions& oracle,
                      const collision::OracleRequest& request) {
  const double reach = std::max(request.contact_band_mm, request.penetration_search_mm);
  const int covering = static_cast<int>(std::ceil(reach / oracle.voxel_size_mm + 1e-6));
  return std::max({covering, oracle.sdf_dilation_voxels, 1});
}

namespace {

// FCL's median per query and offset ("obb:boolean", offset) -> us: the reference of the IST
// speedups.
using FclMedians = std::map<std::pair<std::string, double>, double>;

// The poses of one round and how many of them the slower queries time.
struct RoundPoses {
  std::vector<std::vector<Eigen::Isometry3d>> at;  ///< per offset
  std::size_t slow_reps = 0, slowest_reps = 0;
};

void SetSpeedup(BenchRow* row, const std::string& reference, const FclMedians& fcl_median) {
  const auto it = fcl_median.find({reference, row->offset_mm});
  if (it == fcl_median.end()) return;
  row->fcl_reference = reference;
  if (row->us.median > 0) row->speedup = it->second / row->us.median;
}

// FCL's boolean, all-contacts and (OBBRSS) distance queries at one offset.
void AddFclOffsetRows(const FclPeer& peer, FclBv bv, const std::string& variant, double offset,
                      const std::vector<Eigen::Isometry3d>& at, std::size_t slow_reps,
                      std::vector<BenchRow>* rows, FclMedians* fcl_median) {
  auto add = [&](const std::string& query, std::size_t reps, auto&& fn) {
    BenchRow row = MakeRow("fcl", variant, "");
    row.query = query;
    row.offset_mm = offset;
    row.reps = static_cast<int>(std::min(reps, at.size()));
    fn(&row);
    (*fcl_median)[{variant + ":" + query, offset}] = row.us.median;
    rows->push_back(row);
  };
  add("boolean", at.size(), [&](BenchRow* row) {
    bool hit = false;
    row->us = TimePoses(at, at.size(), [&](const Eigen::Isometry3d& X) { hit = peer.Collide(X); });
    row->pairs = peer.Collide(at[0]) ? 1 : 0;
    (void)hit;
  });
  add("collide-all", slow_reps, [&](BenchRow* row) {
    row->us =
        TimePoses(at, slow_reps, [&](const Eigen::Isometry3d& X) { (void)peer.CollideAll(X); });
    row->pairs = peer.CollideAll(at[0]);
  });
  if (bv == FclBv::kOBBRSS) {
    add("distance", slow_reps, [&](BenchRow* row) {
      row->us =
          TimePoses(at, slow_reps, [&](const Eigen::Isometry3d& X) { (void)peer.Distance(X); });
      row->min_distance_mm = peer.Distance(at[0]).distance_mm;
    });
  }
}

// FCL's rows of one bounding-volume type: its build, then every offset.
void AddFclRows(const BenchCase& bc, FclBv bv, const BenchOptions& options, const RoundPoses& poses,
                std::vector<BenchRow>* rows, FclMedians* fcl_median) {
  const std::string variant = bv == FclBv::kOBB ? "obb" : "obbrss";
  Log(options, "FCL " + variant + ": building");
  const FclPeer peer(*bc.lower_L, *bc.upper_U, bv);
  BenchRow build = MakeRow("fcl", variant, "trees");
  build.query = "build";
  build.reps = 1;
  build.us = {1e6 * peer.build_seconds(), 1e6 * peer.build_seconds()};
  build.bytes = peer.approx_bytes();
  rows->push_back(build);
  Log(options, "FCL " + variant + ": built in " + Fixed(peer.build_seconds(), 2) + " s (" +
                   std::to_string(peer.approx_bytes() >> 20) + " MB); timing the sweep");
  for (std::size_t k = 0; k < options.offsets_mm.size(); ++k) {
    AddFclOffsetRows(peer, bv, variant, options.offsets_mm[k], poses.at[k], poses.slow_reps, rows,
                     fcl_median);
  }
  Log(options, "FCL " + variant + ": done");
}

// The structure of the build row of the oracle as the commands build it (tree_queries = false).
constexpr const char* kCommandsOracle = "commands-oracle";

bool IsOracleBuild(const BenchRow& r) {
  return r.method == "ist" && r.query == "build" &&
         (r.structure == "oracle" || r.structure == kCommandsOracle);
}

BenchRow BuildRow(const std::string& variant, const std::string& structure, double voxel,
                  double seconds, std::size_t bytes) {
  BenchRow build = MakeRow("ist", variant, structure);
  build.voxel_mm = voxel;
  build.query = "build";
  build.reps = 1;
  build.us = {1e6 * seconds, 1e6 * seconds};
  build.bytes = bytes;
  return build;
}

// The build rows of one voxel size: the trees per sphere mode (simple and optimized spheres
// need only the voxels and the octree; the explicit, saved tree adds its precomputed spheres
// and slabs) and the oracle.
void AddIstBuildRows(double voxel, const collision::JawOracle& oracle, double oracle_seconds,
                     std::vector<BenchRow>* rows) {
  const auto& ls = oracle.lower_tree().stats();
  const auto& us = oracle.upper_tree().stats();
  const double implicit_s =
      ls.seconds_voxelize + ls.seconds_octree + us.seconds_voxelize + us.seconds_octree;
  const std::size_t implicit_bytes =
      ls.total_bytes() - ls.bytes_explicit + us.total_bytes() - us.bytes_explicit;
  for (const SphereMode mode : kSphereModes) {
    const bool saved = mode == SphereMode::kExplicit;
    rows->push_back(BuildRow(collision::ToString(mode), "trees", voxel,
                             saved ? ls.total_seconds() + us.total_seconds() : implicit_s,
                             saved ? ls.total_bytes() + us.total_bytes() : implicit_bytes));
  }
  rows->push_back(BuildRow("explicit", "oracle", voxel, oracle_seconds, oracle.MemoryBytes()));
}

BenchRow IstRow(const std::string& variant, const std::string& query, double voxel, double offset) {
  BenchRow row = MakeRow("ist", variant, "");
  row.voxel_mm = voxel;
  row.query = query;
  row.offset_mm = offset;
  return row;
}

// The sphere-tree queries at one offset: boolean (first overlap) and all voxel pairs within
// the band, per sphere mode.
void AddTreeQueryRows(const collision::JawOracle& oracle, double voxel, double offset,
                      const std::vector<Eigen::Isometry3d>& at, const BenchOptions& options,
                      const RoundPoses& poses, const FclMedians& fcl_median,
                      std::vector<BenchRow>* rows) {
  const collision::SphereTree& lower = oracle.lower_tree();
  const collision::SphereTree& upper = oracle.upper_tree();
  collision::CollisionResult res;
  for (const SphereMode mode : kSphereModes) {
    collision::CollisionRequest req;
    req.spheres = mode;
    req.first_only = true;
    BenchRow row = IstRow(collision::ToString(mode), "boolean", voxel, offset);
    row.reps = static_cast<int>(at.size());
    row.us = TimePoses(at, at.size(), [&](const Eigen::Isometry3d& X) {
      collision::Collide(lower, upper, X, req, &res);
    });
    collision::Collide(lower, upper, at[0], req, &res);
    row.pairs = res.overlap ? 1 : 0;
    SetSpeedup(&row, "obb:boolean", fcl_median);
    rows->push_back(row);
  }
  for (const SphereMode mode : kSphereModes) {
    collision::CollisionRequest req;
    req.spheres = mode;
    req.delta_mm = options.delta_mm;
    BenchRow row = IstRow(collision::ToString(mode), "pairs", voxel, offset);
    row.reps = static_cast<int>(std::min(poses.slow_reps, at.size()));
    row.us = TimePoses(at, poses.slow_reps, [&](const Eigen::Isometry3d& X) {
      collision::Collide(lower, upper, X, req, &res);
    });
    collision::Collide(lower, upper, at[0], req, &res);
    row.pairs = res.pairs.size();
    SetSpeedup(&row, "obb:collide-all", fcl_median);
    rows->push_back(row);
  }
}

// The contact oracle at one offset, at each accuracy level.
void AddOracleRows(const collision::JawOracle& oracle, double voxel, double offset,
                   const std::vector<Eigen::Isometry3d>& at, const BenchOptions& options,
                   const RoundPoses& poses, const FclMedians& fcl_median,
                   std::vector<BenchRow>* rows) {
  const std::pair<collision::AccuracyLevel, const char*> levels[] = {
      {collision::AccuracyLevel::kVoxel, "oracle-voxel"},
      {collision::AccuracyLevel::kSubVoxel, "oracle-subvoxel"},
      {collision::AccuracyLevel::kExact, "oracle-exact"}};
  for (const auto& [level, name] : levels) {
    collision::OracleRequest req;
    req.level = level;
    req.contact_band_mm = options.delta_mm;
    collision::OracleResult result;
    const std::size_t reps =
        level == collision::AccuracyLevel::kExact ? poses.slowest_reps : at.size();
    BenchRow row = IstRow("explicit", name, voxel, offset);
    row.reps = static_cast<int>(std::min(reps, at.size()));
    row.us =
        TimePoses(at, reps, [&](const Eigen::Isometry3d& X) { oracle.Query(X, req, &result); });
    oracle.Query(at[0], req, &result);
    row.pairs = result.contact_samples;
    row.min_distance_mm = result.min_distance_mm;
    row.max_penetration_mm = result.max_penetration_mm;
    row.contact_area_mm2 = result.contact_area_mm2;
    row.penetration_area_mm2 = result.penetration_area_mm2;
    SetSpeedup(&row, "obbrss:collide-all", fcl_median);
    rows->push_back(row);
  }
}

// OpenVDB's rows of one voxel size: the narrow-band level set of the lower jaw (its build),
// then, at every offset, the sub-voxel oracle's work done OpenVDB's way: every upper sample of
// `oracle` placed by the pose and sampled trilinearly, counted as the oracle counts (the
// contact band of the bench, the penetration search plus the oracle's field band), at the same
// poses as the oracle's sub-voxel rows.
void AddOpenVdbRows(const BenchCase& bc, const collision::JawOracle& oracle, double voxel,
                    const BenchOptions& options, const RoundPoses& poses,
                    std::vector<BenchRow>* rows) {
  collision::OracleRequest request;
  request.contact_band_mm = options.delta_mm;
  const int half_width = OpenVdbBandVoxels(OracleOptionsFor(voxel), request);
  Log(options, "OpenVDB " + Fixed(voxel, 2) + " mm: building the level set (half width " +
                   std::to_string(half_width) + " voxels)");
  const OpenVdbPeer peer(*bc.lower_L, voxel, half_width);
  BenchRow build = MakeRow("openvdb", "levelset", "grid");
  build.voxel_mm = voxel;
  build.query = "build";
  build.reps = 1;
  build.us = {1e6 * peer.build_seconds(), 1e6 * peer.build_seconds()};
  build.bytes = peer.approx_bytes();
  rows->push_back(build);
  Log(options, "OpenVDB " + Fixed(voxel, 2) + " mm: built in " + Fixed(peer.build_seconds(), 2) +
                   " s (" + std::to_string(peer.approx_bytes() >> 20) + " MB, " +
                   std::to_string(peer.active_voxels()) + " active voxels); sampling " +
                   std::to_string(oracle.num_samples()) + " samples per pose");
  const OpenVdbCountRule rule{request.contact_band_mm,
                              request.penetration_search_mm + oracle.lower_sdf().band_mm()};
  const std::vector<Eigen::Vector3f>& samples_U = oracle.samples_U();
  const std::vector<float>& areas = oracle.sample_areas_mm2();
  for (std::size_t k = 0; k < options.offsets_mm.size(); ++k) {
    const std::vector<Eigen::Isometry3d>& at = poses.at[k];
    BenchRow row = MakeRow("openvdb", "levelset", "");
    row.voxel_mm = voxel;
    row.query = "oracle-subvoxel";
    row.offset_mm = options.offsets_mm[k];
    row.reps = static_cast<int>(at.size());
    row.us = TimePoses(at, at.size(), [&](const Eigen::Isometry3d& X) {
      (void)peer.Sample(samples_U, areas, X, rule);
    });
    const OpenVdbSampleResult r = peer.Sample(samples_U, areas, at[0], rule);
    row.pairs = r.contact_samples;
    row.min_distance_mm = r.min_distance_mm;
    row.max_penetration_mm = r.max_penetration_mm;
    row.contact_area_mm2 = r.contact_area_mm2;
    row.penetration_area_mm2 = r.penetration_area_mm2;
    rows->push_back(row);
  }
  Log(options, "OpenVDB " + Fixed(voxel, 2) + " mm: done");
}

// Every IST row of one voxel size: the oracle (and its trees) built once, then every offset;
// then OpenVDB's rows on the oracle's samples.
void AddIstRows(const BenchCase& bc, double voxel, const BenchOptions& options,
                const RoundPoses& poses, const FclMedians& fcl_median,
                std::vector<BenchRow>* rows) {
  // First the oracle without the pair queries' trees (tree_queries = false, as every command
  // builds it; at the bench's sample spacing, the commands' default from 0.2 mm up), what a user
  // waits for; then the bench's own, with the trees its pair rows query.
  Log(options, "IST " + Fixed(voxel, 2) + " mm: building the oracle as the commands do");
  {
    collision::OracleOptions commands = OracleOptionsFor(voxel);
    commands.tree_queries = false;
    const double start = NowSeconds();
    const collision::JawOracle oracle(bc.lower_L, bc.upper_U, commands);
    rows->push_back(
        BuildRow("explicit", kCommandsOracle, voxel, NowSeconds() - start, oracle.MemoryBytes()));
  }
  Log(options, "IST " + Fixed(voxel, 2) + " mm: building the trees and the oracle");
  const double t0 = NowSeconds();
  const collision::JawOracle oracle(bc.lower_L, bc.upper_U, OracleOptionsFor(voxel));
  const double oracle_seconds = NowSeconds() - t0;
  AddIstBuildRows(voxel, oracle, oracle_seconds, rows);
  Log(options, "IST " + Fixed(voxel, 2) + " mm: built in " + Fixed(oracle_seconds, 2) + " s (" +
                   std::to_string(oracle.MemoryBytes() >> 20) + " MB); timing the sweep");
  for (std::size_t k = 0; k < options.offsets_mm.size(); ++k) {
    const double offset = options.offsets_mm[k];
    AddTreeQueryRows(oracle, voxel, offset, poses.at[k], options, poses, fcl_median, rows);
    AddOracleRows(oracle, voxel, offset, poses.at[k], options, poses, fcl_median, rows);
  }
  Log(options, "IST " + Fixed(voxel, 2) + " mm: done");
  if (options.openvdb && OpenVdbPeer::Available()) {
    AddOpenVdbRows(bc, oracle, voxel, options, poses, rows);
  }
}

// One whole sweep: FCL first (its rows are the reference of the IST speedups), then IST per
// voxel size, each followed by OpenVDB at that size.
std::vector<BenchRow> RunBenchRound(const BenchCase& bc, const BenchOptions& options) {
  std::vector<BenchRow> rows;
  RoundPoses poses;
  poses.at = SweepPoses(bc, options.offsets_mm, options.reps, options.jitter_deg, options.jitter_mm,
                        options.seed);
  poses.slow_reps = static_cast<std::size_t>(std::max(3, options.reps / 3));
  poses.slowest_reps = static_cast<std::size_t>(std::max(2, options.reps / 5));
  FclMedians fcl_median;
  if (options.fcl && FclPeer::Available()) {
    for (const FclBv bv : {FclBv::kOBB, FclBv::kOBBRSS}) {
      AddFclRows(bc, bv, options, poses, &rows, &fcl_median);
    }
  }
  for (const double voxel : options.voxels_mm) {
    AddIstRows(bc, voxel, options, poses, fcl_median, &rows);
  }
  return rows;
}

// The key of a row among those of its voxel size: "levelset:oracle-subvoxel@0.200@-0.100", or
// "...@build" for a build row.
std::string PeerKey(const std::string& reference, double voxel, double offset) {
  return reference + "@" + Fixed(voxel, 4) + "@" +
         (std::isfinite(offset) ? Fixed(offset, 4) : std::string("build"));
}

// Speedups against OpenVDB from the merged medians, OpenVDB's median (or build time) over the
// IST's at the same voxel size (and offset): the sub-voxel oracle against the level set's
// samples, the oracle's build against the level set's build.
void SetOpenVdbSpeedups(std::vector<BenchRow>* rows) {
  std::map<std::string, double> openvdb_median;
  for (const BenchRow& r : *rows) {
    if (r.method == "openvdb")
      openvdb_median[PeerKey(r.variant + ":" + r.query, r.voxel_mm, r.offset_mm)] = r.us.median;
  }
  if (openvdb_median.empty()) return;
  for (BenchRow& r : *rows) {
    if (r.method != "ist" || r.variant != "explicit") continue;
    std::string reference;
    if (r.query == "oracle-subvoxel") reference = "levelset:oracle-subvoxel";
    if (r.query == "build" && IsOracleBuild(r)) reference = "levelset:build";
    if (reference.empty()) continue;
    const auto it = openvdb_median.find(PeerKey(reference, r.voxel_mm, r.offset_mm));
    if (it == openvdb_median.end()) continue;
    r.openvdb_reference = reference;
    if (r.us.median > 0) r.speedup_openvdb = it->second / r.us.median;
  }
}

}  // namespace

std::vector<BenchRow> RunBench(const BenchCase& bc, const BenchOptions& options) {
  if (options.rounds < 1) throw std::invalid_argument("BenchOptions.rounds must be at least 1");
  std::vector<BenchRow> rows;
  for (int round = 0; round < options.rounds; ++round) {
    if (options.rounds > 1)
      Log(options, "round " + std::to_string(round + 1) + " of " + std::to_string(options.rounds));
    std::vector<BenchRow> next = RunBenchRound(bc, options);
    if (rows.empty()) {
      rows = std::move(next);
      continue;
    }
    for (std::size_t i = 0; i < rows.size(); ++i) {  // the same rows in the same order
      rows[i].us.median = std::min(rows[i].us.median, next[i].us.median);
      rows[i].us.max = std::max(rows[i].us.max, next[i].us.max);
    }
  }
  // Speedups from the merged medians: FCL median / IST median at the offset.
  std::map<std::pair<std::string, double>, double> fcl_median;
  for (const BenchRow& r : rows) {
    if (r.method == "fcl" && r.query != "build")
      fcl_median[{r.variant + ":" + r.query, r.offset_mm}] = r.us.median;
  }
  for (BenchRow& r : rows) {
    if (r.fcl_reference.empty()) continue;
    const auto it = fcl_median.find({r.fcl_reference, r.offset_mm});
    if (it != fcl_median.end() && r.us.median > 0) r.speedup = it->second / r.us.median;
  }
  SetOpenVdbSpeedups(&rows);
  return rows;
}

std::string BenchCsv(const std::vector<BenchRow>& rows) {
  std::ostringstream csv;
  csv << "method,variant,voxel_mm,query,offset_mm,median_us,max_us,rate_hz,pairs,bytes,structure,"
         "reps,"
         "min_distance_mm,max_penetration_mm,fcl_reference,speedup_vs_fcl,openvdb_reference,"
         "speedup_vs_openvdb,contact_area_mm2,penetration_area_mm2\n";
  auto num = [](double v, int digits) {
    return std::isfinite(v) ? Fixed(v, digits) : std::string();
  };
  for (const BenchRow& r : rows) {
    const bool build = r.query == "build";
    csv << r.method << ',' << r.variant << ',' << num(r.voxel_mm, 3) << ',' << r.query << ','
        << num(r.offset_mm, 3) << ',' << Fixed(r.us.median, 2) << ',' << Fixed(r.us.max, 2) << ','
        << (build || r.us.median <= 0 ? std::string() : Fixed(1e6 / r.us.median, 1)) << ','
        << (build ? std::string() : std::to_string(r.pairs)) << ','
        << (build ? std::to_string(r.bytes) : std::string()) << ',' << r.structure << ',' << r.reps
        << ',' << num(r.min_distance_mm, 5) << ',' << num(r.max_penetration_mm, 5) << ','
        << r.fcl_reference << ',' << num(r.speedup, 2) << ',' << r.openvdb_reference << ','
        << num(r.speedup_openvdb, 2) << ',' << num(r.contact_area_mm2, 4) << ','
        << num(r.penetration_area_mm2, 4) << '\n';
  }
  return csv.str();
}

namespace {

std::string OffsetLabel(double offset) {
  char text[32];
  std::snprintf(text, sizeof text, "%+g", offset);
  return offset == 0.0 ? std::string("0") : std::string(text);
}

// One series: rate against the offset index, for rows matching `keep`.
template <class Keep>
ChartSeries RateSeries(const std::vector<BenchRow>& rows, const std::vector<double>& offsets,
                       const std::string& name, bool dashed, int color, Keep&& keep) {
  ChartSeries s;
  s.name = name;
  s.dashed = dashed;
  s.color = color;
  for (const BenchRow& r : rows) {
    if (r.query == "build" || !keep(r)) continue;
    const auto it = std::find(offsets.begin(), offsets.end(), r.offset_mm);
    if (it == offsets.end() || r.us.median <= 0) continue;
    s.x.push_back(static_cast<double>(it - offsets.begin()));
    s.y.push_back(1e6 / r.us.median);
  }
  return s;
}

// What the rate charts share: the offsets in sweep order (the categorical x axis), the voxel
// sizes, the rows and the subtitle; every chart drawn goes to `files`.
struct RateCharts {
  const std::vector<BenchRow>& rows;
  std::string subtitle;
  std::vector<double> offsets;
  std::set<double> voxels;
  std::vector<std::string> labels;
  std::vector<std::pair<std::string, std::string>> files;

  RateCharts(const std::vector<BenchRow>& bench_rows, std::string chart_subtitle)
      : rows(bench_rows), subtitle(std::move(chart_subtitle)) {
    for (const BenchRow& r : rows) {
      if (r.query == "build") continue;
      if (std::find(offsets.begin(), offsets.end(), r.offset_mm) == offsets.end())
        offsets.push_back(r.offset_mm);
      if (std::isfinite(r.voxel_mm)) voxels.insert(r.voxel_mm);
    }
    for (const double o : offsets) labels.push_back(OffsetLabel(o));
  }

  LineChart Chart(const std::string& title) const {
    LineChart c;
    c.title = title;
    c.subtitle = subtitle;
    c.x_label =
        "offset along the occlusal axis, mm (0 = registered bite, > 0 open, < 0 interpenetrating)";
    c.y_label = "queries per second (Hz), log";
    c.log_y = true;
    c.x_categories = labels;
    c.references = {{1000.0, "1 kHz (haptic)"}};
    return c;
  }

  // The FCL series (dashed, colours from 5 on) that have points.
  void AddFcl(LineChart* c,
              std::initializer_list<std::pair<const char*, const char*>> which) const {
    int color = 5;
    for (const auto& which_one : which) {
      const std::string variant = which_one.first, query = which_one.second;
      ChartSeries s = RateSeries(
          rows, offsets, "FCL " + variant + " " + query, true, color++, [&](const BenchRow& r) {
            return r.method == "fcl" && r.variant == variant && r.query == query;
          });
      if (!s.x.empty()) c->series.push_back(s);
    }
  }

  // OpenVDB's sampled level set at voxel size v (dashed), when it has points.
  void AddOpenVdb(LineChart* c, double v, const std::string& name, int color) const {
    ChartSeries s = RateSeries(rows, offsets, name, true, color, [&](const BenchRow& r) {
      return r.method == "openvdb" && r.query == "oracle-subvoxel" && r.voxel_mm == v;
    });
    if (!s.x.empty()) c->series.push_back(s);
  }

  bool HasOpenVdb() const {
    return std::any_of(rows.begin(), rows.end(),
                       [](const BenchRow& r) { return r.method == "openvdb"; });
  }

  // Renders the chart when any series has a point.
  void Emit(const std::string& file, const LineChart& c) {
    bool any = false;
    for (const auto& s : c.series) any = any || !s.x.empty();
    if (any) files.emplace_back(file, RenderLineChartPng(c));
  }
};

// At one voxel size: the boolean and the pairs query per sphere mode, and the oracle per
// level, each against the matching FCL queries.
void AddVoxelCharts(double v, RateCharts* charts) {
  const std::vector<BenchRow>& rows = charts->rows;
  const std::string vs = Fixed(v, v < 0.1 ? 3 : (v < 1 ? 1 : 0));
  const std::string tag = Fixed(v, 2) + "mm";
  for (const char* query : {"boolean", "pairs"}) {
    const bool boolean = query == std::string("boolean");
    LineChart c = charts->Chart(
        std::string(boolean ? "Boolean collision query" : "All voxel pairs within the band") +
        ", IST at " + vs + " mm voxels, against FCL");
    int color = 0;
    for (const char* variant : {"simple", "optimized", "explicit"}) {
      c.series.push_back(RateSeries(rows, charts->offsets, std::string("IST ") + variant, false,
                                    color++, [&](const BenchRow& r) {
                                      return r.method == "ist" && r.variant == variant &&
                                             r.query == query && r.voxel_mm == v;
                                    }));
    }
    if (boolean) {
      charts->AddFcl(&c, {{"obb", "boolean"}, {"obbrss", "boolean"}});
    } else {
      charts->AddFcl(&c, {{"obb", "collide-all"}, {"obbrss", "collide-all"}});
    }
    charts->Emit(std::string(query) + "-" + tag + ".png", c);
  }
  // (The title's width: with OpenVDB, the band's words give way to the peers' names.)
  LineChart c =
      charts->Chart("Contact oracle at " + vs + " mm voxels " +
                    (charts->HasOpenVdb() ? "(contacts + penetration), against FCL and OpenVDB"
                                          : "(contacts within the band + penetration)"));
  int color = 0;
  for (const char* query : {"oracle-voxel", "oracle-subvoxel", "oracle-exact"}) {
    c.series.push_back(RateSeries(rows, charts->offsets, std::string("IST ") + query, false,
                                  color++, [&](const BenchRow& r) {
                                    return r.method == "ist" && r.query == query && r.voxel_mm == v;
                                  }));
  }
  charts->AddFcl(&c, {{"obbrss", "collide-all"}, {"obbrss", "distance"}});
  charts->AddOpenVdb(&c, v, "OpenVDB level set", 8);
  charts->Emit("oracle-" + tag + ".png", c);
}

// Across voxel sizes: the explicit boolean query and the sub-voxel oracle.
void AddByVoxelCharts(RateCharts* charts) {
  for (const char* query : {"boolean", "oracle-subvoxel"}) {
    const bool boolean = query == std::string("boolean");
    LineChart c = charts->Chart(
        std::string(boolean ? "Boolean query (explicit IST)" : "Sub-voxel oracle") +
        " by voxel size, against FCL" +
        (!boolean && charts->HasOpenVdb() ? " and OpenVDB (same colour, dashed)" : ""));
    int color = 0;
    for (const double v : charts->voxels) {
      c.series.push_back(RateSeries(charts->rows, charts->offsets, "IST " + Fixed(v, 2) + " mm",
                                    false, color++, [&](const BenchRow& r) {
                                      return r.method == "ist" && r.variant == "explicit" &&
                                             r.query == query && r.voxel_mm == v;
                                    }));
    }
    if (boolean) {
      charts->AddFcl(&c, {{"obb", "boolean"}});
    } else {
      charts->AddFcl(&c, {{"obbrss", "collide-all"}});
      color = 0;
      for (const double v : charts->voxels) {
        charts->AddOpenVdb(&c, v, "OpenVDB " + Fixed(v, 2) + " mm", color++);
      }
    }
    charts->Emit(std::string(query) + "-by-voxel.png", c);
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> BenchCharts(const std::vector<BenchRow>& rows,
                                                             const std::string& subtitle) {
  RateCharts charts(rows, subtitle);
  for (const double v : charts.voxels) AddVoxelCharts(v, &charts);
  AddByVoxelCharts(&charts);
  return std::move(charts.files);
}

namespace {

// The builds: the IST oracle's (both jaws: trees, the lower's distance field and bounds, the
// upper's samples), FCL's (both jaws' BVH trees) and OpenVDB's (the lower jaw's level set), wall
// time; the oracle's line with the peers' build times over its own (FCL's OBBRSS, OpenVDB's at
// the same voxel size).
void SummarizeBuilds(const std::vector<BenchRow>& rows, std::ostringstream* s) {
  double fcl_obbrss_us = std::numeric_limits<double>::quiet_NaN();
  for (const BenchRow& r : rows) {
    if (r.method == "fcl" && r.variant == "obbrss" && r.query == "build")
      fcl_obbrss_us = r.us.median;
  }
  bool header = false;
  for (const BenchRow& r : rows) {
    if (r.query != "build") continue;
    const bool oracle = IsOracleBuild(r);
    if (!oracle && r.method == "ist") continue;  // the trees alone: in the CSV
    if (!header) {
      *s << "builds, wall time (IST oracle: both jaws, " << kCommandsOracle
         << " without the pair queries' trees; FCL: both jaws' BVH trees; OpenVDB: the lower "
            "jaw's level set), and the peers' build time over the oracle's\n";
      header = true;
    }
    const std::string key =
        r.method + " " + r.variant + " " +
        (std::isfinite(r.voxel_mm) ? Fixed(r.voxel_mm, 2) + "mm " : std::string()) + r.structure;
    char line[256];
    std::snprintf(line, sizeof line, "  %-40s %10.3f s, %6.1f MB", key.c_str(), 1e-6 * r.us.median,
                  static_cast<double>(r.bytes) / (1 << 20));
    *s << line;
    if (oracle && std::isfinite(fcl_obbrss_us) && r.us.median > 0) {
      std::snprintf(line, sizeof line, "   FCL obbrss %.3gx", fcl_obbrss_us / r.us.median);
      *s << line;
    }
    if (oracle && std::isfinite(r.speedup_openvdb)) {
      std::snprintf(line, sizeof line, "   OpenVDB levelset %.3gx", r.speedup_openvdb);
      *s << line;
    }
    *s << "\n";
  }
}

}  // namespace

std::string BenchSummary(const std::vector<BenchRow>& rows) {
  // Worst median over the offsets, per method/variant/voxel/query; and the
  // smallest speedups over FCL and OpenVDB.
  constexpr double kInf = std::numeric_limits<double>::infinity();
  struct Worst {
    double us = 0.0, offset = 0.0, min_speedup = kInf, min_speedup_openvdb = kInf;
    std::string reference, openvdb_reference;
  };
  std::map<std::string, Worst> worst;
  std::vector<std::string> order;
  for (const BenchRow& r : rows) {
    if (r.query == "build") continue;
    const std::string key =
        r.method + " " + r.variant + " " +
        (std::isfinite(r.voxel_mm) ? Fixed(r.voxel_mm, 2) + "mm " : std::string()) + r.query;
    if (!worst.count(key)) order.push_back(key);
    Worst& w = worst[key];
    if (r.us.median >= w.us) {
      w.us = r.us.median;
      w.offset = r.offset_mm;
    }
    if (std::isfinite(r.speedup)) {
      w.min_speedup = std::min(w.min_speedup, r.speedup);
      w.reference = r.fcl_reference;
    }
    if (std::isfinite(r.speedup_openvdb)) {
      w.min_speedup_openvdb = std::min(w.min_speedup_openvdb, r.speedup_openvdb);
      w.openvdb_reference = r.openvdb_reference;
    }
  }
  std::ostringstream s;
  s << "worst median over the sweep (thread CPU us), and the smallest speedup over the matching "
       "FCL query (and OpenVDB's, where it ran)\n";
  for (const std::string& key : order) {
    const Worst& w = worst[key];
    char line[256];
    std::snprintf(line, sizeof line, "  %-40s %10.1f us at %+.2f mm", key.c_str(), w.us, w.offset);
    s << line;
    if (std::isfinite(w.min_speedup)) {
      char ratio[32];
      std::snprintf(ratio, sizeof ratio, "%.3g", w.min_speedup);
      s << "   >= " << ratio << "x FCL " << w.reference;
    }
    if (std::isfinite(w.min_speedup_openvdb)) {
      char ratio[32];
      std::snprintf(ratio, sizeof ratio, "%.3g", w.min_speedup_openvdb);
      s << "   >= " << ratio << "x OpenVDB " << w.openvdb_reference;
    }
    s << "\n";
  }
  SummarizeBuilds(rows, &s);
  return s.str();
}

}  // namespace occlude::app
