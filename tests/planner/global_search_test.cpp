// The global search on the synthetic pair (5000 triangles, 0.8 then 0.5 mm):
// from the upper given in a uniformly random frame it finds the designed bite
// as its first proposal; the pose as given changes nothing; every pose is
// finite and feasible or flagged; the same result for one and two threads;
// progress in phase order; bad arches and settings rejected; the seat of a
// pose is the local search's.
#include "occlude/planner/global_search.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "planner_fixture.h"

namespace occlude::planner {
namespace {

// The designed bite is a seat: its own local search stays within this of it (plan_test.cpp).
constexpr double kBarMm = 0.3, kBarDeg = 1.0;
constexpr double kGlobalPenetrationLimitMm = 0.05 + 0.004;  // the limit and the settle's tolerance

JawArch SyntheticLowerArch() {
  const auto& c = test::Synthetic();
  return JawArchFromTeeth(ToothTops(c.pair.lower_L, Eigen::Vector3d::UnitY()),
                          Eigen::Vector3d::UnitY());
}

JawArch UpperArchIn(const io::TriangleMesh& upper, const Eigen::Vector3d& occlusal) {
  return JawArchFromTeeth(ToothTops(upper, occlusal), occlusal);
}

// A scan small enough for the sanitizer lane, wide enough for the synthetic pair.
GlobalRequest Request() {
  GlobalRequest g;
  g.lower_L = SyntheticLowerArch();
  g.upper_U = UpperArchIn(test::Synthetic().pair.upper_U, -Eigen::Vector3d::UnitY());
  g.local.num_threads = 2;
  g.local.max_proposals = 4;
#ifdef OCCLUDE_SANITIZED
  g.scan.sagittal_range_mm = 6.0;
  g.scan.sagittal_step_mm = 2.0;
  g.scan.lateral_range_mm = 0.0;
  g.scan.max_basins = 4;
  g.scan.max_refined = 2;
#else
  g.scan.sagittal_range_mm = 10.0;
  g.scan.max_basins = 6;
  g.scan.max_refined = 3;
#endif
  return g;
}

// The search with the upper in its own frame (computed once for the tests that share it).
const GlobalResult& Baseline() {
  static const GlobalResult* r = new GlobalResult(GlobalSearch(test::CoarseToFine(), Request()));
  return *r;
}

PoseError ToDesign(const Eigen::Isometry3d& X_LU) {
  const auto& c = test::Synthetic();
  return ComparePoses(X_LU, c.pair.X_LU, c.points_U);
}

TEST(GlobalSearchTest, FindsTheDesignedBiteFirst) {
  const GlobalResult& r = Baseline();
  ASSERT_FALSE(r.proposals.empty());
  const PoseError e = ToDesign(r.proposals.front().proposal.X_LU);
  EXPECT_LE(e.translation_mm, kBarMm);
  EXPECT_LE(e.rotation_deg, kBarDeg);
  EXPECT_GT(r.scan_poses, 0);
  EXPECT_FALSE(r.basins.empty());
  EXPECT_GT(r.cpu_seconds, 0.0);
  // Its shift from the aligned pose is the shift between the two poses.
  const GlobalProposal& p = r.proposals.front();
  const ArchShift s = ShiftBetween(r.alignment.X_LU, p.proposal.X_LU, r.pivot_L, Request().lower_L);
  EXPECT_NEAR(p.from_aligned.sagittal_mm, s.sagittal_mm, 1e-9);
  EXPECT_TRUE(ApplyShift(r.alignment.X_LU, p.from_aligned, r.pivot_L, Request().lower_L)
                  .isApprox(p.proposal.X_LU, 1e-9));
}

TEST(GlobalSearchTest, EveryPoseIsFiniteAndFeasibleOrFlagged) {
  const GlobalResult& r = Baseline();
  for (std::size_t k = 0; k < r.proposals.size(); ++k) {
    const Proposal& p = r.proposals[k].proposal;
    EXPECT_TRUE(p.X_LU.matrix().allFinite()) << k;
    if (p.evaluation.feasible) {
      EXPECT_LE(p.evaluation.constrained_penetration_mm, kGlobalPenetrationLimitMm) << k;
    } else {
      EXPECT_TRUE(p.status == SolveStatus::kInfeasible || p.status == SolveStatus::kFailed) << k;
    }
    for (std::size_t j = 0; j < k; ++j) {
      EXPECT_TRUE(DistinctPoses(p.X_LU, r.proposals[j].proposal.X_LU, test::Synthetic().points_U,
                                Request().local))
          << j << " " << k;
    }
  }
}

// The pose as given only sets from_given: the seats are the same, bit for bit.
TEST(GlobalSearchTest, ThePoseAsGivenChangesNothing) {
  GlobalRequest g = Request();
  g.local.X_LU_start = Eigen::Translation3d(40.0, -20.0, 5.0) *
                       Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 1, 0).normalized());
  const GlobalResult r = GlobalSearch(test::CoarseToFine(), g);
  const GlobalResult& base = Baseline();
  ASSERT_EQ(r.proposals.size(), base.proposals.size());
  for (std::size_t k = 0; k < r.proposals.size(); ++k) {
    EXPECT_TRUE(r.proposals[k].proposal.X_LU.isApprox(base.proposals[k].proposal.X_LU, 0.0)) << k;
  }
}

TEST(GlobalSearchTest, SameResultForOneAndTwoThreads) {
  GlobalRequest g = Request();
  g.local.num_threads = 1;
  const GlobalResult r = GlobalSearch(test::CoarseToFine(), g);
  const GlobalResult& base = Baseline();
  ASSERT_EQ(r.basins.size(), base.basins.size());
  ASSERT_EQ(r.proposals.size(), base.proposals.size());
  for (std::size_t k = 0; k < r.proposals.size(); ++k) {
    EXPECT_TRUE(r.proposals[k].proposal.X_LU.isApprox(base.proposals[k].proposal.X_LU, 0.0)) << k;
    EXPECT_EQ(r.proposals[k].basin, base.proposals[k].basin);
  }
}

// The upper mesh in a uniformly random frame 20-60 mm away (as scanned apart), its oracles built
// in that frame and its arch found there: the search still puts the designed bite first.
TEST(GlobalSearchTest, FindsTheDesignedBiteFromARandomFrame) {
  const auto& c = test::Synthetic();
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::Quaterniond q = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
  const Eigen::Vector3d away = 35.0 * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
  const Eigen::Isometry3d M = Eigen::Translation3d(away) * q;  // U -> the upper's file frame
  auto upper = std::make_shared<io::TriangleMesh>(c.pair.upper_U.Transformed(M));
  const collision::JawOracle coarse(c.lower, upper, StageOracleOptions({}, {0.8, 0.5}, 0));
  const collision::JawOracle fine(c.lower, upper, StageOracleOptions({}, {0.8, 0.5}, 1));
  const OracleSchedule schedule{{&coarse, collision::AccuracyLevel::kSubVoxel},
                                {&fine, collision::AccuracyLevel::kSubVoxel}};
  GlobalRequest request = Request();
  request.upper_U = UpperArchIn(*upper, M.linear() * -Eigen::Vector3d::UnitY());
  const GlobalResult r = GlobalSearch(schedule, request);
  ASSERT_FALSE(r.proposals.empty());
  const PoseError e = ToDesign(r.proposals.front().proposal.X_LU * M);
  EXPECT_LE(e.translation_mm, kBarMm);
  EXPECT_LE(e.rotation_deg, kBarDeg);
}

TEST(GlobalSearchTest, ReportsProgressInPhaseOrder) {
  GlobalRequest g = Request();
  g.scan.sagittal_range_mm = 2.0;
  g.scan.lateral_range_mm = 0.0;
  g.scan.max_basins = 2;
  g.scan.max_refined = 1;
  std::vector<std::pair<GlobalRequest::Phase, std::pair<int, int>>> calls;
  g.on_progress = [&](GlobalRequest::Phase phase, int done, int total) {
    calls.push_back({phase, {done, total}});
  };
  GlobalSearch(test::CoarseToFine(), g);
  ASSERT_FALSE(calls.empty());
  EXPECT_EQ(calls.front().first, GlobalRequest::Phase::kScan);
  EXPECT_EQ(calls.back().first, GlobalRequest::Phase::kRefine);
  for (std::size_t i = 1; i < calls.size(); ++i) {
    EXPECT_GE(static_cast<int>(calls[i].first), static_cast<int>(calls[i - 1].first));
    if (calls[i].first == calls[i - 1].first) {
      EXPECT_GT(calls[i].second.first, calls[i - 1].second.first);
    }
  }
  for (const auto& [phase, dt] : calls) EXPECT_LE(dt.first, dt.second) << ToString(phase);
}

void ExpectSearchRejected(const GlobalRequest& g, const std::string& words) {
  try {
    GlobalSearch(test::CoarseToFine(), g);
    ADD_FAILURE() << "accepted; expected an error naming '" << words << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(GlobalSearchTest, RejectsBadArchesAndSettings) {
  GlobalRequest g = Request();
  g.upper_U = g.lower_L;  // the lower's arch given for the upper
  ExpectSearchRejected(g, "cannot face each other");
  g = Request();
  // Upside down: occlusal and lateral both reversed (the handedness survives), so the arch
  // points into the upper jaw.
  g.upper_U.occlusal_J = -g.upper_U.occlusal_J;
  g.upper_U.lateral_J = -g.upper_U.lateral_J;
  ExpectSearchRejected(g, "upper arch: occlusal_J points into the jaw");
  g = Request();
  g.upper_U.curve_J.clear();  // no teeth found
  ExpectSearchRejected(g, "curve_J: needs at least 4 points");
  g = Request();
  g.scan.sagittal_step_mm = 0.0;
  ExpectSearchRejected(g, "GlobalRequest.scan.sagittal_step_mm");
  g = Request();
  g.scan.max_refined = g.scan.max_basins + 1;
  ExpectSearchRejected(g, "GlobalRequest.scan.max_refined");
  g = Request();
  g.alignment.overjet_mm = 50.0;
  ExpectSearchRejected(g, "GlobalRequest.alignment");
  g = Request();
  g.ranking.comparable_contact = -0.5;
  ExpectSearchRejected(g, "SeatRanking.comparable_contact");
  g = Request();
  g.local.max_penetration_mm = -1.0;
  ExpectSearchRejected(g, "PlanRequest.max_penetration_mm");
  EXPECT_THROW(GlobalSearch({}, Request()), std::invalid_argument);
  OracleSchedule no_oracle = test::CoarseToFine();
  no_oracle.back().oracle = nullptr;
  EXPECT_THROW(GlobalSearch(no_oracle, Request()), std::invalid_argument);
}

// The scan visits every grid pose: per axis the multiples of the step within the range.
TEST(GlobalSearchTest, ScansTheWholeGrid) {
  const GlobalScanSettings s = Request().scan;
  auto values = [](double range, double step) {
    int n = 0;
    for (double v = -range; v <= range + 1e-9; v += step) ++n;
    return n;
  };
  EXPECT_EQ(Baseline().scan_poses, values(s.sagittal_range_mm, s.sagittal_step_mm) *
                                       values(s.lateral_range_mm, s.lateral_step_mm) *
                                       values(s.yaw_range_deg, s.yaw_step_deg) *
                                       values(s.pitch_range_deg, s.pitch_step_deg));
}

// The molar relationship (clinical.md) of the synthetic pair at X_LU, mean of both sides, mm:
// the upper first molar's mb cusp from the lower first molar's buccal groove along the lower's
// mesio-distal direction (+ = upper mesial). 0 at the designed bite, about +7 at class2_shift_L.
double MolarOffset(const Eigen::Isometry3d& X_LU) {
  const io::SyntheticJawPair& pair = test::Synthetic().pair;
  auto at = [&pair](io::Jaw jaw, int fdi, io::LandmarkType type) {
    for (const io::Landmark& m : pair.landmarks) {
      if (m.jaw == jaw && m.tooth_fdi == fdi && m.type == type) return m.p;
    }
    ADD_FAILURE() << "no landmark " << fdi << " " << io::ToString(type);
    return Eigen::Vector3d(Eigen::Vector3d::Zero());
  };
  const Eigen::Vector3d occlusal = pair.occlusal_axis_L;
  double sum = 0.0;
  for (const auto& [upper, lower] : {std::pair{16, 46}, std::pair{26, 36}}) {
    using T = io::LandmarkType;
    const Eigen::Vector3d groove = 0.5 * (at(io::Jaw::kLower, lower, T::kMbCusp) +
                                          at(io::Jaw::kLower, lower, T::kMiddleBuccalCusp));
    Eigen::Vector3d t =
        at(io::Jaw::kLower, lower, T::kMesial) - at(io::Jaw::kLower, lower, T::kDistal);
    t = (t - t.dot(occlusal) * occlusal).normalized();
    sum += (X_LU * at(io::Jaw::kUpper, upper, T::kMbCusp) - groove).dot(t);
  }
  return 0.5 * sum;
}

// A judge that asks for the molar relationship `target_mm` (the ranking term |offset - target|),
// and with `hard` admits only seats within the Class I band of it (1.5 mm, clinical.md).
SeatRanking MolarRanking(double target_mm, bool hard) {
  SeatRanking ranking;
  ranking.judge = [target_mm, hard](const GlobalProposal& seat) {
    SeatJudgement j;
    j.penalty = std::abs(MolarOffset(seat.proposal.X_LU) - target_mm);
    j.admissible = !hard || j.penalty <= 1.5;
    return j;
  };
  return ranking;
}

// Started a cusp period off (the upper given at the full-cusp Class II seat, class2_shift_L from
// the bite), the search finds both seats; a judge preferring Class I molars ranks the designed
// bite first, one preferring the Class II finish ranks that first, and as a hard constraint
// Class I sets the Class II seat aside.
TEST(GlobalSearchTest, AClinicalJudgeRanksTheSeats) {
  const auto& c = test::Synthetic();
  GlobalRequest g = Request();
  g.local.X_LU_start = Eigen::Translation3d(c.pair.class2_shift_L) * c.pair.X_LU;
  g.local.max_proposals = 8;  // every distinct seat, so that the re-rankings below see them all
  // Along the arch only (both seats lie on it), cheap enough for the sanitizer lane.
  g.scan = {};
  g.scan.sagittal_range_mm = 10.0;
  g.scan.sagittal_step_mm = 1.0;
  g.scan.lateral_range_mm = g.scan.yaw_range_deg = g.scan.pitch_range_deg = 0.0;
  g.scan.max_basins = 6;
  g.scan.max_refined = 4;
  g.ranking = MolarRanking(0.0, false);
  const GlobalResult r = GlobalSearch(test::CoarseToFine(), g);
  ASSERT_GE(r.proposals.size(), 2u);
  // Each seat's depth is the seat objective's drop from the jaws apart: positive, and in the
  // opposite order of the seat cost (one sample set, one open cost).
  for (const GlobalProposal& p : r.proposals) {
    EXPECT_GT(p.seat_depth, 0.0);
    EXPECT_NEAR(p.seat_depth + p.proposal.seat_cost,
                r.proposals.front().seat_depth + r.proposals.front().proposal.seat_cost, 1e-9);
  }
  const GlobalProposal& first = r.proposals.front();
  const PoseError e = ToDesign(first.proposal.X_LU);
  EXPECT_LE(e.translation_mm, kBarMm);
  EXPECT_LE(e.rotation_deg, kBarDeg);
  EXPECT_NEAR(first.from_given.sagittal_mm, -c.pair.class2_shift_L.norm(), 1.0);
  EXPECT_LE(first.judgement.penalty, 1.0);
  bool class2_found = false;
  for (const GlobalProposal& p : r.proposals)
    class2_found |= std::abs(MolarOffset(p.proposal.X_LU) - 7.0) <= 1.5;
  ASSERT_TRUE(class2_found) << "the Class II seat is not among the proposals";
  // It competes on the penalty: deep enough (62 % of the designed bite's depth here).
  double deepest = 0.0;
  for (const GlobalProposal& p : r.proposals) deepest = std::max(deepest, p.seat_depth);
  for (const GlobalProposal& p : r.proposals) {
    if (std::abs(MolarOffset(p.proposal.X_LU) - 7.0) <= 1.5) {
      EXPECT_GE(p.seat_depth, SeatRanking{}.comparable_depth * deepest);
    }
  }

  const RankedSeats class2 = RankSeats(r.proposals, MolarRanking(7.0, false), 8);
  EXPECT_NEAR(MolarOffset(class2.proposals.front().proposal.X_LU), 7.0, 1.5);
  const RankedSeats hard = RankSeats(r.proposals, MolarRanking(0.0, true), 8);
  ASSERT_FALSE(hard.proposals.empty());
  EXPECT_TRUE(hard.proposals.front().proposal.X_LU.isApprox(first.proposal.X_LU, 0.0));
  for (const GlobalProposal& p : hard.proposals)
    EXPECT_LE(std::abs(MolarOffset(p.proposal.X_LU)), 1.5);
  ASSERT_FALSE(hard.excluded.empty());
  EXPECT_EQ(hard.proposals.size() + hard.excluded.size(), r.proposals.size());
}

// The seat of a pose is the local search from it: one start, the request's solver.
TEST(SeatOfTest, IsTheLocalSearchFromThePose) {
  const auto& c = test::Synthetic();
  PlanRequest settings;
  settings.num_threads = 1;
  const Proposal seat = SeatOf(test::CoarseToFine(), c.pair.X_LU, settings);
  const PoseError e = ToDesign(seat.X_LU);
  EXPECT_LE(e.translation_mm, kBarMm);
  EXPECT_LE(e.rotation_deg, kBarDeg);
  PlanRequest one = settings;
  one.X_LU_start = c.pair.X_LU;
  one.num_starts = 1;
  one.num_global_samples = 0;
  one.max_proposals = 1;
  const PlanResult plan = Plan(test::CoarseToFine(), one);
  ASSERT_EQ(plan.proposals.size(), 1u);
  EXPECT_TRUE(seat.X_LU.isApprox(plan.proposals.front().X_LU, 0.0));
}

}  // namespace
}  // namespace occlude::planner
