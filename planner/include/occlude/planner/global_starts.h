// The start poses the global search is validated from, drawn from a caller's seeded
// generator so that `occlude validate --global` and bench/global_measure.cpp draw the same
// starts: the upper jaw shifted along the arch from its reference (`sagittal`), shifted by a cusp
// period (`cusp`) or turned and moved far away (`apart`). Millimetres in L; the pivot in L at the
// reference pose.
#pragma once

#include <Eigen/Geometry>
#include <random>

namespace occlude::planner {

/// A unit vector uniform on the sphere.
Eigen::Vector3d RandomUnitVector(std::mt19937& rng);

/// A rotation uniform on SO(3) (a normalized Gaussian quaternion).
Eigen::Matrix3d UniformRotation(std::mt19937& rng);

/// The reference shifted along `anterior_L` by a uniform 3-12 mm either way plus a rotation of
/// up to 10 deg (uniform angle) about a random axis through `p_LPivot` (ComposePose about the
/// pivot, relative to X_LU_ref).
Eigen::Isometry3d SagittalStart(const Eigen::Isometry3d& X_LU_ref, const Eigen::Vector3d& p_LPivot,
                                const Eigen::Vector3d& anterior_L, std::mt19937& rng);

/// The reference shifted along `anterior_L` by `shift_mm` (signed: + moves the upper forward, the
/// Class II way) plus a jitter of up to 0.5 mm (uniform in the ball) and up to 3 deg (uniform
/// angle, random axis through `p_LPivot`), so that starts a cusp period off sit in different
/// frames.
Eigen::Isometry3d CuspStart(const Eigen::Isometry3d& X_LU_ref, const Eigen::Vector3d& p_LPivot,
                            const Eigen::Vector3d& anterior_L, double shift_mm, std::mt19937& rng);

/// The upper at the reference turned uniformly at random about `p_LPivot`, then moved 20-60 mm
/// (uniform) in a random direction.
Eigen::Isometry3d ApartStart(const Eigen::Isometry3d& X_LU_ref, const Eigen::Vector3d& p_LPivot,
                             std::mt19937& rng);

}  // namespace occlude::planner
