// What a pose is worth: contact, penetration (true maximum and the
// outlier-robust measure the constraint uses, with the outliers listed),
// per-tooth totals and the score, from one oracle query; plus the geometric
// helpers of the planner (occlusal pivot, reference points for errors).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "occlude/collision/oracle.h"
#include "occlude/io/triangle_mesh.h"
#include "occlude/planner/request.h"

namespace occlude::planner {

/// A penetrating upper sample the constraint ignored (a scanner spike, presumably).
struct OutlierPoint {
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();  ///< position in L at the evaluated pose
  double depth_mm = 0.0;                          ///< > 0
  double area_mm2 = 0.0;
  std::int32_t part = 0;  ///< upper part (tooth) index
  bool spike = false;     ///< in a spike patch (else: within the deepest-area budget)
};

struct PoseEvaluation {
  double contact_area_mm2 = 0.0;  ///< 0 <= d <= contact band
  std::size_t contact_samples = 0;
  double max_penetration_mm = 0.0;  ///< true deepest measured depth (>= 0)
  double constrained_penetration_mm =
      0.0;  ///< the measure the constraint compares (see PenetrationMeasure)
  double penetration_area_mm2 = 0.0;
  std::size_t deep_samples = 0;        ///< inside the lower beyond the measured range
  std::vector<OutlierPoint> outliers;  ///< penetrating samples left out of the measure
  double left_share = 0.0, right_share = 0.0, anterior_share = 0.0, posterior_share = 0.0;
  double posterior_left_mm2 = 0.0, posterior_right_mm2 = 0.0;
  std::vector<collision::PartTotals> parts;  ///< per upper part (tooth)
  double score = 0.0;     ///< contact area minus the bilateral penalty (mm^2); higher is better
  bool feasible = false;  ///< constrained_penetration_mm <= max_penetration_mm and no deep samples
};

/// One oracle query at X_LU (level of `stage`) turned into a PoseEvaluation under the
/// request's band, penetration measure and score weights.
PoseEvaluation EvaluatePose(const OracleStage& stage, const Eigen::Isometry3d& X_LU,
                            const PlanRequest& request);

/// A penetrating sample (depth > 0) at its position in L.
struct PenetratingSample {
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();
  double depth_mm = 0.0;
  double area_mm2 = 0.0;
};
/// Penetrating samples linked by proximity (a chain of samples within link_mm).
struct PenetrationPatch {
  std::vector<std::size_t> members;  ///< indices into the samples
  double depth_mm = 0.0;             ///< deepest member
  double area_mm2 = 0.0;
  Eigen::Vector3d centre_L = Eigen::Vector3d::Zero();  ///< area-weighted
  Eigen::Vector3d deepest_L = Eigen::Vector3d::Zero();
  /// A scanner spike: deeper than the radius of a disc of its area (steeper than a hemisphere
  /// pressed in: a crown would have to sink deeper than its own radius of curvature) and at most
  /// the size cap in area.
  bool spike = false;
};
/// Groups penetrating samples into patches (grid hash, O(n)); patches in the order of their
/// first member. `max_spike_area_mm2` caps the area of a patch that may be a spike (0: none).
std::vector<PenetrationPatch> PenetrationPatches(const std::vector<PenetratingSample>& samples,
                                                 double link_mm, double max_spike_area_mm2);
/// Per sample: member of a spike patch.
std::vector<bool> SpikeMembers(const std::vector<PenetratingSample>& samples, double link_mm,
                               double max_spike_area_mm2);
/// SpikeMembers as the penetration measure uses it, cheaply: only samples deeper than
/// `shallow_mm` are linked (a patch misjudged for its missing shallow rim is at most
/// 2 shallow_mm deep: harmless when that is below the limit), and none is a spike when the
/// samples deeper than `limit_mm` cover more than kNestedCaps size caps (deeply nested jaws:
/// infeasible whatever the spikes, and thousands of samples to link).
inline constexpr double kNestedCaps = 4.0;
std::vector<bool> SpikeMembersForMeasure(const std::vector<PenetratingSample>& samples,
                                         double link_mm, double max_spike_area_mm2, double limit_mm,
                                         double shallow_mm);
/// The spike-patch size cap the request asks for (0 when outliers are off: kMax).
double SpikePatchCap(const PlanRequest& request);
/// The `shallow_mm` the planner links above: half the smaller of the limit and the seat
/// objective's penetration allowance (at least 0.002 mm).
double SpikeShallowMm(const PlanRequest& request);

/// The robust penetration measure of a list of (depth > 0, area) samples with `deep` samples
/// beyond the measured range (counted at `deep_depth_mm`, `deep_area_mm2` each): the deepest
/// depth left after discarding the deepest samples whose total area fits the outlier budget.
/// `outlier_index` (optional) receives the indices of the discarded samples.
double RobustPenetration(const std::vector<std::pair<double, double>>& depth_area, std::size_t deep,
                         double deep_depth_mm, double deep_area_mm2, double outlier_budget_mm2,
                         std::vector<std::size_t>* outlier_index = nullptr);
/// Outlier area budget of the request given the near-contact (contact + penetration) area.
double OutlierBudget(const PlanRequest& request, double near_contact_area_mm2);

/// Reference points of the upper arch in U for pose errors: the default pivot (the centre of the
/// upper occlusal surface, collision::UpperOcclusalCentre, at X_LU), the most
/// anterior occlusal point (incisors) and the most posterior occlusal points left and right
/// (molars), taken on the occlusal-facing triangles at X_LU.
std::vector<Eigen::Vector3d> ArchReferencePoints_U(const io::TriangleMesh& upper_U,
                                                   const Eigen::Isometry3d& X_LU,
                                                   const collision::ArchFrame& arch);

/// Largest displacement (mm) of `points_U` between two poses, and their relative rotation (deg).
struct PoseError {
  double translation_mm = 0.0;
  double rotation_deg = 0.0;
};
PoseError ComparePoses(const Eigen::Isometry3d& X_LU_a, const Eigen::Isometry3d& X_LU_b,
                       const std::vector<Eigen::Vector3d>& points_U);

/// A pose on the straight path between two poses, evaluated.
struct PathPoint {
  double s = 0.0;  ///< 0 at the path's start, 1 at its end
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();
  PoseError from_start;  ///< displacement from the start pose (ComparePoses' points)
  PoseEvaluation evaluation;
};
/// `steps + 1` poses at s = k / steps between X_LU_from (s = 0) and X_LU_to (s = 1): the pivot
/// parameters of X_LU_to relative to X_LU_from (about p_LPivot) scaled by s, each evaluated
/// on `stage` under the request. Throws std::invalid_argument when steps < 1.
std::vector<PathPoint> EvaluatePath(const OracleStage& stage, const Eigen::Isometry3d& X_LU_from,
                                    const Eigen::Isometry3d& X_LU_to,
                                    const Eigen::Vector3d& p_LPivot,
                                    const std::vector<Eigen::Vector3d>& points_U,
                                    const PlanRequest& request, int steps);
/// Does `a` Pareto-dominate `b` for "maximal contact, no interpenetration": strictly more
/// contact area, no deeper outlier-robust penetration and no more deep samples. A pose that
/// another dominates is the optimum of no objective that rewards contact and penalizes
/// penetration.
bool Dominates(const PoseEvaluation& a, const PoseEvaluation& b);

}  // namespace occlude::planner
