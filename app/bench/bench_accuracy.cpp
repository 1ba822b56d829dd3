// The speed-against-accuracy run of `occlude bench --accuracy` (see
// bench_accuracy.h): builds each method once, queries it at every pose, turns
// its answer into claims and scores them (bench_accuracy_score_internal.h).
#include "bench/bench_accuracy.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>
#include <random>

#include "base/percentile.h"
#include "bench/bench_accuracy_answers_internal.h"
#include "bench/bench_accuracy_score_internal.h"
#include "bench/bench_accuracy_truth_internal.h"
#include "bench/bench_poses_internal.h"
#include "bench/fcl_peer.h"
#include "occlude/collision/collide.h"
#include "occlude/collision/oracle.h"

namespace occlude::app {
namespace {

using collision::AccuracyLevel;
using collision::SphereMode;

void Log(const AccuracyOptions& options, const std::string& line) {
  if (options.log) *options.log << "accuracy: " << line << std::endl;
}

// One warm-up call, then `reps` timed calls (thread CPU, us) appended to `us`.
template <class F>
void TimeInto(std::vector<double>* us, int reps, F&& f) {
  f();
  for (int i = 0; i < reps; ++i) {
    const double t0 = ThreadCpuSeconds();
    f();
    us->push_back(1e6 * (ThreadCpuSeconds() - t0));
  }
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A row being measured: its times and its score.
struct Method {
  AccuracyRow row;
  std::vector<double> us;
  Score score;
};

Method NewMethod(const std::string& method, const std::string& variant, const std::string& query,
                 const std::string& level, double voxel_mm) {
  Method m;
  m.row.method = method;
  m.row.variant = variant;
  m.row.query = query;
  m.row.level = level;
  m.row.voxel_mm = voxel_mm;
  return m;
}

AccuracyRow Finish(Method m, int poses) {
  AccuracyRow& r = m.row;
  r.poses = poses;
  r.us = Summarize(&m.us);  // sorts
  r.p95_us = NearestRankPercentile(m.us, 0.95, kNaN);
  std::sort(m.score.errors.begin(), m.score.errors.end());
  r.median_err_mm = NearestRankPercentile(m.score.errors, 0.5, kNaN);
  r.p95_err_mm = NearestRankPercentile(m.score.errors, 0.95, kNaN);
  r.max_err_mm = m.score.errors.empty() ? r.p95_err_mm : m.score.errors.back();
  std::sort(m.score.pen_errors.begin(), m.score.pen_errors.end());
  r.pen_err_median_mm = NearestRankPercentile(m.score.pen_errors, 0.5, kNaN);
  r.pen_err_max_mm = m.score.pen_errors.empty() ? r.pen_err_median_mm : m.score.pen_errors.back();
  r.claims = m.score.claims;
  r.unscored = m.score.unscored;
  r.contacts_defined = m.score.contacts_defined;
  r.truth_contacts = m.score.truth_contacts;
  r.truth_half = m.score.truth_half;
  r.missed = m.score.missed;
  r.missed_half = m.score.missed_half;
  r.false_contacts = m.score.false_contacts;
  r.false_double = m.score.false_double;
  return r;
}

}  // namespace

std::vector<Eigen::Isometry3d> AccuracyPoses(const BenchCase& bc, const AccuracyOptions& options) {
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = std::max(1, options.poses);
  std::vector<double> offsets;
  for (int k = 0; k < n; ++k) {
    offsets.push_back(options.offset_lo_mm +
                      (options.offset_hi_mm - options.offset_lo_mm) * (k + unit(rng)) / n);
  }
  // Two poses per offset, the second jittered: keep the jittered one.
  const auto sweep =
      SweepPoses(bc, offsets, 2, options.jitter_deg, options.jitter_mm, options.seed + 1);
  std::vector<Eigen::Isometry3d> poses;
  for (const auto& at : sweep) poses.push_back(at[1]);
  return poses;
}

namespace {

// What every measurement shares: the case, the poses and the truth at each.
struct Study {
  const BenchCase& bc;
  const AccuracyOptions& options;
  const std::vector<Eigen::Isometry3d>& poses;
  std::vector<PoseTruth>& truths;
  int np() const { return static_cast<int>(poses.size()); }
};

// FCL all-contacts (OBB, OBBRSS) and distance (OBBRSS).
void MeasureFcl(const Study& st, std::vector<AccuracyRow>* rows) {
  for (const FclBv bv : {FclBv::kOBB, FclBv::kOBBRSS}) {
    const std::string variant = bv == FclBv::kOBB ? "obb" : "obbrss";
    const FclPeer peer(*st.bc.lower_L, *st.bc.upper_U, bv);
    Method all = NewMethod("fcl", variant, "collide-all", "exact", std::nan(""));
    Method dist = NewMethod("fcl", variant, "distance", "exact", std::nan(""));
    for (std::size_t k = 0; k < st.poses.size(); ++k) {
      const Eigen::Isometry3d& X = st.poses[k];
      TimeInto(&all.us, st.options.reps, [&] { (void)peer.CollideAll(X); });
      ScoreAnswer(FclPairsAnswer(peer.IntersectingPairs(X)), &st.truths[k], &all.score);
      if (bv != FclBv::kOBBRSS) continue;
      FclQueryResult r;
      TimeInto(&dist.us, st.options.reps, [&] { r = peer.Distance(X); });
      ScoreAnswer(FclDistanceAnswer(r), &st.truths[k], &dist.score);
    }
    all.row.build_s = dist.row.build_s = peer.build_seconds();
    all.row.bytes = dist.row.bytes = peer.approx_bytes();
    rows->push_back(Finish(std::move(all), st.np()));
    if (bv == FclBv::kOBBRSS) rows->push_back(Finish(std::move(dist), st.np()));
    Log(st.options, "FCL " + variant + " done");
  }
}

constexpr std::pair<AccuracyLevel, const char*> kLevels[] = {{AccuracyLevel::kVoxel, "voxel"},
                                                             {AccuracyLevel::kSubVoxel, "subvoxel"},
                                                             {AccuracyLevel::kExact, "exact"}};

// The oracle at its three levels at pose k: timed without point lists, then
// queried once more with them for the claims.
void MeasureOracle(const Study& st, const collision::JawOracle& oracle, double spacing_mm,
                   std::size_t k, std::vector<Method>* rows) {
  const Eigen::Isometry3d& X = st.poses[k];
  for (std::size_t l = 0; l < 3; ++l) {
    collision::OracleRequest req;
    req.level = kLevels[l].first;
    req.contact_band_mm = st.options.delta_mm;
    req.keep_points = false;
    collision::OracleResult result;
    TimeInto(&(*rows)[l].us, st.options.reps, [&] { oracle.Query(X, req, &result); });
    req.keep_points = true;
    oracle.Query(X, req, &result);
    ScoreAnswer(OracleAnswer(oracle, result, X, spacing_mm), &st.truths[k], &(*rows)[l].score);
  }
}

// The pair query (voxel level or with exact triangles) with each sphere mode
// at pose k. The modes report the same pairs (collide.h): each is timed, and
// scored once unless its answer differs.
void MeasurePairs(const Study& st, const collision::SphereTree& lower,
                  const collision::SphereTree& upper, bool exact, std::size_t k,
                  std::vector<Method>* group) {
  collision::CollisionRequest req;
  req.delta_mm = st.options.delta_mm;
  req.exact = exact;
  collision::CollisionResult results[3];
  for (std::size_t m = 0; m < 3; ++m) {
    req.spheres = kSphereModes[m];
    TimeInto(&(*group)[m].us, st.options.reps,
             [&] { collision::Collide(lower, upper, st.poses[k], req, &results[m]); });
  }
  auto answer = [&](const collision::CollisionResult& r) {
    return exact ? PairsExactAnswer(r) : PairsVoxelAnswer(upper, r, st.options.delta_mm);
  };
  Score first;
  ScoreAnswer(answer(results[2]), &st.truths[k], &first);
  for (std::size_t m = 0; m < 3; ++m) {
    const bool same = exact ? ContactKeys(results[m]) == ContactKeys(results[2])
                            : SortedPairs(results[m]) == SortedPairs(results[2]);
    if (same) {
      MergeScore(first, &(*group)[m].score);
      continue;
    }
    Log(st.options, std::string("warning: ") + collision::ToString(kSphereModes[m]) +
                        " spheres answered differently from explicit; scored separately");
    ScoreAnswer(answer(results[m]), &st.truths[k], &(*group)[m].score);
  }
}

// Every IST method at one voxel size (one oracle build serves them all).
void MeasureVoxelSize(const Study& st, double voxel, std::vector<AccuracyRow>* rows) {
  const double t0 = NowSeconds();
  const collision::OracleOptions oracle_options = OracleOptionsFor(voxel);
  const collision::JawOracle oracle(st.bc.lower_L, st.bc.upper_U, oracle_options);
  const double oracle_s = NowSeconds() - t0;
  Log(st.options,
      std::to_string(voxel) + " mm: oracle built in " + std::to_string(oracle_s) + " s; querying");
  std::vector<Method> oracle_rows, voxel_rows, exact_rows;
  for (const auto& [level, name] : kLevels) {
    oracle_rows.push_back(NewMethod("ist", "explicit", "oracle", name, voxel));
  }
  for (const SphereMode mode : kSphereModes) {
    voxel_rows.push_back(NewMethod("ist", collision::ToString(mode), "pairs", "voxel", voxel));
    exact_rows.push_back(NewMethod("ist", collision::ToString(mode), "pairs", "exact", voxel));
  }
  for (std::size_t k = 0; k < st.poses.size(); ++k) {
    MeasureOracle(st, oracle, oracle_options.sample_spacing_mm, k, &oracle_rows);
    MeasurePairs(st, oracle.lower_tree(), oracle.upper_tree(), false, k, &voxel_rows);
    MeasurePairs(st, oracle.lower_tree(), oracle.upper_tree(), true, k, &exact_rows);
    st.truths[k].ClearCache();
  }
  for (Method& m : oracle_rows) {
    m.row.build_s = oracle_s;
    m.row.bytes = oracle.MemoryBytes();
    rows->push_back(Finish(std::move(m), st.np()));
  }
  const auto& ls = oracle.lower_tree().stats();
  const auto& us = oracle.upper_tree().stats();
  for (auto* group : {&voxel_rows, &exact_rows}) {
    for (Method& m : *group) {
      m.row.build_s = ls.total_seconds() + us.total_seconds();
      m.row.bytes = ls.total_bytes() + us.total_bytes();
      rows->push_back(Finish(std::move(m), st.np()));
    }
  }
  Log(st.options, std::to_string(voxel) + " mm: done");
}

}  // namespace

std::vector<AccuracyRow> RunAccuracy(const BenchCase& bc, const AccuracyOptions& options) {
  const std::vector<Eigen::Isometry3d> poses = AccuracyPoses(bc, options);
  Log(options, "ground truth: lower distance grid and upper samples at " +
                   std::to_string(options.truth_spacing_mm) + " mm");
  const LowerDistance lower(bc.lower_L);
  const UpperSamples samples(bc.upper_U, options.truth_spacing_mm);
  std::vector<PoseTruth> truths;
  truths.reserve(poses.size());
  std::size_t contacts = 0;
  for (const auto& X : poses) {
    truths.emplace_back(lower, samples, X, options.delta_mm);
    contacts += truths.back().contact_ids().size();
  }
  Log(options, std::to_string(samples.size()) + " upper samples; " + std::to_string(contacts) +
                   " truth contacts over " + std::to_string(poses.size()) + " poses");
  const Study study{bc, options, poses, truths};
  std::vector<AccuracyRow> rows;
  if (options.fcl && FclPeer::Available()) MeasureFcl(study, &rows);
  for (const double voxel : options.voxels_mm) MeasureVoxelSize(study, voxel, &rows);
  MarkPareto(&rows);
  return rows;
}

bool FindsTheContacts(const AccuracyRow& r) {
  return r.contacts_defined && static_cast<double>(r.missed_half) <=
                                   kParetoMaxMissedHalfBand * static_cast<double>(r.truth_half);
}

void MarkPareto(std::vector<AccuracyRow>* rows) {
  // Errors closer than this are equal (rounding; the same claims scored twice).
  constexpr double kSameErrorMm = 1e-9;
  auto eligible = [](const AccuracyRow& r) {
    return std::isfinite(r.p95_err_mm) && r.us.median > 0 && FindsTheContacts(r);
  };
  for (AccuracyRow& r : *rows) {
    r.pareto = eligible(r);
    if (!r.pareto) continue;
    for (const AccuracyRow& o : *rows) {
      if (&o == &r || !eligible(o)) continue;
      const bool no_worse =
          o.us.median <= r.us.median && o.p95_err_mm <= r.p95_err_mm + kSameErrorMm;
      const bool better = o.us.median < r.us.median || o.p95_err_mm < r.p95_err_mm - kSameErrorMm;
      if (no_worse && better) {
        r.pareto = false;
        break;
      }
    }
  }
}

}  // namespace occlude::app
