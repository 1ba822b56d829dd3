// Closest point on a triangle to a point: the exact primitive under every
// distance the collision module reports (mm, any common frame).
#pragma once

#include <Eigen/Core>

namespace occlude::collision {

/// Result of ClosestPointOnTriangle.
struct TrianglePoint {
  Eigen::Vector3d point;        ///< closest point on the (closed) triangle
  Eigen::Vector3d barycentric;  ///< weights of a, b, c (non-negative, sum 1)
  double squared_distance = 0.0;
};

/// Closest point of triangle (a, b, c) to p. Degenerate triangles (segments,
/// points) are handled: the answer is then the closest point of the segment/point.
TrianglePoint ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Closest points between segments [p0, p1] and [q0, q1]: returns the squared
/// distance and writes the parameters s, t in [0, 1] of the closest points.
double ClosestPointsSegmentSegment(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                   const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, double* s,
                                   double* t);

}  // namespace occlude::collision
