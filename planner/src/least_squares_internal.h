// Internals of the least-squares model (least_squares.h): the fixed sample
// set, the per-sample residuals with analytic Jacobians in the ambient
// parameters z = (t mm, w rad), and the pose manifold about the pivot.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "occlude/planner/least_squares.h"
#include "search_internal.h"

namespace occlude::planner {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Row6d = Eigen::Matrix<double, 1, 6>;

struct SurfaceResiduals::Impl {
  Impl(const OracleStage& stage, const detail::SampleSet& all, const Eigen::Isometry3d& X_LU_base,
       const Eigen::Isometry3d& X_LU_ref, const Eigen::Vector3d& p_LPivot,
       const ResidualSettings& settings, std::size_t max_samples,
       const std::vector<bool>* excluded = nullptr);

  /// Signed distance of sample i at ambient parameters z and its gradient (1x6) in z.
  double Distance(std::size_t i, const Vector6d& z, Row6d* gradient) const;
  /// Hinge and attraction residuals of sample i (see least_squares.h) with their Jacobians.
  void Residuals(std::size_t i, const Vector6d& z, double* hinge, double* attraction,
                 Row6d* j_hinge, Row6d* j_attraction) const;

  OracleStage stage;
  Eigen::Isometry3d X_ref;
  Eigen::Vector3d pivot;
  ResidualSettings settings;
  std::vector<Eigen::Vector3d> v_L;  ///< X_ref * p_U - pivot, per sample
  std::vector<double> area;
  std::vector<bool> attract;  ///< occlusal-facing: takes part in the attraction
};

namespace detail {
/// The cross-product matrix of w: Hat(w) v = w x v.
Eigen::Matrix3d Hat(const Eigen::Vector3d& w);
/// Left Jacobian of SO(3) and its inverse at rotation vector w (rad).
Eigen::Matrix3d LeftJacobian(const Eigen::Vector3d& w);
Eigen::Matrix3d LeftJacobianInverse(const Eigen::Vector3d& w);
/// Ambient z (t mm, w rad) <-> x (t mm, w deg).
Vector6d AmbientFromX(const Vector6d& x);
Vector6d XFromAmbient(const Vector6d& z);
}  // namespace detail

}  // namespace occlude::planner
