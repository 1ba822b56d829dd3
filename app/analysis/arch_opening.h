// Which way the incisors are, from the outline of the crowns seen from the occlusal side: the
// dental arch is a U, and the edge of its convex hull that spans the U's opening (between the
// last molars) is the one whose middle lies farthest from any crown. Anterior is across that
// edge, into the U.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace occlude::analysis {

struct ArchOpening {
  Eigen::Vector2d anterior{0.0, 1.0};  ///< unit, in the plane coordinates of the points
  Eigen::Vector2d middle{0.0, 0.0};    ///< middle of the opening's hull edge
  double width_mm = 0.0;               ///< length of that edge
  double depth_mm = 0.0;               ///< distance from its middle to the nearest crown point
  double confidence = 0.0;  ///< in [0, 1]: how much emptier it is than the next-best edge
};

/// Convex hull of 2-D points, counter-clockwise, without collinear points.
std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> points);

/// The opening of the arch whose crowns cover `crown_points` (plane coordinates, mm); nullopt
/// semantics: confidence 0 when fewer than 3 points or no hull edge is empty in its middle.
ArchOpening FindArchOpening(const std::vector<Eigen::Vector2d>& crown_points);

}  // namespace occlude::analysis
