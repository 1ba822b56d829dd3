// The geometry of implicit spheres: everything the traversal needs to derive a
// node's sphere from its octree cube, without storing it.
//
// Simple sphere (paper eq. 3): centre = cube centre, radius = sqrt(3)/2 * edge.
// Child offset: a node at level L has edge s*2^L, its children edge s*2^(L-1),
// so each child's centre is offset from the parent's centre by a quarter of the
// parent's edge, s*2^(L-2), along every axis (sign from the child slot). The
// paper's s*2^(L-1) is the same offset with L counting the child's level, and
// Ruffaldi's s*2^(L-2) with L counting the parent's; tests/collision prove it.
//
// Optimized sphere: the smallest sphere enclosing the occupied child CUBES (not
// the child spheres): the leaf test of the traversal is on voxel cubes, and
// cubes nest, so a sphere that encloses its occupied child cubes encloses every
// voxel cube beneath it. One entry per 8-bit child mask, in units of the node's
// edge, with the centre relative to the node's cube centre. Entry 0 (a leaf,
// which has no children) is the cube's own circumsphere.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace occlude::collision {

/// sqrt(3)/2: radius of the sphere enclosing a unit cube.
inline constexpr double kCubeCircumradius = 0.86602540378443864676;

inline double SimpleRadius(double edge) { return kCubeCircumradius * edge; }

/// Per-axis offset from a parent node's centre to each child's centre, for a
/// parent at `parent_level` with voxel size s: s * 2^(parent_level - 2).
inline double ChildCenterOffset(double voxel_size_mm, int parent_level) {
  return std::ldexp(voxel_size_mm, parent_level - 2);
}

/// +1 or -1 per axis for child slot 0..7 (bit 0 = x, bit 1 = y, bit 2 = z).
inline Eigen::Vector3d ChildSlotSign(int slot) {
  return Eigen::Vector3d((slot & 1) ? 1.0 : -1.0, (slot & 2) ? 1.0 : -1.0, (slot & 4) ? 1.0 : -1.0);
}

struct UnitSphere {
  Eigen::Vector3d center;  ///< relative to the node's cube centre, in node edges
  double radius = 0.0;     ///< in node edges
};

/// The optimized-sphere lookup table over the 256 child masks (computed once).
const std::array<UnitSphere, 256>& OptimizedSphereTable();

/// Smallest enclosing sphere of a point set (Welzl's algorithm); exposed for tests.
UnitSphere MinimumEnclosingSphere(const Eigen::Vector3d* points, int count);

}  // namespace occlude::collision
