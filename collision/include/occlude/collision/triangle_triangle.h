// Exact triangle-triangle intersection test and minimum distance: the narrow
// phase under every contact query between the two jaw meshes (mm, any common
// frame). "Exact" means exact up to floating-point rounding: every decision is
// the sign of a determinant of the input coordinates, and a quantity is treated
// as zero only when it lies within a rounding bound of zero (see the .cpp).
// Exception, thin triangles: with a corner angle of sine s < 1e-3 a triangle's
// plane is known only to ~eps / s, so results involving it are accurate to
// about that times its size; with s <= 1.5e-8 it counts as its longest edge.
#pragma once

#include <Eigen/Core>

namespace occlude::collision {

/// True when the closed triangles (a0,a1,a2) and (b0,b1,b2) share at least one
/// point (touching counts). Coplanar and degenerate (segment/point) triangles
/// are handled. No allocation, no normalisation.
bool TrianglesIntersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                        const Eigen::Vector3d& a2, const Eigen::Vector3d& b0,
                        const Eigen::Vector3d& b1, const Eigen::Vector3d& b2);

/// Result of TriangleTriangleDistance / TrianglesWithin.
struct TriangleDistance {
  double distance = 0.0;                          ///< Euclidean, mm; 0 when they intersect
  Eigen::Vector3d p_a = Eigen::Vector3d::Zero();  ///< closest point on A
  Eigen::Vector3d p_b = Eigen::Vector3d::Zero();  ///< closest point on B
  /// The TrianglesIntersect verdict. When true, p_a and p_b are one common
  /// point (equal up to rounding) and distance is 0. (A pair touching only up
  /// to rounding may be judged disjoint and still get a distance that rounds
  /// to 0.)
  bool intersecting = false;
};

/// Minimum distance between the closed triangles A = (a0,a1,a2) and
/// B = (b0,b1,b2), with the closest points. When they do not intersect,
/// distance == |p_a - p_b| (computed from the returned points).
TriangleDistance TriangleTriangleDistance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                          const Eigen::Vector3d& a2, const Eigen::Vector3d& b0,
                                          const Eigen::Vector3d& b1, const Eigen::Vector3d& b2);

/// True when the distance between A and B is <= max_distance. When true and
/// `out` is non-null, *out is exactly what TriangleTriangleDistance returns.
/// When false, out->distance is a lower bound of the distance that exceeds
/// max_distance (p_a/p_b unspecified, intersecting false): the function returns
/// as soon as a bounding-box or plane test proves the triangles farther apart
/// than max_distance. `out` may be null.
bool TrianglesWithin(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                     const Eigen::Vector3d& a2, const Eigen::Vector3d& b0,
                     const Eigen::Vector3d& b1, const Eigen::Vector3d& b2, double max_distance,
                     TriangleDistance* out);

}  // namespace occlude::collision
