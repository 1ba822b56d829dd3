// `occlude bench --accuracy`: speed against accuracy. Every collision method
// (the contact oracle at each voxel size and accuracy level; the IST pair query
// with simple, optimized and explicit spheres at voxel level and with exact
// triangle refinement; FCL all-contacts and distance) is timed at the same
// seeded poses about the registered bite and scored against exact
// triangle-level ground truth (bench_accuracy_score_internal.h states the definitions).
//
// Poses: `poses` offsets along the occlusal axis, stratified over
// [offset_lo_mm, offset_hi_mm] (one uniform draw per stratum), each with the
// bench's seeded rigid jitter (rotation up to jitter_deg about the upper's
// centroid, translation up to jitter_mm across the axis). Query times are
// thread CPU time; each pose is queried `reps` times after one warm-up call.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench.h"

namespace occlude::app {

struct AccuracyOptions {
  std::vector<double> voxels_mm = {0.8, 0.4, 0.2, 0.1};
  int poses = 16;
  double offset_lo_mm = -0.2, offset_hi_mm = 1.0;
  double jitter_deg = 0.2, jitter_mm = 0.05;
  int reps = 3;  ///< timed queries per pose
  std::uint32_t seed = 1;
  double delta_mm = 0.1;           ///< contact band
  double truth_spacing_mm = 0.05;  ///< spacing of the fixed upper samples
  bool fcl = true;
  std::ostream* log = nullptr;
};

/// One method at one voxel size over all poses.
struct AccuracyRow {
  std::string method;   ///< ist, fcl
  std::string variant;  ///< simple, optimized, explicit, obb, obbrss
  std::string query;    ///< oracle, pairs, collide-all, distance
  std::string level;    ///< voxel, subvoxel, exact
  double voxel_mm = std::numeric_limits<double>::quiet_NaN();  ///< NaN for FCL
  int poses = 0;
  Summary us;  ///< median and max thread-CPU us per query
  double p95_us = 0.0;
  double median_err_mm = std::numeric_limits<double>::quiet_NaN();
  double p95_err_mm = std::numeric_limits<double>::quiet_NaN();
  double max_err_mm = std::numeric_limits<double>::quiet_NaN();
  std::size_t claims = 0, unscored = 0;
  bool contacts_defined = true;  ///< false: the query lists no contacts (missed/false empty)
  std::size_t truth_contacts = 0, truth_half = 0;
  std::size_t missed = 0, missed_half = 0, false_contacts = 0, false_double = 0;
  double pen_err_median_mm = std::numeric_limits<double>::quiet_NaN();
  double pen_err_max_mm = std::numeric_limits<double>::quiet_NaN();
  double build_s = 0.0;  ///< wall time to build what the query needs
  std::size_t bytes = 0;
  bool pareto = false;  ///< on the time / p95-error Pareto front
};

/// The seeded poses X_LU of the study.
std::vector<Eigen::Isometry3d> AccuracyPoses(const BenchCase& bench_case,
                                             const AccuracyOptions& options);

/// Runs every method; rows in a fixed order (FCL, then per voxel size the
/// oracle levels and the pair queries), with the Pareto flags set.
std::vector<AccuracyRow> RunAccuracy(const BenchCase& bench_case, const AccuracyOptions& options);

/// A method on the Pareto front must find the contacts: miss at most this
/// fraction of the truth contacts within half the band (else a query that
/// claims little, such as FCL's intersections only, would look exact).
inline constexpr double kParetoMaxMissedHalfBand = 0.01;
bool FindsTheContacts(const AccuracyRow& row);

/// Marks the rows on the Pareto front of (median_us, p95_err_mm) among the
/// rows that find the contacts: no other such row is at least as fast and at
/// least as accurate and better in one of them.
void MarkPareto(std::vector<AccuracyRow>* rows);

/// The CSV, opening with '#' comment lines (the definitions, the case and the machine).
std::string AccuracyCsv(const std::vector<AccuracyRow>& rows, const std::string& about);
/// The table the planner can pick voxel sizes from (JSON).
std::string AccuracyTableJson(const std::vector<AccuracyRow>& rows, const std::string& case_name,
                              const std::string& machine, const AccuracyOptions& options);
/// Charts (file name, PNG): time (log x) against p95 and max error (log y), Pareto front.
std::vector<std::pair<std::string, std::string>> AccuracyCharts(
    const std::vector<AccuracyRow>& rows, const std::string& subtitle);

}  // namespace occlude::app
