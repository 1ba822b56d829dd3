// Internals shared by the planner's solvers: the occlusal sample set each stage
// evaluates, the problem (pivot, bounds, locks) as a 6-vector of parameters
// (translation mm, rotation deg), the fast set evaluation, the settle along
// the occlusal axis, the local and global solvers, and the solver chain per
// start that Plan and the global search share.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "inner_threads.h"
#include "occlude/planner/least_squares.h"
#include "occlude/planner/plan.h"

namespace occlude::planner::detail {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Upper samples in U: area-weighted centroids of the occlusal surface clustered on a grid.
struct SampleSet {
  std::vector<Eigen::Vector3d> p_U;
  std::vector<double> area_mm2;
  std::vector<std::int32_t> part;
  /// Cosine between the cluster's mean normal and the direction towards the lower (at the
  /// pose the set was built at): the seat attraction acts on occlusal-facing samples only.
  std::vector<double> facing;
  double spacing_mm = 0.0;
  std::size_t size() const { return p_U.size(); }
};
/// Samples of the upper triangles (at X_LU) facing the lower (normal . -occlusal > -0.3)
/// within the lowest `crown_depth_mm` along the occlusal axis, clustered on a `spacing_mm` grid.
SampleSet OcclusalSamples(const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU,
                          const Eigen::Vector3d& occlusal_L, double spacing_mm,
                          double crown_depth_mm = 8.0);
/// Sample spacing used with a stage: about 0.6 voxel, within [0.25, 0.6] mm.
double StageSpacing(const OracleStage& stage);

/// Signed distance of p_L to the lower surface at the stage's level (kVoxel is answered
/// like kSubVoxel). False when unknown; then *deep says whether p_L is in the lower's interior.
bool StageDistance(const OracleStage& stage, const Eigen::Vector3d& p_L, double reach_mm, double* d,
                   Eigen::Vector3d* gradient, bool* deep);
/// Samples per block when a loop over samples runs on a job's threads (ForBlocks).
constexpr std::size_t kSamplesPerBlock = 512;

/// Everything a solve needs besides the stage.
struct Problem {
  const PlanRequest* request = nullptr;
  Eigen::Isometry3d X_ref = Eigen::Isometry3d::Identity();  ///< the start pose
  Eigen::Vector3d pivot_L = Eigen::Vector3d::Zero();
  collision::ArchFrame arch;
  Eigen::Vector3d settle_dir =
      Eigen::Vector3d::Zero();  ///< occlusal axis without locked components
  Vector6d lower = Vector6d::Zero(), upper = Vector6d::Zero();  ///< bounds (locked: 0, 0)
  std::vector<Eigen::Vector3d> ref_points_U;
};
/// The problem of `request` on `schedule`; its arch frame is the finest oracle's, or `arch`.
Problem MakeProblem(const OracleSchedule& schedule, const PlanRequest& request,
                    const collision::ArchFrame* arch = nullptr);

Eigen::Isometry3d PoseOf(const Problem& problem, const Vector6d& x);
Vector6d ParamsOf(const Problem& problem, const Eigen::Isometry3d& X_LU);
Vector6d Clamp(const Problem& problem, const Vector6d& x);
PoseParameters ToParameters(const Vector6d& x);
Vector6d FromParameters(const PoseParameters& p);
bool Finite(const Vector6d& x);

/// The seat objective's settings for a stage: the request's window (within the field's band),
/// scale and allowance.
ResidualSettings SeatSettings(const OracleStage& stage, const PlanRequest& request);

/// Evaluation of a sample set at a pose (fast, approximate: the solvers' objective).
struct SetEvaluation {
  double seat_cost = 0.0;     ///< the seat objective (SeatSampleCost summed; lower is better)
  double smooth_score = 0.0;  ///< attraction-weighted area minus the bilateral penalty
  double contact_area_mm2 = 0.0;
  double robust_penetration_mm = 0.0;
  /// Smooth penetration excess: sqrt(sum a (depth - limit)+^2 / near-contact area), mm, over the
  /// non-spike samples (zero when no sample is deeper than the limit; C1 in the pose).
  double excess_rms_mm = 0.0;
  double max_penetration_mm = 0.0;
  double min_distance_mm = 0.0;  ///< smallest known distance (+inf if none)
  std::size_t deep = 0;
  bool feasible = false;
};
SetEvaluation EvaluateSet(const OracleStage& stage, const SampleSet& samples,
                          const Eigen::Isometry3d& X_LU, const Problem& problem);
/// Per sample of the set: in a spike patch at X_LU (see PenetrationPatch), so left out of the
/// penetration penalty and measure.
std::vector<bool> SpikeSamples(const OracleStage& stage, const SampleSet& samples,
                               const Eigen::Isometry3d& X_LU, const Problem& problem);

/// Moves x along the settle direction (within bounds) to where the penetration measure of
/// the set just meets the limit: closes open jaws, opens nested ones.
Vector6d SettleOnSet(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                     const Vector6d& x, int* evaluations);
/// The same with the oracle's own measure (EvaluatePose), starting from a nearly settled x.
Vector6d SettleOnOracle(const OracleStage& stage, const Problem& problem, const Vector6d& x,
                        int* evaluations);

/// The polish of a pose on the last stage (polish.cpp): a pattern search on the seat cost of
/// the stage's samples at the pose settled on the stage's oracle, over the five motions that
/// leave the settle direction free (along the arch's anterior and lateral axes; about its
/// occlusal, lateral and anterior axes through the pivot, turning by step / lever where the
/// lever is the arch's reach from the pivot).
struct PolishSettings {
  double step_mm = 0.1;        ///< first step (mm at the arch's far end)
  double min_step_mm = 0.025;  ///< stops below this step
  int max_costs = 40;          ///< settled costs at most
};

struct LocalResult {
  Vector6d x = Vector6d::Zero();
  SolveStatus status = SolveStatus::kFailed;
  std::string message;
  int evaluations = 0;
};
/// NLopt: minimize the seat cost of the set (COBYLA, BOBYQA or Sbplx), then settle.
LocalResult NloptLocal(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                       const Vector6d& x0, int max_evaluations);
/// Ceres: least squares on the samples' signed distances (outer loop re-collects samples and
/// settles; a round that does not lower the settled seat cost is halved, then ends the loop
/// with status kConverged).
LocalResult CeresLocal(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                       const Vector6d& x0, int max_outer, int max_evaluations);
/// The best pose the pattern search finds from x, settled on the stage's oracle (x itself,
/// settled, when no motion lowers its cost). Adds its oracle queries to *evaluations.
Vector6d Polish(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                const Vector6d& x, const PolishSettings& settings, int* evaluations);
/// Global stage: `count` poses sampled uniformly in the bounds (seeded), each settled and
/// ranked by the seat cost on the set; returns them best first.
std::vector<Vector6d> GlobalSeeds(const OracleStage& stage, const SampleSet& samples,
                                  const Problem& problem, int count, std::uint32_t seed,
                                  int* evaluations);

/// A search on a schedule: the problem and the occlusal sample set of each stage.
struct SearchContext {
  const OracleSchedule* schedule = nullptr;
  const Problem* problem = nullptr;
  std::vector<SampleSet> sets;  ///< per stage (stages of equal spacing share equal sets)
};
/// The sample sets of every stage of `schedule`, taken at the problem's reference pose.
SearchContext MakeSearchContext(const OracleSchedule& schedule, const Problem& problem);

/// The request's solver from `start` on stages [first, stop] (coarse-to-fine and nlopt-global
/// walk them; the single-stage solvers run on the last stage only). Never throws; a failure or
/// a non-finite pose gives status kFailed at the start pose.
LocalResult SafeChain(const SearchContext& c, const Vector6d& start, std::size_t first,
                      std::size_t stop);
/// The final settle of a chain's result on the last stage's oracle and its evaluation.
Proposal Finish(const SearchContext& c, int index, const LocalResult& r);
/// The candidates best first (feasible before infeasible, then the lowest seat cost, then the
/// least penetration; ties by position), keeping at most `max_count` distinct poses.
std::vector<Proposal> BestDistinct(const std::vector<Proposal>& candidates, const Problem& problem,
                                   int max_count);

/// Progress and the wall-clock budget of the local solves (PlanRequest::max_seconds).
struct Tracker {
  const PlanRequest* request = nullptr;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  int total = 0;
  std::atomic<int> done{0}, skipped{0};
  std::mutex mutex;
  std::function<void(int done, int total)> report;  ///< called serialized; may be empty
  bool OutOfTime() const;
  void Done();
};

/// Chains run from a list of starts: their finished proposals (in start order), the oracle
/// queries of all the runs (each counted once; a proposal's own count includes its coarse
/// run's), and the CPU seconds of the helper threads.
struct Candidates {
  std::vector<Proposal> proposals;
  int evaluations = 0;
  double worker_cpu = 0.0;
  /// CoarseThenFine: thread CPU seconds of the coarse runs and of the refinements (summed
  /// over the jobs).
  double coarse_cpu = 0.0, fine_cpu = 0.0;
};
/// Every start through the whole chain (stages 0..last) and Finish; starts after the first
/// are skipped when the tracker is out of time.
Candidates EachStart(const SearchContext& c, const std::vector<Vector6d>& starts, Tracker* tracker);
/// Every start on stage 0 only; the `refine_count` best distinct coarse seats (by the coarse
/// seat cost) go on through stages 1..last and Finish: the fine models see only seats that
/// can win. Starts after the first are skipped when the tracker is out of time.
Candidates CoarseThenFine(const SearchContext& c, const std::vector<Vector6d>& starts,
                          std::size_t refine_count, Tracker* tracker);

/// Runs job(i) for i in [0, n) on up to `threads` std::threads; the results land in slots
/// indexed by i, so they do not depend on the thread count. Each worker's jobs may use the
/// threads the workers leave idle (InnerBudget: threads / workers each). Returns the CPU seconds
/// of the threads other than the caller (the caller's own are on its clock), its jobs' helpers
/// included. A job's exception stops the jobs not yet started and is rethrown on the caller
/// once every worker has stopped (the lowest-numbered failed job's).
template <typename Job>
double ParallelFor(std::size_t n, int threads, Job job) {
  std::atomic<std::size_t> next{0};
  const int count = std::max(1, std::min<int>(threads, static_cast<int>(n)));
  const int inner = std::max(1, threads / count);
  std::vector<double> cpu(static_cast<std::size_t>(count), 0.0);
  std::vector<std::exception_ptr> failed(n);
  auto worker = [&](int slot) {
    const InnerBudgetScope scope(inner);  // the worker's budget, the thread's own again after
    const double t0 = CpuSeconds();
    for (std::size_t i = next++; i < n; i = next++) {
      try {
        job(i);
      } catch (...) {
        failed[i] = std::current_exception();
        next = n;  // no new job starts
      }
    }
    cpu[static_cast<std::size_t>(slot)] =
        (slot == 0 ? 0.0 : CpuSeconds() - t0) + CurrentInnerBudget().helper_cpu;
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < count; ++t) pool.emplace_back(worker, t);
  worker(0);
  for (auto& t : pool) t.join();
  for (const std::exception_ptr& e : failed) {
    if (e) std::rethrow_exception(e);  // the lowest-numbered job's that failed
  }
  double others = 0.0;
  for (const double c : cpu) others += c;
  return others;
}

}  // namespace occlude::planner::detail
