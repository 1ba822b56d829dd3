// Pose files: a JSON object holding a 4x4 rigid transform X_LU (the pose of the
// upper jaw U in the lower jaw frame L, mm), under "X_LU" or "matrix".
#pragma once

#include <Eigen/Geometry>
#include <filesystem>

namespace occlude::app {

/// Reads and validates a pose file. Throws UserError naming the file and what is
/// wrong: unreadable, not JSON, no matrix, not 4x4, non-finite, not rigid
/// (rotation not orthonormal within 1e-6, a reflection, or last row not 0 0 0 1).
Eigen::Isometry3d ReadPoseFile(const std::filesystem::path& file);

/// Checks a matrix is a finite rigid transform; returns an empty string if so,
/// else what is wrong.
std::string RigidTransformError(const Eigen::Matrix4d& m);

}  // namespace occlude::app
