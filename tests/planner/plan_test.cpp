// The planner on the synthetic pair: every solver returns near the ground
// truth from perturbed starts, within the penetration limit; locks, bounds,
// distinct proposals, determinism, hard starts and failure reporting.
#include "occlude/planner/plan.h"

#include <gtest/gtest.h>

#include <cmath>

#include "planner_fixture.h"

namespace occlude::planner {
namespace {

using test::PerturbedRequest;
using test::Synthetic;

// The synthetic bite locks (contacts on cusp inclines facing every direction), so the designed
// pose is the seat the solvers must find again: the success bar, 0.3 mm at the
// reference points and 1 degree. (Measured with plan_measure on 10k triangles, 0.8/0.4 mm:
// median 0.12 mm / 0.13 deg, most of it the allowed 0.05 mm of closing.)
constexpr double kReturnToleranceMm = 0.3;
constexpr double kReturnToleranceDeg = 1.0;
// The limit plus the final settle's bisection tolerance (0.003 mm).
constexpr double kPenetrationLimitMm = 0.05 + 0.004;

const OracleSchedule& ScheduleFor(SolverKind kind) {
  return kind == SolverKind::kCoarseToFine ? test::CoarseToFine() : Synthetic().schedule.stages;
}

class SolverReturnTest : public ::testing::TestWithParam<SolverKind> {};

TEST_P(SolverReturnTest, ReturnsNearGroundTruthFromPerturbedStart) {
  const auto& c = Synthetic();
  PlanRequest req = PerturbedRequest(GetParam(), 1.0, 2.0);
  const PlanResult res = Plan(ScheduleFor(GetParam()), req);
  ASSERT_FALSE(res.proposals.empty());
  const Proposal& p = res.proposals.front();
  const PoseError e = ComparePoses(p.X_LU, c.pair.X_LU, c.points_U);
  EXPECT_LE(e.translation_mm, kReturnToleranceMm) << ToString(GetParam()) << " " << p.message;
  EXPECT_LE(e.rotation_deg, kReturnToleranceDeg) << ToString(GetParam());
  EXPECT_LE(p.evaluation.constrained_penetration_mm, kPenetrationLimitMm);
  EXPECT_TRUE(p.evaluation.feasible);
  EXPECT_GT(p.evaluation.contact_area_mm2, 1.0);
  EXPECT_TRUE(p.X_LU.matrix().allFinite());
  // Ceres' rounds of solve and settle end converged or by their round limit, which the
  // status and the message say (not the evaluation budget: far from spent here).
  EXPECT_TRUE(p.status == SolveStatus::kConverged || p.status == SolveStatus::kMaxIterations)
      << ToString(p.status);
  EXPECT_LT(p.evaluations, req.max_evaluations);
  if (p.status == SolveStatus::kMaxIterations) {
    EXPECT_NE(p.message.find("rounds of solve and settle"), std::string::npos) << p.message;
  }
}

// NLopt: see NloptSolversStayFeasible.
INSTANTIATE_TEST_SUITE_P(LeastSquaresSolvers, SolverReturnTest,
                         ::testing::Values(SolverKind::kCeres, SolverKind::kCoarseToFine),
                         [](const ::testing::TestParamInfo<SolverKind>& param_info) {
                           std::string n = ToString(param_info.param);
                           for (char& ch : n) ch = ch == '-' ? '_' : ch;
                           return n;
                         });

// The NLopt solvers minimize the same seat cost derivative-free (AUGLAG around BOBYQA by
// default). Measured with `occlude validate --synthetic 5000 --voxels 0.5 --solver nlopt-local
// --starts 8 --magnitudes 1:2`: 62 % of the runs within 0.3 mm (COBYLA: 25 %), so from the
// three fixed perturbations here at least one must return within 0.3 mm, and every result must
// be feasible and finite.
TEST(PlanTest, NloptSolversStayFeasibleAndMostlyReturn) {
  const auto& c = Synthetic();
  for (SolverKind kind : {SolverKind::kNloptLocal, SolverKind::kNloptGlobal}) {
    int returned = 0;
#ifdef OCCLUDE_SANITIZED
    // The sanitizer lane looks for memory and UB errors: one start of each kind (the
    // release lane checks that one of three returns).
    constexpr int kVariants = 1;
#else
    constexpr int kVariants = 3;
#endif
    for (int variant = 0; variant < kVariants; ++variant) {
      const PlanRequest req = PerturbedRequest(kind, 1.0, 2.0, variant);
      const PlanResult res = Plan(c.schedule.stages, req);
      ASSERT_FALSE(res.proposals.empty());
      const Proposal& p = res.proposals.front();
      EXPECT_TRUE(p.evaluation.feasible) << ToString(kind) << " " << p.message;
      EXPECT_LE(p.evaluation.constrained_penetration_mm, kPenetrationLimitMm);
      EXPECT_TRUE(p.X_LU.matrix().allFinite());
      EXPECT_GT(p.evaluations, 10);
      const PoseError e = ComparePoses(p.X_LU, c.pair.X_LU, c.points_U);
      returned +=
          e.translation_mm <= kReturnToleranceMm && e.rotation_deg <= kReturnToleranceDeg ? 1 : 0;
    }
    if (kVariants == 3) {
      EXPECT_GE(returned, 1) << ToString(kind);
    }
  }
}

// The synthetic pair's full-cusp Class II alternative (the upper a premolar width mesial) is a
// seat of its own: from near it the search stays there rather than sliding back to the designed
// bite, with contact comparable to the bite's. Measured with occlude_synthetic_basins (5,000
// triangles, 0.8/0.4 mm): the seat lies 0.16 mm short of the shift and 0.7 deg off it, with
// 75 % of the bite's contact; bars here: 0.6 mm / 1.5 deg and 40 %.
TEST(PlanTest, ClassTwoAlternativeIsASeatOfItsOwn) {
  constexpr double kSeatMm = 0.6, kSeatDeg = 1.5, kContactShare = 0.4;
  const auto& c = Synthetic();
  const Eigen::Isometry3d X_alt = Eigen::Translation3d(c.pair.class2_shift_L) * c.pair.X_LU;
  PlanRequest near_bite = PerturbedRequest(SolverKind::kCoarseToFine, 0.5, 1.0);
  const Proposal bite = Plan(test::CoarseToFine(), near_bite).proposals.front();
  PlanRequest req = near_bite;
  PoseParameters perturb;
  perturb.translation_mm = Eigen::Vector3d(0.3, -0.2, 0.3);
  perturb.rotation_deg = Eigen::Vector3d(-0.5, 0.6, 0.4);
  req.X_LU_start = ComposePose(perturb, X_alt * c.points_U[0], X_alt);
  const PlanResult res = Plan(test::CoarseToFine(), req);
  ASSERT_FALSE(res.proposals.empty());
  const Proposal& p = res.proposals.front();
  const PoseError to_alt = ComparePoses(p.X_LU, X_alt, c.points_U);
  EXPECT_LE(to_alt.translation_mm, kSeatMm);
  EXPECT_LE(to_alt.rotation_deg, kSeatDeg);
  EXPECT_GT(ComparePoses(p.X_LU, c.pair.X_LU, c.points_U).translation_mm,
            0.5 * c.pair.class2_shift_L.norm());
  EXPECT_TRUE(p.evaluation.feasible);
  EXPECT_GE(p.evaluation.contact_area_mm2, kContactShare * bite.evaluation.contact_area_mm2)
      << "bite " << bite.evaluation.contact_area_mm2;
  EXPECT_GT(p.evaluation.posterior_left_mm2, 0.0);
  EXPECT_GT(p.evaluation.posterior_right_mm2, 0.0);
}

TEST(PlanTest, LockedDofsStayFixed) {
  PlanRequest req = PerturbedRequest(SolverKind::kCeres, 0.5, 1.0);
  req.locked = {true, false, false, false, true, false};  // x translation, y rotation
  const PlanResult res = Plan(Synthetic().schedule.stages, req);
  ASSERT_FALSE(res.proposals.empty());
  const PoseParameters& p = res.proposals.front().params;
  EXPECT_NEAR(p.translation_mm.x(), 0.0, 1e-9);
  EXPECT_NEAR(p.rotation_deg.y(), 0.0, 1e-6);
}

TEST(PlanTest, BoundsRespected) {
  for (SolverKind kind : {SolverKind::kNloptLocal, SolverKind::kCeres}) {
    PlanRequest req = PerturbedRequest(kind, 1.0, 2.0);
    req.lower_bound.translation_mm = Eigen::Vector3d(-0.2, -3.0, -0.2);
    req.upper_bound.translation_mm = Eigen::Vector3d(0.2, 3.0, 0.2);
    req.lower_bound.rotation_deg = Eigen::Vector3d::Constant(-0.5);
    req.upper_bound.rotation_deg = Eigen::Vector3d::Constant(0.5);
    const PlanResult res = Plan(Synthetic().schedule.stages, req);
    ASSERT_FALSE(res.proposals.empty());
    const PoseParameters& p = res.proposals.front().params;
    for (int i = 0; i < 3; ++i) {
      EXPECT_GE(p.translation_mm[i], req.lower_bound.translation_mm[i] - 1e-9)
          << ToString(kind) << i;
      EXPECT_LE(p.translation_mm[i], req.upper_bound.translation_mm[i] + 1e-9)
          << ToString(kind) << i;
      // The rotation vector's norm bounds each component of the composed rotation.
      EXPECT_LE(std::abs(p.rotation_deg[i]), 0.5 + 1e-6) << ToString(kind) << i;
    }
  }
}

TEST(PlanTest, ProposalsAreDistinctAndSorted) {
  PlanRequest req = PerturbedRequest(SolverKind::kNloptGlobal, 1.0, 2.0);
#ifdef OCCLUDE_SANITIZED
  req.num_starts = 3;
#else
  req.num_starts = 4;
#endif
  req.num_global_samples = 12;
  req.max_proposals = 3;
  req.num_threads = 2;
  const PlanResult res = Plan(Synthetic().schedule.stages, req);
  ASSERT_GE(res.proposals.size(), 1u);
  const auto& pts = Synthetic().points_U;
  for (std::size_t i = 0; i < res.proposals.size(); ++i) {
    for (std::size_t j = i + 1; j < res.proposals.size(); ++j) {
      EXPECT_TRUE(DistinctPoses(res.proposals[i].X_LU, res.proposals[j].X_LU, pts, req))
          << i << " " << j;
      if (res.proposals[i].evaluation.feasible && res.proposals[j].evaluation.feasible) {
        EXPECT_LE(res.proposals[i].seat_cost, res.proposals[j].seat_cost);
      }
    }
  }
}

TEST(PlanTest, DeterministicForSeedAndThreads) {
  PlanRequest req = PerturbedRequest(SolverKind::kNloptLocal, 1.0, 2.0);
#ifdef OCCLUDE_SANITIZED
  req.num_starts = 2;  // one per thread: still two threads finishing in either order
#else
  req.num_starts = 3;
#endif
  req.num_threads = 2;
  req.max_proposals = 3;
  req.seed = 11;
  const PlanResult a = Plan(Synthetic().schedule.stages, req);
  const PlanResult b = Plan(Synthetic().schedule.stages, req);
  ASSERT_EQ(a.proposals.size(), b.proposals.size());
  for (std::size_t i = 0; i < a.proposals.size(); ++i) {
    EXPECT_TRUE(a.proposals[i].X_LU.isApprox(b.proposals[i].X_LU, 0.0)) << i;
    EXPECT_EQ(a.proposals[i].start_index, b.proposals[i].start_index);
  }
}

// The coarse-then-fine path (several starts on the coarse stage, the best distinct refined):
// the same proposals, bit for bit, from one thread and from two.
TEST(PlanTest, CoarseToFineSameForOneAndTwoThreads) {
  PlanRequest req = PerturbedRequest(SolverKind::kCoarseToFine, 1.0, 2.0);
  req.num_starts = 3;
  req.num_global_samples = 6;
  req.max_proposals = 2;
  req.seed = 3;
  const PlanResult one = Plan(test::CoarseToFine(), req);
  req.num_threads = 2;
  const PlanResult two = Plan(test::CoarseToFine(), req);
  ASSERT_EQ(one.proposals.size(), two.proposals.size());
  ASSERT_GE(one.starts_run, 2);
  for (std::size_t i = 0; i < one.proposals.size(); ++i) {
    EXPECT_TRUE(one.proposals[i].X_LU.isApprox(two.proposals[i].X_LU, 0.0)) << i;
    EXPECT_EQ(one.proposals[i].start_index, two.proposals[i].start_index);
    EXPECT_EQ(one.proposals[i].evaluations, two.proposals[i].evaluations);
  }
  EXPECT_EQ(one.total_evaluations, two.total_evaluations);
}

// One start (refine's case) spreads its loops over the samples on every thread (ForBlocks): the
// same proposal, bit for bit, its evaluations and seat cost, from one thread and from two, for
// each least-squares and settle path.
TEST(PlanTest, OneStartSameForOneAndTwoThreads) {
  for (const SolverKind kind : {SolverKind::kCeres, SolverKind::kCoarseToFine}) {
    PlanRequest req = PerturbedRequest(kind, 1.0, 2.0, 1);
    const PlanResult one = Plan(ScheduleFor(kind), req);
    req.num_threads = 2;
    const PlanResult two = Plan(ScheduleFor(kind), req);
    ASSERT_EQ(one.proposals.size(), 1u) << ToString(kind);
    ASSERT_EQ(two.proposals.size(), 1u) << ToString(kind);
    const Proposal &a = one.proposals[0], &b = two.proposals[0];
    EXPECT_TRUE(a.X_LU.isApprox(b.X_LU, 0.0)) << ToString(kind);
    EXPECT_EQ(a.evaluations, b.evaluations) << ToString(kind);
    EXPECT_EQ(a.seat_cost, b.seat_cost) << ToString(kind);
    EXPECT_EQ(a.evaluation.contact_area_mm2, b.evaluation.contact_area_mm2) << ToString(kind);
    EXPECT_EQ(a.status, b.status) << ToString(kind);
    // The helpers' CPU is the plan's too.
    EXPECT_GT(two.cpu_seconds, 0.0);
  }
}

TEST(PlanTest, FarApartAndNestedStartsGiveFinitePoses) {
  const auto& c = Synthetic();
  for (const double offset : {6.0, -1.5}) {
    for (SolverKind kind : {SolverKind::kNloptLocal, SolverKind::kCeres}) {
#ifdef OCCLUDE_SANITIZED
      // The sanitizer lane: each solver from one of the two starts (the release lane: both).
      if ((kind == SolverKind::kCeres) != (offset < 0.0)) continue;
#endif
      PlanRequest req = PerturbedRequest(kind, 0.0, 0.0);
      req.X_LU_start = Eigen::Translation3d(offset * c.pair.occlusal_axis_L) * c.pair.X_LU;
      req.lower_bound.translation_mm = Eigen::Vector3d::Constant(-8.0);
      req.upper_bound.translation_mm = Eigen::Vector3d::Constant(8.0);
      const PlanResult res = Plan(c.schedule.stages, req);
      ASSERT_FALSE(res.proposals.empty());
      const Proposal& p = res.proposals.front();
      EXPECT_TRUE(p.X_LU.matrix().allFinite()) << offset;
      EXPECT_TRUE(p.evaluation.feasible) << offset << " " << ToString(kind) << " " << p.message;
      // Brought back to the bite along the occlusal axis.
      EXPECT_LE(ComparePoses(p.X_LU, c.pair.X_LU, c.points_U).translation_mm, kReturnToleranceMm)
          << offset << " " << ToString(kind);
    }
  }
}

TEST(PlanTest, InfeasibleRequestReturnsBestWithClearStatus) {
  const auto& c = Synthetic();
  // Nested 1.5 mm and the occlusal translation locked: no feasible pose within the bounds.
  PlanRequest req = PerturbedRequest(SolverKind::kNloptLocal, 0.0, 0.0);
  req.X_LU_start = Eigen::Translation3d(-1.5 * c.pair.occlusal_axis_L) * c.pair.X_LU;
  req.locked = {false, true, false, false, false, false};
  req.lower_bound.translation_mm = Eigen::Vector3d::Constant(-0.3);
  req.upper_bound.translation_mm = Eigen::Vector3d::Constant(0.3);
  req.lower_bound.rotation_deg = Eigen::Vector3d::Constant(-1.0);
  req.upper_bound.rotation_deg = Eigen::Vector3d::Constant(1.0);
  req.max_evaluations = 40;
  const PlanResult res = Plan(c.schedule.stages, req);
  ASSERT_FALSE(res.proposals.empty());
  const Proposal& p = res.proposals.front();
  EXPECT_EQ(p.status, SolveStatus::kInfeasible) << p.message;
  EXPECT_FALSE(p.evaluation.feasible);
  EXPECT_FALSE(p.message.empty());
  EXPECT_TRUE(p.X_LU.matrix().allFinite());
}

TEST(PlanTest, RequestErrorsNameTheField) {
  PlanRequest req;
  req.max_penetration_mm = -1.0;
  try {
    ValidateRequest(req);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_penetration_mm"), std::string::npos) << e.what();
  }
  try {
    SolverKindFromName("newton");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("solver"), std::string::npos) << e.what();
  }
  for (SolverKind k : {SolverKind::kNloptLocal, SolverKind::kNloptGlobal, SolverKind::kCeres,
                       SolverKind::kCoarseToFine}) {
    EXPECT_EQ(SolverKindFromName(ToString(k)), k);
  }
  EXPECT_THROW(Plan({}, PlanRequest{}), std::invalid_argument);
}

}  // namespace
}  // namespace occlude::planner

namespace occlude::planner {
namespace {

// The straight path between two poses: its ends are the two poses, each point evaluated as
// EvaluatePose would, the displacement grows linearly along a pure translation; the bite of
// the synthetic pair has contact, the pose opened 0.5 mm none (its jaws are >= 0.38 mm apart).
TEST(EvaluatePathTest, EndsAtBothPosesAndEvaluatesEachPoint) {
  const auto& c = Synthetic();
  const OracleStage& stage = c.schedule.stages.back();
  const PlanRequest request;
  Eigen::Isometry3d X_open = c.pair.X_LU;
  X_open.pretranslate(0.5 * c.pair.occlusal_axis_L);
  const std::vector<PathPoint> path =
      EvaluatePath(stage, c.pair.X_LU, X_open, c.pivot_L, c.points_U, request, 5);
  ASSERT_EQ(path.size(), 6u);
  EXPECT_TRUE(path.front().X_LU.isApprox(c.pair.X_LU, 1e-12));
  EXPECT_TRUE(path.back().X_LU.isApprox(X_open, 1e-12));
  for (const PathPoint& p : path) {
    EXPECT_NEAR(p.from_start.translation_mm, 0.5 * p.s, 1e-9) << p.s;
    EXPECT_NEAR(p.from_start.rotation_deg, 0.0, 1e-6) << p.s;
    const PoseEvaluation direct = EvaluatePose(stage, p.X_LU, request);
    EXPECT_DOUBLE_EQ(p.evaluation.contact_area_mm2, direct.contact_area_mm2) << p.s;
    EXPECT_DOUBLE_EQ(p.evaluation.constrained_penetration_mm, direct.constrained_penetration_mm)
        << p.s;
  }
  EXPECT_GT(path.front().evaluation.contact_area_mm2, 1.0);
  EXPECT_EQ(path.back().evaluation.contact_area_mm2, 0.0);
  EXPECT_THROW(EvaluatePath(stage, c.pair.X_LU, X_open, c.pivot_L, c.points_U, request, 0),
               std::invalid_argument);
}

}  // namespace
}  // namespace occlude::planner
