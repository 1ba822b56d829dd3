// Exact refinement: the triangles stored per surface voxel turn each voxel pair
// into candidate triangle pairs; duplicates (the same two triangles meet in
// many voxel pairs) are removed by sorting 64-bit keys, then each pair gets the
// exact triangle-triangle distance with an early exit beyond delta.
#include "collide_exact.h"

#include <algorithm>

#include "occlude/collision/triangle_triangle.h"

namespace occlude::collision {

void RefineExact(const SphereTree& a, const SphereTree& b, const Eigen::Isometry3d& X_AB,
                 double delta_mm, CollisionResult* result) {
  thread_local std::vector<std::uint64_t> keys;
  keys.clear();
  const VoxelGrid& ga = a.grid();
  const VoxelGrid& gb = b.grid();
  for (const VoxelPair& p : result->pairs) {
    for (auto i = ga.triangles_begin(p.voxel_a); i < ga.triangles_end(p.voxel_a); ++i) {
      const std::uint64_t ta = ga.triangle_indices[i];
      for (auto j = gb.triangles_begin(p.voxel_b); j < gb.triangles_end(p.voxel_b); ++j) {
        keys.push_back(ta << 32 | gb.triangle_indices[j]);
      }
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  result->triangle_tests = keys.size();

  const io::TriangleMesh& ma = a.mesh();
  const io::TriangleMesh& mb = b.mesh();
  for (const std::uint64_t key : keys) {
    const auto ta = static_cast<std::uint32_t>(key >> 32);
    const auto tb = static_cast<std::uint32_t>(key & 0xffffffffu);
    const Eigen::Vector3d b0 = X_AB * mb.corner(tb, 0);
    const Eigen::Vector3d b1 = X_AB * mb.corner(tb, 1);
    const Eigen::Vector3d b2 = X_AB * mb.corner(tb, 2);
    TriangleDistance d;
    if (!TrianglesWithin(ma.corner(ta, 0), ma.corner(ta, 1), ma.corner(ta, 2), b0, b1, b2, delta_mm,
                         &d)) {
      continue;
    }
    TriangleContact c;
    c.triangle_a = ta;
    c.triangle_b = tb;
    c.distance_mm = d.distance;
    c.p_A_on_a = d.p_a;
    c.p_A_on_b = d.p_b;
    c.intersecting = d.intersecting;
    result->triangles_intersect = result->triangles_intersect || c.intersecting;
    if (c.distance_mm < result->min_distance_mm) {
      result->min_distance_mm = c.distance_mm;
      result->closest = c;
    }
    result->contacts.push_back(c);
  }
}

}  // namespace occlude::collision
