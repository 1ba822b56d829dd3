// The 6-DOF pose of the upper jaw U relative to the lower jaw L, as the planner
// and the user see it: a translation in mm and a rotation in degrees about a
// pivot point (the centre of the upper arch's occlusal surface), so that small
// rotations do not swing the arch around a far-away origin.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace occlude::planner {

/// Pose parameters relative to a reference pose X_LU_ref:
///   X_LU = T(p_LPivot + translation_mm) * R(rotation_deg) * T(-p_LPivot) * X_LU_ref
/// where p_LPivot is the pivot in L at the reference pose and R is the rotation
/// vector (axis * angle) `rotation_deg` in degrees, expressed in L.
struct PoseParameters {
  Eigen::Vector3d translation_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation_deg = Eigen::Vector3d::Zero();
};

/// Rotation matrix of a rotation vector given in degrees (exact for any angle).
Eigen::Matrix3d RotationFromVectorDeg(const Eigen::Vector3d& rotation_deg);
/// Rotation vector in degrees of a rotation matrix (angle in [0, 180]).
Eigen::Vector3d VectorDegFromRotation(const Eigen::Matrix3d& R);

/// X_LU from parameters, pivot p_LPivot (mm, in L) and reference pose X_LU_ref.
Eigen::Isometry3d ComposePose(const PoseParameters& params, const Eigen::Vector3d& p_LPivot,
                              const Eigen::Isometry3d& X_LU_ref);
/// Inverse of ComposePose: the parameters that give X_LU.
PoseParameters DecomposePose(const Eigen::Isometry3d& X_LU, const Eigen::Vector3d& p_LPivot,
                             const Eigen::Isometry3d& X_LU_ref);

}  // namespace occlude::planner
