// The occlusal plane of one jaw's mesh in any frame: which way the crowns point and the plane
// through their cusps. The crowns stick out of the gingiva or base: seen from the occlusal side
// the surface faces the viewer (an open scan seen from behind shows its back faces) and is
// rugged (a model's base or a slab's back is flat); the plane is then fitted through the
// highest local maxima of the surface seen from that side (cusp tips and incisal edges).
#pragma once

#include <Eigen/Core>
#include <string>

#include "height_map.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::analysis {

struct OcclusalPlane {
  Eigen::Vector3d point_J = Eigen::Vector3d::Zero();  ///< centroid of the cusps it was fitted to
  Eigen::Vector3d up_J = Eigen::Vector3d::UnitZ();    ///< unit normal, out of the crowns
  int cusps = 0;                                      ///< local maxima the plane was fitted through
  double rms_mm = 0.0;                                ///< their RMS distance from it
  double confidence = 0.0;  ///< in [0, 1]: how clearly one side showed the crowns
  std::string note;         ///< doubts, empty when none
};

/// Local maxima of a height map: filled cells at least as high as every filled cell within
/// `radius_mm`, and higher than the mean of that neighbourhood by `prominence_mm`.
std::vector<int> HeightPeaks(const HeightMap& map, double radius_mm, double prominence_mm);

/// The occlusal plane of `mesh` (non-empty), from maps of `cell` mm.
OcclusalPlane FindOcclusalPlane(const io::TriangleMesh& mesh, double cell);

}  // namespace occlude::analysis
