// Internals of the least-squares model (least_squares.h): the fixed sample
// set, the per-sample residuals with analytic Jacobians in the ambient
// parameters z = (t mm, w rad), and the pose manifold about the pivot.
#pragma once

#include <Eigen/Core>
#include <cstdint>
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

  /// The rotation of ambient parameters z = (t mm, w rad) and its left Jacobian, which every
  /// sample at z shares: computed once per parameter point, not once per sample.
  struct PoseAt {
    explicit PoseAt(const Vector6d& z);
    Vector6d z;
    Eigen::Matrix3d R;   ///< Exp(w)
    Eigen::Matrix3d Jl;  ///< LeftJacobian(w)
  };

  /// Signed distance of sample i at the pose's parameters and its gradient (1x6) in z.
  double Distance(std::size_t i, const PoseAt& pose, Row6d* gradient) const;
  /// Hinge and attraction residuals of sample i (see least_squares.h) with their Jacobians.
  void Residuals(std::size_t i, const PoseAt& pose, double* hinge, double* attraction,
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

/// The residuals of one model's samples at the last parameter point asked for. Ceres evaluates
/// a sample's hinge and attraction as two residual blocks at the same point, and every block at
/// one rotation: the memo computes the rotation once per point and each sample's residuals once
/// per point (once more with their Jacobians when a cost-only evaluation came first). The
/// answers are bit-identical to Impl::Residuals. Not thread-safe: one memo per Ceres problem,
/// which evaluates on one thread.
class ResidualMemo {
 public:
  explicit ResidualMemo(const SurfaceResiduals::Impl& model);

  struct Sample {
    std::uint64_t point = 0;  ///< the number of the point it was computed at; 0: never
    bool has_jacobians = false;
    double hinge = 0.0, attraction = 0.0;
    Row6d j_hinge = Row6d::Zero(), j_attraction = Row6d::Zero();
  };

  /// Sample i's residuals at ambient parameters z[0..5] (and their Jacobians if `jacobians`).
  const Sample& At(std::size_t i, const double* z, bool jacobians);

 private:
  const SurfaceResiduals::Impl& model_;
  SurfaceResiduals::Impl::PoseAt pose_;
  std::uint64_t point_ = 0;
  std::vector<Sample> samples_;
};

/// The rotation of rotation vector w (rad): Exp(w) = exp(Hat(w)).
Eigen::Matrix3d Exp(const Eigen::Vector3d& w);
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
