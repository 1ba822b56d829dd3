// The settings of an occlusion search (PlanRequest) and the schedule of
// oracles it runs on (OracleStage). Units: mm, mm^2 and degrees; frames as in
// pose.h (parameters are relative to the start pose X_LU_start, about the pivot).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "occlude/collision/oracle.h"
#include "occlude/planner/pose.h"

namespace occlude::planner {

/// The search methods; every one is a complete solver (see plan.h).
enum class SolverKind {
  kNloptLocal,   ///< "nlopt-local": constrained local search from each start (NlopLocalMethod)
  kNloptGlobal,  ///< "nlopt-global": seeded sampling of the bounds; the best seeds through NLopt on
                 ///< each stage (coarse: all, finer: the best)
  kCeres,        ///< "ceres": least squares on signed-distance residuals from each start
  kCoarseToFine,  ///< "coarse-to-fine": sampling + Ceres on each stage (coarse: all seeds, finer:
                  ///< the best)
};
const char* ToString(SolverKind kind);
/// Parses a solver name as printed by ToString; throws std::invalid_argument naming "solver"
/// and listing the valid names.
SolverKind SolverKindFromName(const std::string& name);

/// The local NLopt method: COBYLA, or the augmented Lagrangian around BOBYQA / Sbplx.
enum class NloptLocalMethod { kCobyla, kAuglagBobyqa, kAuglagSbplx };
const char* ToString(NloptLocalMethod method);
/// Parses "cobyla", "auglag-bobyqa" or "auglag-sbplx"; throws std::invalid_argument naming
/// "nlopt_local".
NloptLocalMethod NloptLocalMethodFromName(const std::string& name);

/// How the penetration constraint treats the deepest samples (scanner spikes).
enum class PenetrationMeasure {
  kMax,          ///< the deepest sample: no outliers
  kOutlierArea,  ///< the depth left after discarding the deepest samples up to outlier_area_mm2
  kPercentile,   ///< the same with a budget of (100 - percentile) % of the near-contact area
};
const char* ToString(PenetrationMeasure measure);

/// DOF order everywhere: 0-2 translation x, y, z (mm, in L), 3-5 rotation vector x, y, z (deg).
inline constexpr int kNumDof = 6;

struct PlanRequest {
  /// Start (and reference) pose of U in L; parameters and bounds are relative to it.
  Eigen::Isometry3d X_LU_start = Eigen::Isometry3d::Identity();
  SolverKind solver = SolverKind::kCoarseToFine;
  /// Measured on the synthetic pair (1 mm / 2 deg starts, 0.8/0.4 mm): AUGLAG-BOBYQA 4 of 6
  /// runs within 0.3 mm, COBYLA 0 of 6, AUGLAG-Sbplx 1 of 6.
  NloptLocalMethod nlopt_local = NloptLocalMethod::kAuglagBobyqa;

  double contact_band_mm = 0.1;      ///< contact: 0 <= d <= band
  double max_penetration_mm = 0.05;  ///< constraint on the penetration measure
  PenetrationMeasure penetration_measure = PenetrationMeasure::kOutlierArea;
  double outlier_area_mm2 = 0.05;        ///< kOutlierArea: deepest area that may exceed the limit
  double penetration_percentile = 99.0;  ///< kPercentile, in (0, 100]
  /// kOutlierArea / kPercentile: penetration patches steeper than a hemisphere (deeper than the
  /// radius of a disc of their area: scan spikes, folds, flaps) up to this area are outliers
  /// too (see PenetrationPatch); 0 turns spike patches off.
  double spike_patch_max_mm2 = 5.0;
  /// Samples up to this distance above the lower surface count in the smooth contact score
  /// (reported/diagnostic; the solvers' driver is the seat objective below).
  double attraction_range_mm = 0.6;
  /// Seat objective (Chang et al. 2010: minimize the distance between the occlusal surfaces
  /// without collision): every occlusal upper sample with gap d in (0, seat_window_mm] is
  /// pulled towards the lower (robust, Cauchy of scale seat_scale_mm); penetration beyond
  /// seat_penetration_allowance_mm is pushed out by a strong Huber hinge. Contact area stays
  /// the ranking quality of the proposals.
  double seat_window_mm = 1.0;
  double seat_scale_mm = 0.3;
  double seat_penetration_allowance_mm = 0.02;
  /// Only occlusal-facing upper samples attract: normal within acos(seat_min_facing) of the
  /// direction towards the lower (the steep incisor sides keep their designed overjet gap).
  double seat_min_facing = 0.6;
  /// 0..1: subtracts this share of the left/right imbalance of posterior contact from the
  /// score (0 = plain contact area).
  double bilateral_posterior_weight = 0.0;

  /// Bounds of the parameters relative to the start pose (lower <= 0 <= upper per DOF).
  PoseParameters lower_bound{Eigen::Vector3d::Constant(-3.0), Eigen::Vector3d::Constant(-6.0)};
  PoseParameters upper_bound{Eigen::Vector3d::Constant(3.0), Eigen::Vector3d::Constant(6.0)};
  /// Locked DOFs keep their start value (order as kNumDof).
  std::array<bool, kNumDof> locked{};
  /// Rotation pivot in L at the start pose; default the centre of the upper occlusal surface
  /// (collision::UpperOcclusalCentre, the upper at X_LU_start).
  std::optional<Eigen::Vector3d> pivot_L;

  /// Polish each result on the last stage: a pattern search on the seat cost of the last
  /// stage's samples at the pose settled on its oracle, over the motions that leave the
  /// occlusal axis free (along the arch, across it, its three rotations), at most 40 settled
  /// costs. The solve-and-settle rounds stop anywhere along a flat seat (c4-ios: results 0.3-0.5
  /// mm and 0.3-0.9 deg of yaw apart in one seat); the polish takes each to the bottom of its
  /// seat, at about 0.1 s per result on a 10k-triangle jaw (0.4 mm stage). The global search
  /// always polishes; off by default for the local search (its speed).
  bool polish = false;

  std::uint32_t seed = 1;
  int num_starts = 4;  ///< local solves (the start pose and sampled starts)
  int num_global_samples =
      48;  ///< global stage: poses sampled in the bounds (nlopt-global, coarse-to-fine)
  int num_threads = 2;                   ///< threads for the starts (std::thread); 1 = serial
  int max_proposals = 3;                 ///< K distinct occlusions returned (best first)
  double distinct_translation_mm = 0.5;  ///< proposals differ by more than this at a reference
  double distinct_rotation_deg = 2.0;    ///< point, or by more than this rotation
  int max_evaluations = 600;             ///< oracle queries per local solve (per stage)
  /// Wall-clock budget (s) of the local solves: starts not begun by then are skipped (the
  /// result says how many ran); 0 = no budget.
  double max_seconds = 0.0;
  /// Called (from the solver threads, serialized) after each local solve: solves done, total.
  std::function<void(int done, int total)> on_progress;
};

/// Throws std::invalid_argument naming the first invalid field of `request` and how to fix it.
void ValidateRequest(const PlanRequest& request);

/// One oracle of the schedule and the accuracy it is queried at.
struct OracleStage {
  const collision::JawOracle* oracle = nullptr;
  collision::AccuracyLevel level = collision::AccuracyLevel::kSubVoxel;
};
/// Coarse to fine: the global stage uses the first entry, the local solvers the last;
/// coarse-to-fine walks all of them in order.
using OracleSchedule = std::vector<OracleStage>;

/// Oracles built by the planner for a schedule (owns them; `stages` points into them).
struct OwnedSchedule {
  std::vector<std::unique_ptr<collision::JawOracle>> oracles;
  OracleSchedule stages;
};
/// Band of the first stage's distance field when the schedule has several stages (mm): wide,
/// so that starts a few millimetres off still feel the other jaw.
inline constexpr double kCoarseBandMm = 3.0;
/// Builds one oracle per voxel size (coarse first, e.g. {0.8, 0.4}) and a schedule querying
/// each at kSubVoxel, plus a last stage querying the finest at kExact when `exact_last`. With
/// several voxel sizes the first oracle's field reaches kCoarseBandMm.
/// Throws std::invalid_argument for an empty or non-positive voxel list.
/// The oracle options of stage `index` of a schedule with these voxel sizes (what
/// BuildSchedule uses; for callers that build the oracles themselves).
collision::OracleOptions StageOracleOptions(const collision::OracleOptions& base,
                                            const std::vector<double>& voxel_sizes_mm,
                                            std::size_t index);
OwnedSchedule BuildSchedule(const std::shared_ptr<const io::TriangleMesh>& lower_L,
                            const std::shared_ptr<const io::TriangleMesh>& upper_U,
                            const std::vector<double>& voxel_sizes_mm, bool exact_last,
                            const collision::OracleOptions& base_options = {});

}  // namespace occlude::planner
