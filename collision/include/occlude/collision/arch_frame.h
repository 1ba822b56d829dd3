// The arch frame of a jaw pair and the centre of the upper occlusal surface: the anatomical
// directions the reports, the planner's settling and the benchmarks measure along, and the one
// point every module rotates the upper jaw about by default (the planner's pivot, the case
// session's pivot, the validation's reference points).
//
// Frames: L is the lower jaw's frame; the upper jaw's mesh is in its own frame U and placed in
// L by a pose X_LU. Millimetres.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "occlude/io/triangle_mesh.h"

namespace occlude::collision {

/// Anatomical directions of the lower arch in L (for left/right and
/// anterior/posterior shares). lateral = occlusal x anterior points to the
/// patient's left.
struct ArchFrame {
  Eigen::Vector3d origin_L = Eigen::Vector3d::Zero();
  Eigen::Vector3d occlusal_L = Eigen::Vector3d::UnitY();  ///< lower -> upper
  Eigen::Vector3d anterior_L = Eigen::Vector3d::UnitZ();  ///< towards the incisors
  Eigen::Vector3d lateral_L = Eigen::Vector3d::UnitX();   ///< patient's left
  double anterior_split_mm = 0.0;  ///< (p - origin).anterior above this = anterior region
};

/// Estimates the arch frame from the two jaws in a common frame (the bite as
/// given): occlusal = normal of the plane fitted through the interface (lower
/// vertices within 1.5 mm of an upper vertex; with fewer than 30 of them, the
/// lower jaw's smallest principal axis), oriented lower -> upper; lateral = the widest
/// horizontal direction of the lower arch; anterior = the horizontal direction
/// where the arch narrows (incisors); the anterior region is the front 35 % of
/// the arch depth.
ArchFrame EstimateArchFrame(const io::TriangleMesh& lower_L, const io::TriangleMesh& upper_L);

/// The centre of the upper arch's occlusal surface, in L with the upper at X_LU: the centre
/// of the upper's bounding box in L (its vertices placed by X_LU) moved along `occlusal_L`
/// (unit, lower -> upper) to the height of the 5th lowest percentile of its vertices (the
/// cusp tips). The origin for an empty mesh.
Eigen::Vector3d UpperOcclusalCentre(const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU,
                                    const Eigen::Vector3d& occlusal_L);

}  // namespace occlude::collision
