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
  // The samples are drawn in order, then settled and scored in parallel (each on its own).
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vector6d> poses(static_cast<std::size_t>(std::max(0, count)));
  for (Vector6d& x : poses) {
    for (int i = 0; i < kNumDof; ++i)
      x[i] = problem.lower[i] + unit(rng) * (problem.upper[i] - problem.lower[i]);
    // The settle sets the occlusal height; start each sample from the reference height.
    const Eigen::Vector3d t = x.head<3>();
    x.head<3>() = t - problem.settle_dir * problem.settle_dir.dot(t);
    x = Clamp(problem, x);
  }
  std::vector<double> scores(poses.size());
  std::vector<int> evals(poses.size(), 0);
  ParallelFor(poses.size(), problem.request->num_threads, [&](std::size_t k) {
    poses[k] = SettleOnSet(stage, samples, problem, poses[k], &evals[k]);
    const SetEvaluation e = EvaluateSet(stage, samples, PoseOf(problem, poses[k]), problem);
    ++evals[k];
    scores[k] = -e.seat_cost;
  });
  for (const int e : evals) *evaluations += e;
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
