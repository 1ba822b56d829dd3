// Global stage: poses sampled uniformly in the bounds from a seeded generator,
// each settled along the occlusal axis and ranked by the seat cost on the
// sample set; the best seed the local solvers.
#include <algorithm>
#include <numeric>

#include "search_internal.h"

namespace occlude::planner::detail {

std::vector<Vector6d> GlobalSeeds(const OracleStage& stage, const SampleSet& samples,
                                  const Problem& problem, int count, std::uint32_t seed,
                                  int* evaluations) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vector6d> poses;
  std::vector<double> scores;
  for (int k = 0; k < count; ++k) {
    Vector6d x;
    for (int i = 0; i < kNumDof; ++i)
      x[i] = problem.lower[i] + unit(rng) * (problem.upper[i] - problem.lower[i]);
    // The settle sets the occlusal height; start each sample from the reference height.
    const Eigen::Vector3d t = x.head<3>();
    x.head<3>() = t - problem.settle_dir * problem.settle_dir.dot(t);
    x = Clamp(problem, x);
    x = SettleOnSet(stage, samples, problem, x, evaluations);
    const SetEvaluation e = EvaluateSet(stage, samples, PoseOf(problem, x), problem);
    ++*evaluations;
    poses.push_back(x);
    scores.push_back(-e.seat_cost);
  }
  std::vector<std::size_t> order(poses.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return scores[a] > scores[b]; });
  std::vector<Vector6d> sorted;
  sorted.reserve(order.size());
  for (const std::size_t i : order) sorted.push_back(poses[i]);
  return sorted;
}

}  // namespace occlude::planner::detail
