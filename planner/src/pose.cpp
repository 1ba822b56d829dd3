// Pose parameterization about a pivot (see pose.h for the formula).
#include "occlude/planner/pose.h"

#include <cmath>

#include "occlude/angles.h"

namespace occlude::planner {
namespace {
constexpr double kDegPerRad = 180.0 / kPi;
}

Eigen::Matrix3d RotationFromVectorDeg(const Eigen::Vector3d& rotation_deg) {
  const double angle_rad = rotation_deg.norm() / kDegPerRad;
  if (angle_rad == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle_rad, rotation_deg.normalized()).toRotationMatrix();
}

Eigen::Vector3d VectorDegFromRotation(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.axis() * aa.angle() * kDegPerRad;
}

Eigen::Isometry3d ComposePose(const PoseParameters& params, const Eigen::Vector3d& p_LPivot,
                              const Eigen::Isometry3d& X_LU_ref) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = RotationFromVectorDeg(params.rotation_deg);
  delta.translation() = p_LPivot + params.translation_mm - delta.linear() * p_LPivot;
  return delta * X_LU_ref;
}

PoseParameters DecomposePose(const Eigen::Isometry3d& X_LU, const Eigen::Vector3d& p_LPivot,
                             const Eigen::Isometry3d& X_LU_ref) {
  const Eigen::Isometry3d delta = X_LU * X_LU_ref.inverse();
  PoseParameters params;
  params.rotation_deg = VectorDegFromRotation(delta.linear());
  params.translation_mm = delta.translation() - p_LPivot + delta.linear() * p_LPivot;
  return params;
}

}  // namespace occlude::planner
