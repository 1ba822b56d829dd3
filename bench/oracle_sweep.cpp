// Timing program for the speed targets of the collision queries and the
// contact oracle on a real case (default a-bite-3shape, 0.2 mm voxels): the
// upper jaw is moved along an axis from +5 mm open through the registered bite
// to 0.2 mm interpenetration, with a small random pose jitter (fixed seed), and
// each query is timed as thread CPU time (the machine is shared), median over
// repetitions, worst over the jittered poses of an offset. Also times the lower
// distance-field build and Interpolate, and checks the sub-voxel oracle against
// exact distances (p95 error, contacts within 0.05 mm missed).
//
//   occlude_oracle_sweep [--case a-bite-3shape] [--axis y] [--reps 15] [--jitter 3]
//                        [--only boolean|oracle|sdf|build|digest|saved] [--profile OFFSET]
//                        [--voxel 0.2] [--builds 3] [--threads 0]
//
// --only build builds the oracle (--voxel, default options otherwise, as `occlude bench`)
// --builds times and prints each build's wall time and process CPU time (all threads), with
// OracleOptions::threads = --threads (0 = every core).
// --only saved saves the oracle to a file, times --builds loads of it (cold: its pages dropped
// from the page cache first; warm) and prints the digests of the built and loaded oracles.
// --only digest prints a hash of every answer (totals, parts, points, residuals) of the
// voxel, sub-voxel and exact levels at the sweep's jittered poses: equal digests from two
// builds of the library mean bit-identical answers.
//
// --profile OFFSET repeats only the sub-voxel oracle query at that offset (no jitter) for
// 10 s of thread CPU, for a profiler: perf record -g occlude_oracle_sweep --profile -0.2
// ($OCCLUDE_CELL_LEVEL sets OracleOptions::cell_level there; $OCCLUDE_PROFILE_QUERY=boolean
// repeats the explicit boolean query instead, =voxel the voxel-level oracle).
//
// Exits 0 with a message when the shared data folder is absent ($OCCLUDE_DATA_DIR
// overrides ../shared/data beside the checkout).
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "data_dir.h"
#include "occlude/angles.h"
#include "occlude/clock.h"
#include "occlude/collision/collide.h"
#include "occlude/collision/oracle.h"
#include "occlude/collision/oracle_file.h"
#include "occlude/collision/signed_distance.h"
#include "occlude/io/content_hash.h"
#include "occlude/io/mesh_io.h"
#include "session/jaw_pair.h"

namespace {

using namespace occlude;  // NOLINT: a small program
using Eigen::Isometry3d;
using Eigen::Vector3d;

double ClockSeconds(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Median thread CPU microseconds of f() over reps calls (one warm-up call first).
template <class F>
double MedianMicros(F&& f, int reps) {
  f();
  std::vector<double> us;
  for (int i = 0; i < reps; ++i) {
    const double t0 = ThreadCpuSeconds();
    f();
    us.push_back(1e6 * (ThreadCpuSeconds() - t0));
  }
  std::sort(us.begin(), us.end());
  return us[us.size() / 2];
}

struct Args {
  std::string case_name = "a-bite-3shape";
  int axis = 1;
  int reps = 15;
  int jitter = 3;
  std::string only;
  double voxel_mm = 0.2;
  int builds = 3;
  int threads = 0;      ///< OracleOptions::threads of --only build / digest
  std::string profile;  ///< offset (mm) to repeat the oracle query at, for a profiler
  std::string compare;  ///< offsets (mm, comma-separated) for the field bound A/B comparison
};

Args Parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--case") a.case_name = v;
    if (k == "--axis") a.axis = v == "x" ? 0 : (v == "z" ? 2 : 1);
    if (k == "--reps") a.reps = std::max(1, std::atoi(v.c_str()));
    if (k == "--jitter") a.jitter = std::max(1, std::atoi(v.c_str()));
    if (k == "--only") a.only = v;
    if (k == "--voxel") a.voxel_mm = std::atof(v.c_str());
    if (k == "--builds") a.builds = std::max(1, std::atoi(v.c_str()));
    if (k == "--threads") a.threads = std::max(0, std::atoi(v.c_str()));
    if (k == "--profile") a.profile = v;
    if (k == "--compare-field-bound") a.compare = v;
  }
  return a;
}

/// Jittered poses about offset * axis: rotation up to 0.1 degree about a random
/// axis through the lower's centroid, translation up to 0.02 mm; pose 0 is unjittered.
std::vector<Isometry3d> Poses(double offset, const Vector3d& axis, const Vector3d& pivot, int n,
                              std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Isometry3d> poses;
  for (int i = 0; i < n; ++i) {
    Isometry3d X = Isometry3d::Identity();
    if (i > 0) {
      const Vector3d w(u(*rng), u(*rng), u(*rng));
      const double angle = RadiansFromDegrees(0.1) * u(*rng);
      X = Eigen::Translation3d(pivot) * Eigen::AngleAxisd(angle, w.normalized()) *
          Eigen::Translation3d(-pivot);
      X.translation() += 0.02 * Vector3d(u(*rng), u(*rng), u(*rng));
    }
    poses.push_back(Eigen::Translation3d(offset * axis) * X);
  }
  return poses;
}

const std::vector<double> kOffsets = {5.0, 2.0, 1.0,  0.7, 0.5,  0.3,
                                      0.2, 0.1, 0.05, 0.0, -0.1, -0.2};

void RunBoolean(const collision::SphereTree& lower, const collision::SphereTree& upper,
                const Args& args, const Vector3d& axis, const Vector3d& pivot) {
  std::printf("\nboolean (first_only, delta 0.1 mm): worst over %d poses of the median us\n",
              args.jitter);
  std::printf("offset  overlap  simple_us  tests  optimized_us  tests  explicit_us  tests\n");
  std::mt19937 rng(7);
  double worst[3] = {0, 0, 0};
  for (const double offset : kOffsets) {
    const auto poses = Poses(offset, axis, pivot, args.jitter, &rng);
    std::printf("%+6.2f", offset);
    bool first = true;
    int m = 0;
    for (const auto mode : {collision::SphereMode::kSimple, collision::SphereMode::kOptimized,
                            collision::SphereMode::kExplicit}) {
      double us = 0.0;
      std::size_t tests = 0;
      std::size_t btests = 0;
      bool overlap = false;
      for (const auto& X : poses) {
        collision::CollisionRequest req;
        req.spheres = mode;
        req.first_only = true;
        req.delta_mm = 0.1;
        collision::CollisionResult res;
        us = std::max(
            us, MedianMicros([&] { collision::Collide(lower, upper, X, req, &res); }, args.reps));
        tests = std::max(tests, res.node_tests);
        btests = std::max(btests, res.bound_tests);
        overlap = overlap || res.overlap;
      }
      if (first) std::printf("  %7s", overlap ? "yes" : "no");
      first = false;
      std::printf("  %9.1f  %5zu+%-5zu", us, tests, btests);
      worst[m] = std::max(worst[m], us);
      ++m;
    }
    std::printf("\n");
  }
  std::printf("worst: simple %.1f us, optimized %.1f us, explicit %.1f us\n", worst[0], worst[1],
              worst[2]);
}

// The sub-voxel oracle's query times: the worst over jittered poses of the median per offset.
void RunOracleSpeed(const collision::JawOracle& oracle, const Args& args, const Vector3d& axis,
                    const Vector3d& pivot) {
  std::printf(
      "\noracle kSubVoxel (band 0.1 mm, penetration search 0.3 mm): worst over %d poses "
      "of the median us\n",
      args.jitter);
  std::printf(
      "offset  cells_us  query_us(no pts)  query_us(pts)  cells  samples  contacts  max_pen\n");
  std::mt19937 rng(7);
  double worst_cells = 0.0, worst_no = 0.0, worst_pts = 0.0;
  for (const double offset : kOffsets) {
    const auto poses = Poses(offset, axis, pivot, args.jitter, &rng);
    double cells_us = 0.0, no_us = 0.0, pts_us = 0.0;
    collision::OracleResult res;
    for (const auto& X : poses) {
      collision::CellRequest creq;
      creq.cell_level = 1;
      creq.a_level = 1;
      creq.reach_mm = 0.3;
      creq.distance_bound = true;
      collision::CellResult cres;
      cells_us =
          std::max(cells_us, MedianMicros(
                                 [&] {
                                   collision::CollectCells(oracle.lower_tree(), oracle.upper_tree(),
                                                           X, creq, &cres);
                                 },
                                 args.reps));
      collision::OracleRequest req;
      req.level = collision::AccuracyLevel::kSubVoxel;
      req.keep_points = false;
      no_us = std::max(no_us, MedianMicros([&] { oracle.Query(X, req, &res); }, args.reps));
      req.keep_points = true;
      pts_us = std::max(pts_us, MedianMicros([&] { oracle.Query(X, req, &res); }, args.reps));
    }
    std::printf("%+6.2f  %8.1f  %16.1f  %13.1f  %5zu  %7zu  %8zu  %7.3f\n", offset, cells_us, no_us,
                pts_us, res.cells, res.samples_evaluated, res.contact_samples,
                res.max_penetration_mm);
    worst_cells = std::max(worst_cells, cells_us);
    worst_no = std::max(worst_no, no_us);
    worst_pts = std::max(worst_pts, pts_us);
  }
  std::printf("worst: CollectCells %.1f us, Query %.1f us (keep_points=false), %.1f us (true)\n",
              worst_cells, worst_no, worst_pts);
}

// The sub-voxel oracle's accuracy: its contacts against exact distances, and the exact contacts
// within 0.05 mm that the sub-voxel query misses (matched by sample position).
void RunOracleAccuracy(const collision::JawOracle& oracle, const Vector3d& axis) {
  std::vector<double> err;
  std::size_t missed = 0, exact_close = 0;
  for (const double offset : {0.1, 0.05, 0.0, -0.1}) {
    const Isometry3d X = Eigen::Translation3d(offset * axis) * Isometry3d::Identity();
    collision::OracleRequest req;
    req.level = collision::AccuracyLevel::kSubVoxel;
    collision::OracleResult sub, exact;
    oracle.Query(X, req, &sub);
    req.level = collision::AccuracyLevel::kExact;
    oracle.Query(X, req, &exact);
    for (const auto& c : sub.contacts) {
      collision::SignedDistanceSample s;
      if (oracle.lower_sdf().Exact(c.p_L, 0.5, &s))
        err.push_back(std::abs(s.distance - c.distance_mm));
    }
    std::vector<std::array<double, 3>> seen;
    for (const auto& c : sub.contacts) seen.push_back({c.p_L.x(), c.p_L.y(), c.p_L.z()});
    for (const auto& c : sub.penetrations) seen.push_back({c.p_L.x(), c.p_L.y(), c.p_L.z()});
    std::sort(seen.begin(), seen.end());
    for (const auto& c : exact.contacts) {
      if (c.distance_mm > 0.05) continue;
      ++exact_close;
      if (!std::binary_search(seen.begin(), seen.end(),
                              std::array<double, 3>{c.p_L.x(), c.p_L.y(), c.p_L.z()})) {
        ++missed;
      }
    }
  }
  std::sort(err.begin(), err.end());
  if (!err.empty()) {
    std::printf(
        "sub-voxel vs exact over %zu contact samples: median %.5f p95 %.5f max %.5f mm; "
        "exact contacts within 0.05 mm: %zu, missed by sub-voxel: %zu\n",
        err.size(), err[err.size() / 2], err[err.size() * 95 / 100], err.back(), exact_close,
        missed);
  }
}

void RunSdf(const std::shared_ptr<const io::TriangleMesh>& lower, const collision::VoxelGrid& grid,
            const Args& args) {
  std::printf("\nlower distance field at %.2f mm\n", grid.voxel_size_mm);
  std::vector<double> cpu;
  collision::NarrowBandSdf sdf;
  for (int i = 0; i < 3; ++i) {
    const double t0 = ThreadCpuSeconds();
    sdf = collision::NarrowBandSdf::Build(lower, grid);
    cpu.push_back(ThreadCpuSeconds() - t0);
  }
  std::sort(cpu.begin(), cpu.end());
  std::printf(
      "build: median calling-thread CPU %.3f s, wall %.3f s (last), %.1f MB, %zu band voxels\n",
      cpu[1], sdf.build_seconds(), static_cast<double>(sdf.MemoryBytes()) / 1e6,
      sdf.num_band_voxels());
  // Interpolate: points near the surface (triangle centroids pushed along the
  // normal by up to 0.1 mm), random order and a hot set of 1024.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  std::vector<Vector3d> pts;
  const auto& m = *lower;
  for (int i = 0; i < (1 << 16); ++i) {
    const std::size_t t = rng() % m.num_triangles();
    const Vector3d c = (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0;
    const Vector3d n =
        (m.corner(t, 1) - m.corner(t, 0)).cross(m.corner(t, 2) - m.corner(t, 0)).normalized();
    pts.push_back(c + u(rng) * n);
  }
  for (const std::size_t n : {std::size_t{1024}, pts.size()}) {
    double sum = 0.0;
    const int rounds = static_cast<int>((1u << 22) / n);
    const double us = MedianMicros(
        [&] {
          for (int r = 0; r < rounds; ++r) {
            for (std::size_t i = 0; i < n; ++i) {
              double d = 0.0;
              Vector3d g;
              if (sdf.Interpolate(pts[i], &d, &g)) sum += d + g.x();
            }
          }
        },
        std::max(3, args.reps / 5));
    std::printf("Interpolate with gradient, %zu points: %.1f ns/call (checksum %.3g)\n", n,
                1e3 * us / (static_cast<double>(rounds) * static_cast<double>(n)), sum);
  }
}

collision::OracleOptions BuildOptions(const Args& args) {
  collision::OracleOptions options;
  options.voxel_size_mm = args.voxel_mm;
  options.threads = args.threads;
  return options;
}

void RunBuild(const std::shared_ptr<const io::TriangleMesh>& lower,
              const std::shared_ptr<const io::TriangleMesh>& upper, const Args& args) {
  std::printf("\noracle builds at %.2f mm: wall s, process CPU s (all threads), MB, samples\n",
              args.voxel_mm);
  for (int i = 0; i < args.builds; ++i) {
    const double wall0 = ClockSeconds(CLOCK_MONOTONIC);
    const double cpu0 = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
    const collision::JawOracle oracle(lower, upper, BuildOptions(args));
    std::printf("build %d: %.3f s wall, %.3f s CPU, %.1f MB, %zu samples\n", i,
                ClockSeconds(CLOCK_MONOTONIC) - wall0,
                ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - cpu0,
                static_cast<double>(oracle.MemoryBytes()) / 1e6, oracle.num_samples());
  }
}

void RunDigest(const collision::JawOracle& oracle, const Args& args, const Vector3d& axis,
               const Vector3d& pivot) {
  std::mt19937 rng(7);
  io::Hasher64 all;
  std::size_t queries = 0;
  for (const double offset : kOffsets) {
    for (const auto& X : Poses(offset, axis, pivot, args.jitter, &rng)) {
      for (const auto level :
           {collision::AccuracyLevel::kVoxel, collision::AccuracyLevel::kSubVoxel,
            collision::AccuracyLevel::kExact}) {
        for (const bool residuals : {false, true}) {
          collision::OracleRequest req;
          req.level = level;
          req.residuals = residuals;
          req.pivot_L = pivot;
          collision::OracleResult res;
          oracle.Query(X, req, &res);
          collision::HashOracleResult(res, &all);
          ++queries;
        }
      }
    }
  }
  std::printf("digest of %zu answers at %.2f mm: %s (%zu samples)\n", queries, args.voxel_mm,
              io::HashHex(all.Finish()).c_str(), oracle.num_samples());
}

// Saves the oracle (bytes, then a file in the temporary folder), loads it --builds times with
// the file's pages dropped from the page cache first (cold) and kept (warm), and prints the
// digests of the built and the first loaded oracle (equal = bit-identical answers).
void RunSaved(const std::shared_ptr<const io::TriangleMesh>& lower,
              const std::shared_ptr<const io::TriangleMesh>& upper, const Args& args,
              const Vector3d& axis, const Vector3d& pivot) {
  const collision::OracleOptions options = BuildOptions(args);
  const collision::JawOracle built(lower, upper, options);
  double wall0 = ClockSeconds(CLOCK_MONOTONIC);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "occlude_oracle_sweep.oracle";
  collision::SaveOracleFile(built, file);
  std::printf("\nsaved oracle at %.2f mm: %.1f MB file, %.3f s to save (build %.3f s wall)\n",
              args.voxel_mm, static_cast<double>(std::filesystem::file_size(file)) / 1e6,
              ClockSeconds(CLOCK_MONOTONIC) - wall0, built.build_seconds());
  {
    const double t0 = ClockSeconds(CLOCK_MONOTONIC);
    const std::string bytes = collision::SaveOracle(built);
    std::printf("  to bytes: %.3f s wall\n", ClockSeconds(CLOCK_MONOTONIC) - t0);
    for (const auto& section : collision::DescribeOracleBytes(bytes))
      std::printf("  section %s: %.1f MB\n", section.tag.c_str(),
                  static_cast<double>(section.size) / 1e6);
  }
  for (int i = 0; i < args.builds; ++i) {
    for (const bool cold : {true, false}) {
      if (cold) {
        const int fd = ::open(file.c_str(), O_RDONLY);
        if (fd >= 0) {
          ::posix_fadvise(fd, 0, 0, POSIX_FADV_DONTNEED);
          ::close(fd);
        }
      }
      wall0 = ClockSeconds(CLOCK_MONOTONIC);
      const double cpu0 = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
      const collision::JawOracle loaded = collision::LoadOracleFile(file, lower, upper, options);
      std::printf("load %d (%s): %.3f s wall, %.3f s CPU\n", i, cold ? "cold" : "warm",
                  ClockSeconds(CLOCK_MONOTONIC) - wall0,
                  ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - cpu0);
      if (i == 0 && !cold) RunDigest(loaded, args, axis, pivot);
    }
  }
  RunDigest(built, args, axis, pivot);
  std::filesystem::remove(file);
}

// --compare-field-bound: the sub-voxel oracle with and without the field bound.
void RunCompareFieldBound(const std::shared_ptr<const io::TriangleMesh>& lower,
                          const std::shared_ptr<const io::TriangleMesh>& upper, const Args& args,
                          const Vector3d& axis, const Vector3d& pivot) {
  // The sub-voxel oracle with and without the field bound, built once each, queried in
  // alternating blocks at the same poses (so that a noisy machine slows both alike).
  collision::OracleOptions with, without;
  without.field_bound_mm = -1.0;
  const collision::JawOracle a(lower, upper, without), b(lower, upper, with);
  std::printf(
      "offset_mm, surface voxels + reach us, field bound us, ratio, cells a/b, node tests a/b, "
      "same\n");
  std::mt19937 rng(7);
  std::string list = args.compare;
  for (std::size_t start = 0; start < list.size();) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const double offset = std::atof(list.substr(start, comma - start).c_str());
    start = comma + 1;
    const std::vector<Isometry3d> poses = Poses(offset, axis, pivot, 16, &rng);
    collision::OracleRequest req;
    collision::OracleResult ra, rb;
    bool same = true;
    std::vector<double> ta, tb;
    for (int round = 0; round < 40; ++round) {
      for (int which = 0; which < 2; ++which) {
        const collision::JawOracle& o = which == 0 ? a : b;
        collision::OracleResult& r = which == 0 ? ra : rb;
        const double t0 = ThreadCpuSeconds();
        for (const Isometry3d& X : poses) o.Query(X, req, &r);
        (which == 0 ? ta : tb)
            .push_back(1e6 * (ThreadCpuSeconds() - t0) / static_cast<double>(poses.size()));
      }
      same = same && ra.contact_samples == rb.contact_samples &&
             ra.max_penetration_mm == rb.max_penetration_mm &&
             ra.contact_area_mm2 == rb.contact_area_mm2 &&
             ra.penetration_area_mm2 == rb.penetration_area_mm2 &&
             ra.deep_samples == rb.deep_samples;
    }
    std::sort(ta.begin(), ta.end());
    std::sort(tb.begin(), tb.end());
    const double ma = ta[ta.size() / 2], mb = tb[tb.size() / 2];
    std::printf("%+.2f, %.1f, %.1f, %.2f, %zu/%zu, %zu/%zu, %s\n", offset, ma, mb, ma / mb,
                ra.cells, rb.cells, ra.node_tests, rb.node_tests, same ? "yes" : "NO");
  }
}

// --profile OFFSET: one query repeated for 10 s of thread CPU (for a profiler).
void RunProfile(const std::shared_ptr<const io::TriangleMesh>& lower,
                const std::shared_ptr<const io::TriangleMesh>& upper, const Args& args,
                const Vector3d& axis, const Vector3d& /*pivot*/) {
  collision::OracleOptions oopt;
  if (const char* level = std::getenv("OCCLUDE_CELL_LEVEL")) oopt.cell_level = std::atoi(level);
  if (const char* bound = std::getenv("OCCLUDE_FIELD_BOUND"))
    oopt.field_bound_mm = std::atof(bound);
  const collision::JawOracle oracle(lower, upper, oopt);
  const Isometry3d X =
      Eigen::Translation3d(std::atof(args.profile.c_str()) * axis) * Isometry3d::Identity();
  collision::OracleRequest req;
  req.level = collision::AccuracyLevel::kSubVoxel;
  if (const char* search = std::getenv("OCCLUDE_PENETRATION_SEARCH"))
    req.penetration_search_mm = std::atof(search);
  collision::OracleResult res;
  const double t0 = ThreadCpuSeconds();
  std::size_t n = 0;
  // $OCCLUDE_PROFILE_QUERY=boolean: the explicit boolean Collide on the oracle's trees instead.
  const char* which = std::getenv("OCCLUDE_PROFILE_QUERY");
  const bool boolean = which != nullptr && std::string(which) == "boolean";
  if (which != nullptr && std::string(which) == "voxel")
    req.level = collision::AccuracyLevel::kVoxel;
  collision::CollisionRequest creq;
  creq.first_only = true;
  creq.delta_mm = 0.1;
  collision::CollisionResult cres;
  while (ThreadCpuSeconds() - t0 < 10.0) {
    if (boolean) {
      collision::Collide(oracle.lower_tree(), oracle.upper_tree(), X, creq, &cres);
    } else {
      oracle.Query(X, req, &res);
    }
    ++n;
  }
  if (boolean) {
    std::printf("profile: boolean, overlap %d, %zu bound tests\n", cres.overlap ? 1 : 0,
                cres.bound_tests);
  }
  std::printf(
      "profile: offset %s mm, %zu queries, %.1f us each, %zu cells, %zu node tests, %zu samples, "
      "%zu contacts\n",
      args.profile.c_str(), n, 1e6 * (ThreadCpuSeconds() - t0) / static_cast<double>(n), res.cells,
      res.node_tests, res.samples_evaluated, res.contact_samples);
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = Parse(argc, argv);
  const auto dir = bench::SharedCaseDir(args.case_name);
  if (!std::filesystem::exists(dir / "lower.stl")) {
    std::printf(
        "occlude_oracle_sweep: case %s not found under %s (set OCCLUDE_DATA_DIR); skipped\n",
        args.case_name.c_str(), bench::DataDir().c_str());
    return 0;
  }
  const app::JawPair jaws = app::LoadCaseFolder(dir);
  const auto& lower = jaws.lower_L;
  const auto& upper = jaws.upper_U;  // in L at the bite
  Vector3d axis = Vector3d::Zero();
  axis[args.axis] = 1.0;
  Vector3d pivot = Vector3d::Zero();
  for (const auto& v : lower->vertices) pivot += v;
  pivot /= static_cast<double>(lower->vertices.size());
  std::printf("case %s: lower %zu, upper %zu triangles; axis %d; reps %d\n", args.case_name.c_str(),
              lower->num_triangles(), upper->num_triangles(), args.axis, args.reps);

  if (!args.compare.empty()) {
    RunCompareFieldBound(lower, upper, args, axis, pivot);
    return 0;
  }
  if (!args.profile.empty()) {
    RunProfile(lower, upper, args, axis, pivot);
    return 0;
  }
  if (args.only == "build") {
    RunBuild(lower, upper, args);
    return 0;
  }
  if (args.only == "saved") {
    RunSaved(lower, upper, args, axis, pivot);
    return 0;
  }
  if (args.only == "digest") {
    RunDigest(collision::JawOracle(lower, upper, BuildOptions(args)), args, axis, pivot);
    return 0;
  }
  collision::SphereTreeOptions topt;
  topt.voxelize.voxel_size_mm = 0.2;
  if (args.only.empty() || args.only == "boolean") {
    double t0 = ThreadCpuSeconds();
    const auto lt = collision::SphereTree::Build(lower, topt);
    const double lower_s = ThreadCpuSeconds() - t0;
    t0 = ThreadCpuSeconds();
    const auto ut = collision::SphereTree::Build(upper, topt);
    std::printf("trees: lower %.3f s CPU %.1f MB, upper %.3f s CPU %.1f MB\n", lower_s,
                static_cast<double>(lt.stats().total_bytes()) / 1e6, ThreadCpuSeconds() - t0,
                static_cast<double>(ut.stats().total_bytes()) / 1e6);
    RunBoolean(lt, ut, args, axis, pivot);
  }
  if (args.only.empty() || args.only == "sdf") {
    collision::VoxelizeOptions vopt;
    vopt.voxel_size_mm = 0.2;
    RunSdf(lower, collision::Voxelize(*lower, vopt), args);
  }
  if (args.only.empty() || args.only == "oracle") {
    const double t0 = ThreadCpuSeconds();
    const collision::JawOracle oracle(lower, upper);
    std::printf("\noracle build: %.3f s wall, %.3f s calling-thread CPU, %.1f MB, %zu samples\n",
                oracle.build_seconds(), ThreadCpuSeconds() - t0,
                static_cast<double>(oracle.MemoryBytes()) / 1e6, oracle.num_samples());
    RunOracleSpeed(oracle, args, axis, pivot);
    RunOracleAccuracy(oracle, axis);
  }
  return 0;
}
