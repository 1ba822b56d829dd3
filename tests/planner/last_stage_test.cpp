// The last stage's refinement on the synthetic pair: the Ceres rounds never
// raise the seat cost of the settled pose (a round that would is halved, else
// the rounds stop).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace occlude::planner
