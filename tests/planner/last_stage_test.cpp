// The last stage's refinement on the synthetic pair: the Ceres rounds never
// raise the seat cost of the settled pose (a round that would is halved, else
// the rounds stop), and the polish lowers that cost from a pose turned and
// shifted off the designed bite, stays feasible and comes back towards it.
#include <gtest/gtest.h>

#include "occlude/planner/evaluation.h"
#include "planner_fixture.h"
#include "search_internal.h"

namespace occlude::planner {
namespace {

using detail::Vector6d;

// The seat cost of the last stage's samples at a settled pose.
double SettledCost(const detail::SearchContext& c, const Vector6d& x) {
  return detail::EvaluateSet(c.schedule->back(), c.sets.back(), detail::PoseOf(*c.problem, x),
                             *c.problem)
      .seat_cost;
}

TEST(CeresLocalTest, RoundsNeverRaiseTheSettledSeatCost) {
  const test::SyntheticCase& s = test::Synthetic();
  for (int variant = 0; variant < 3; ++variant) {
    const PlanRequest req = test::PerturbedRequest(SolverKind::kCeres, 0.6, 1.5, variant);
    const detail::Problem problem = detail::MakeProblem(s.schedule.stages, req);
    const detail::SearchContext c = detail::MakeSearchContext(s.schedule.stages, problem);
    const OracleStage& stage = s.schedule.stages.back();
    int evals = 0;
    const Vector6d x0 =
        detail::SettleOnSet(stage, c.sets.back(), problem, Vector6d::Zero(), &evals);
    double previous = 0.0;
    for (int rounds = 1; rounds <= 6; ++rounds) {
      const detail::LocalResult r =
          detail::CeresLocal(stage, c.sets.back(), problem, x0, rounds, 100000);
      ASSERT_NE(r.status, SolveStatus::kFailed) << r.message;
      const double cost = SettledCost(c, r.x);
      // Each run repeats the shorter one's rounds (deterministic) and keeps a round only when
      // it lowers the cost.
      if (rounds > 1) {
        EXPECT_LE(cost, previous) << "variant " << variant << ", " << rounds;
      }
      previous = cost;
    }
  }
}

TEST(PolishTest, LowersTheSeatCostAndComesBackTowardsTheBite) {
  const test::SyntheticCase& s = test::Synthetic();
  PlanRequest req;
  req.X_LU_start = s.pair.X_LU;
  const detail::Problem problem = detail::MakeProblem(s.schedule.stages, req);
  const detail::SearchContext c = detail::MakeSearchContext(s.schedule.stages, problem);
  const OracleStage& stage = s.schedule.stages.back();
  // Off the designed bite (the seat of the synthetic pair) by a turn about the occlusal axis
  // and a shift along the arch: the kind of point the rounds stop at on a flat seat.
  const collision::ArchFrame& a = problem.arch;
  for (const double sign : {1.0, -1.0}) {
    Vector6d off = Vector6d::Zero();
    off.head<3>() = sign * 0.25 * a.anterior_L;
    off.tail<3>() = sign * 0.6 * a.occlusal_L;
    int evals = 0;
    const Vector6d start = detail::SettleOnOracle(stage, problem, off, &evals);
    const Vector6d x =
        detail::Polish(stage, c.sets.back(), problem, start, detail::PolishSettings{}, &evals);
    EXPECT_LT(SettledCost(c, x), SettledCost(c, start));
    EXPECT_TRUE(EvaluatePose(stage, detail::PoseOf(problem, x), req).feasible);
    const double before =
        ComparePoses(detail::PoseOf(problem, start), s.pair.X_LU, s.points_U).translation_mm;
    const double after =
        ComparePoses(detail::PoseOf(problem, x), s.pair.X_LU, s.points_U).translation_mm;
    EXPECT_LT(after, before) << "sign " << sign;
    EXPECT_GT(evals, 0);
  }
}

TEST(PolishTest, PlanWithPolishIsNoWorseAndDeterministic) {
  for (int variant = 0; variant < 3; ++variant) {
    PlanRequest req = test::PerturbedRequest(SolverKind::kCeres, 0.8, 2.0, variant);
    const Proposal plain = Plan(test::Synthetic().schedule.stages, req).proposals.front();
    req.polish = true;
    const Proposal polished = Plan(test::Synthetic().schedule.stages, req).proposals.front();
    const Proposal again = Plan(test::Synthetic().schedule.stages, req).proposals.front();
    EXPECT_TRUE(polished.evaluation.feasible);
    // The polish starts where the plain run's final settle ends and keeps only what lowers
    // the cost (on the samples within reach: those beyond are constant).
    EXPECT_LE(polished.seat_cost, plain.seat_cost + 1e-9) << "variant " << variant;
    EXPECT_TRUE(polished.X_LU.isApprox(again.X_LU, 0.0));
  }
}

}  // namespace
}  // namespace occlude::planner
