// Internals shared by the planner's solvers: the occlusal sample set each stage
// evaluates, the problem (pivot, bounds, locks) as a 6-vector of parameters
// (translation mm, rotation deg), the fast set evaluation, the settle along
// the occlusal axis, and the local and global solvers.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "occlude/planner/least_squares.h"
#include "occlude/planner/plan.h"

namespace occlude::planner::detail {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Thread CPU time in seconds.
double CpuSeconds();

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
Problem MakeProblem(const OracleSchedule& schedule, const PlanRequest& request);

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

struct LocalResult {
  Vector6d x = Vector6d::Zero();
  SolveStatus status = SolveStatus::kFailed;
  std::string message;
  int evaluations = 0;
};
/// NLopt: minimize the seat cost of the set (COBYLA, BOBYQA or Sbplx), then settle.
LocalResult NloptLocal(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                       const Vector6d& x0, int max_evaluations);
/// Ceres: least squares on the samples' signed distances (outer loop re-collects samples).
LocalResult CeresLocal(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                       const Vector6d& x0, int max_outer, int max_evaluations);
/// Global stage: `count` poses sampled uniformly in the bounds (seeded), each settled and
/// ranked by the seat cost on the set; returns them best first.
std::vector<Vector6d> GlobalSeeds(const OracleStage& stage, const SampleSet& samples,
                                  const Problem& problem, int count, std::uint32_t seed,
                                  int* evaluations);

}  // namespace occlude::planner::detail
