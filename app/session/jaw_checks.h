// Plausibility checks of a jaw pair that do not stop a run but deserve a
// warning before any work: two jaws far apart (their files may not share a
// frame, so every contact figure would be meaningless) and the same surface
// given for both jaws.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

/// Bounding boxes farther apart than this (mm) at the pose give a warning: a
/// bite scan interlocks, an open scan is a few millimetres apart.
inline constexpr double kJawsFarApartMm = 50.0;

/// Warnings (one line each, without the "warning:" prefix) for the jaws at the
/// pose X_LU: far apart, or identical (same triangles, vertices within 1e-9 mm).
/// `lower_name` and `upper_name` name the files in the messages.
std::vector<std::string> JawPairWarnings(const io::TriangleMesh& lower_L,
                                         const io::TriangleMesh& upper_U,
                                         const Eigen::Isometry3d& X_LU,
                                         const std::string& lower_name,
                                         const std::string& upper_name);

}  // namespace occlude::app
