// The least-squares model of the Ceres solver, exposed for checking: residuals
// of a fixed set of upper samples against the lower jaw's signed distance
// (a penetration hinge and an attraction into the contact band) and their
// analytic Jacobian with respect to the pose parameters.
//
// The seat objective (Chang, Xia, Gateno et al., IEEE TMI 2010: minimize the distance between
// the opposing occlusal surfaces under the no-collision constraint). Per sample i (area a_i,
// signed distance d_i at the pose):
//   hinge      r = w_pen * sqrt(a_i) * min(0, d_i + allowance)   (Huber loss of scale
//                                                    w_pen sqrt(a_i) huber_mm: spikes push
//                                                    linearly)
//   attraction r = sqrt(a_i) * clamp(d_i, 0, window)  (Cauchy loss of scale
//                                                    attraction_scale_mm sqrt(a_i))
// Losses are applied by the solver, not here; SeatCost() gives the same total cost.
// Jacobians come from the oracle's distance gradients (d d / d pose is n^T [I, -(p - pivot)x]
// for the update about the pivot) chained through the parameterization of pose.h.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "occlude/planner/pose.h"
#include "occlude/planner/request.h"

namespace occlude::planner {

struct ResidualSettings {
  double contact_band_mm = 0.1;            ///< (reported contact only; not part of the residuals)
  double penetration_weight = 20.0;        ///< w_pen
  double penetration_allowance_mm = 0.02;  ///< hinge starts beyond this depth
  double penetration_huber_mm = 0.1;       ///< Huber scale of the hinge, as a depth (solver side)
  double attraction_scale_mm = 0.3;        ///< Cauchy scale of the attraction (solver side)
  double window_mm = 1.0;  ///< gaps above this no longer attract (constant residual)
  /// Only samples whose normal is within acos(this) of the direction towards the lower attract
  /// (occlusal surfaces; not the steep incisor and crown sides, whose overjet gap is designed).
  double attraction_min_facing = 0.6;
  double range_mm = 1.0;  ///< samples with d <= range at the base pose take part
  /// Solver side: a near-constant force closing the jaws along the occlusal axis, as a share
  /// of the residual samples' total area (0 = off; 0.1-0.5 made results worse, see report).
  double closure_weight = 0.0;
};

/// Robust cost of one sample (the solver's 0.5 * (rho_hinge + rho_attraction)) at signed
/// distance d (mm), area a (mm^2); `attract` false leaves only the hinge.
double SeatSampleCost(double d, double area_mm2, bool attract, const ResidualSettings& settings);

/// Residuals of the samples within `range_mm` of the lower surface at X_LU_base (at most
/// `max_samples`, thinned evenly with their areas scaled up), parameters relative to
/// X_LU_ref about p_LPivot.
class SurfaceResiduals {
 public:
  SurfaceResiduals(const OracleStage& stage, const Eigen::Isometry3d& X_LU_base,
                   const Eigen::Isometry3d& X_LU_ref, const Eigen::Vector3d& p_LPivot,
                   const ResidualSettings& settings, std::size_t max_samples = 20000);
  ~SurfaceResiduals();
  SurfaceResiduals(SurfaceResiduals&&) noexcept;
  SurfaceResiduals& operator=(SurfaceResiduals&&) noexcept;

  /// Number of residuals: 2 per sample (hinge, attraction).
  int size() const;
  /// Residuals at `params` and, when `jacobian` is given, their derivative (size() x 6) with
  /// respect to (translation mm, rotation deg).
  void Evaluate(const PoseParameters& params, Eigen::VectorXd* residuals,
                Eigen::MatrixXd* jacobian = nullptr) const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace occlude::planner
