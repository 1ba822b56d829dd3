// The last stage's polish (PlanRequest::polish): a pattern search (Hooke and
// Jeeves) on the seat cost of the stage's samples at the pose settled on the
// stage's oracle, over the five motions that leave the settle direction free.
// The solve-and-settle rounds do not minimize that cost: their least-squares
// optimum (a soft hinge beyond the allowance) is settled again each round on
// the samples, and the final settle on the oracle lifts it again where the
// oracle sees a point the samples do not; on flat seats the rounds wander
// (c4-ios: 0.05-0.1 mm per round, the settled cost 118.9-120.6 round to round)
// and end anywhere along the seat.
#include <cmath>

#include "search_internal.h"

namespace occlude::planner::detail {
namespace {

// The arch's largest distance from the pivot among the reference points (mm, at least 1): a
// rotation of `step` / lever radians moves the arch's far end by about `step` mm.
double Lever(const Problem& problem) {
  double lever = 1.0;
  for (const Eigen::Vector3d& p_U : problem.ref_points_U)
    lever = std::max(lever, (problem.X_ref * p_U - problem.pivot_L).norm());
  return lever;
}

// x moved by motion `k` (0-4: along anterior, lateral; about occlusal, lateral, anterior
// through the pivot as the upper carries it) of `step` mm (rotations: `step` / lever rad).
Vector6d Moved(const Problem& problem, const Vector6d& x, int k, double step, double lever) {
  const collision::ArchFrame& a = problem.arch;
  const Eigen::Isometry3d X = PoseOf(problem, x);
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  if (k < 2) {
    motion.translation() = step * (k == 0 ? a.anterior_L : a.lateral_L);
  } else {
    const Eigen::Vector3d axis = k == 2 ? a.occlusal_L : (k == 3 ? a.lateral_L : a.anterior_L);
    const Eigen::Vector3d centre = X * (problem.X_ref.inverse() * problem.pivot_L);
    motion = Eigen::Translation3d(centre) * Eigen::AngleAxisd(step / lever, axis) *
             Eigen::Translation3d(-centre);
  }
  return Clamp(problem, ParamsOf(problem, motion * X));
}

// The samples whose distance the stage knows at x, or that lie deep inside the lower: the others
// are beyond the field's band, where the seat cost of a sample is constant, and stay there
// under the polish's small motions.
SampleSet WithinReach(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                      const Vector6d& x) {
  const Eigen::Isometry3d X = PoseOf(problem, x);
  const double reach = std::max(SeatSettings(stage, *problem.request).window_mm, 0.5);
  SampleSet near;
  near.spacing_mm = samples.spacing_mm;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    double d = 0.0;
    bool deep = false;
    if (!StageDistance(stage, X * samples.p_U[i], reach, &d, nullptr, &deep) && !deep) continue;
    near.p_U.push_back(samples.p_U[i]);
    near.area_mm2.push_back(samples.area_mm2[i]);
    near.part.push_back(samples.part[i]);
    near.facing.push_back(samples.facing[i]);
  }
  return near;
}

}  // namespace

Vector6d Polish(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                const Vector6d& x, const PolishSettings& settings, int* evaluations) {
  const SampleSet near = WithinReach(stage, samples, problem, x);
  auto settled_cost = [&](const Vector6d& y, Vector6d* settled) {
    *settled = SettleOnOracle(stage, problem, y, evaluations);
    ++*evaluations;
    return EvaluateSet(stage, near, PoseOf(problem, *settled), problem).seat_cost;
  };
  Vector6d best = x;
  double cost = settled_cost(x, &best);
  const double lever = Lever(problem);
  int costs = 1;
  // Hooke and Jeeves: an exploratory sweep tries each motion both ways at the step, keeping
  // what lowers the cost; after a sweep that moved, pattern moves repeat the sweep's motion
  // while they lower the cost (valleys that no single motion follows, such as a turn about a
  // point off the pivot); after one that did not, the step halves.
  for (double step = settings.step_mm;
       step >= settings.min_step_mm && costs < settings.max_costs;) {
    const Vector6d base = best;
    for (int k = 0; k < 5 && costs < settings.max_costs; ++k) {
      for (const double sign : {1.0, -1.0}) {
        Vector6d trial;
        const double c = settled_cost(Moved(problem, best, k, sign * step, lever), &trial);
        ++costs;
        if (c < cost) {
          best = trial;
          cost = c;
          break;
        }
      }
    }
    if (best == base) {
      step *= 0.5;
      continue;
    }
    for (Vector6d from = base; costs < settings.max_costs;) {
      Vector6d trial;
      const double c = settled_cost(Clamp(problem, best + (best - from)), &trial);
      ++costs;
      if (!(c < cost)) break;
      from = best;
      best = trial;
      cost = c;
    }
  }
  return best;
}

}  // namespace occlude::planner::detail
