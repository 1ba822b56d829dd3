// What each query answered, as claims about the upper surface (see
// bench_accuracy_answers_internal.h).
#include <algorithm>
#include <map>

#include "bench/bench_accuracy_answers_internal.h"

namespace occlude::app {

using collision::AccuracyLevel;

Answer OracleAnswer(const collision::JawOracle& oracle, const collision::OracleResult& result,
                    const Eigen::Isometry3d& X_LU, double spacing_mm) {
  Answer a;
  const bool voxel = result.level == AccuracyLevel::kVoxel;
  a.cover = voxel ? Cover::kVoxel : Cover::kRadius;
  a.radius_mm = spacing_mm;
  a.grid = &oracle.upper_tree().grid();
  a.has_depth = true;
  a.max_penetration_mm = result.max_penetration_mm;
  const Eigen::Isometry3d X_UL = X_LU.inverse();
  for (const auto* list : {&result.contacts, &result.penetrations}) {
    for (const collision::SurfacePoint& p : *list) {
      Claim c;
      c.p_L = p.p_L;
      c.d_mm = p.distance_mm;
      if (voxel) c.element = SurfaceVoxelOf(*a.grid, X_UL * p.p_L);
      a.claims.push_back(c);
    }
  }
  return a;
}

// Upper voxels of the voxel pairs, each claimed within delta.
Answer PairsVoxelAnswer(const collision::SphereTree& upper, const collision::CollisionResult& r,
                        double delta_mm) {
  Answer a;
  a.region = true;
  a.cover = Cover::kVoxel;
  a.grid = &upper.grid();
  std::vector<std::uint32_t> voxels;
  for (const collision::VoxelPair& p : r.pairs) voxels.push_back(p.voxel_b);
  std::sort(voxels.begin(), voxels.end());
  voxels.erase(std::unique(voxels.begin(), voxels.end()), voxels.end());
  for (const std::uint32_t v : voxels) {
    Claim c;
    c.d_mm = delta_mm;
    c.element = v;
    a.claims.push_back(c);
  }
  return a;
}

// Per upper triangle of the exact pairs, its closest approach (point, distance).
Answer PairsExactAnswer(const collision::CollisionResult& r) {
  Answer a;
  a.cover = Cover::kTriangle;
  std::map<std::uint32_t, const collision::TriangleContact*> closest;
  for (const collision::TriangleContact& c : r.contacts) {
    auto [it, inserted] = closest.emplace(c.triangle_b, &c);
    if (!inserted && c.distance_mm < it->second->distance_mm) it->second = &c;
  }
  for (const auto& [t, c] : closest) {
    Claim claim;
    claim.p_L = c->p_A_on_b;
    claim.d_mm = c->distance_mm;
    claim.element = t;
    a.claims.push_back(claim);
  }
  return a;
}

std::vector<collision::VoxelPair> SortedPairs(const collision::CollisionResult& r) {
  std::vector<collision::VoxelPair> pairs = r.pairs;
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> ContactKeys(
    const collision::CollisionResult& r) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> keys;
  for (const auto& c : r.contacts) keys.emplace_back(c.triangle_a, c.triangle_b);
  return keys;  // already sorted by (a, b)
}

Answer FclPairsAnswer(const std::vector<std::pair<std::size_t, std::size_t>>& pairs) {
  Answer a;
  a.region = true;
  a.cover = Cover::kTriangle;
  std::vector<std::size_t> upper;
  for (const auto& [lower, up] : pairs) upper.push_back(up);
  std::sort(upper.begin(), upper.end());
  upper.erase(std::unique(upper.begin(), upper.end()), upper.end());
  for (const std::size_t t : upper) {
    Claim c;
    c.d_mm = 0.0;  // intersecting: touching or inside somewhere on the triangle
    c.element = static_cast<std::int64_t>(t);
    a.claims.push_back(c);
  }
  return a;
}

Answer FclDistanceAnswer(const FclQueryResult& r) {
  Answer a;
  a.cover = Cover::kNone;
  a.claims.push_back({r.p_L_on_upper, r.distance_mm, -1});
  return a;
}

}  // namespace occlude::app
