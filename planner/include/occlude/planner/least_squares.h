// The least-squares model of the Ceres solver, exposed for checking: residuals
// of a fixed set of upper samples against the lower jaw's signed distance
// (a penetration hinge and an attraction into the contact band) and their
// analytic Jacobian with respect to the pose parameters.
//
// Per sample i (area a_i, signed distance d_i at the pose):
//   hinge      r = w_pen * sqrt(a_i) * min(0, d_i)
//   attraction r = sqrt(a_i) * max(0, d_i - band)   (a Cauchy loss of scale `attraction_scale_mm`
//                                                    is applied by the solver, not here)
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
  double contact_band_mm = 0.1;
  double penetration_weight = 20.0;  ///< w_pen
  double attraction_scale_mm = 0.15; ///< Cauchy scale of the attraction (solver side)
  double range_mm = 0.6;             ///< samples with d <= range at the base pose take part
  /// Solver side: a near-constant force closing the jaws along the occlusal axis, as a share
  /// of the residual samples' total area (0 = off; 0.1-0.5 made results worse, see report).
  double closure_weight = 0.0;
};

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
