// Each query's answer in `occlude bench --accuracy` turned into claims about
// the upper surface (bench_accuracy_score_internal.h defines claims and how they are
// scored): which points or elements a method says are in contact, at what
// distance, and how a truth contact counts as covered by them.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <utility>
#include <vector>

#include "bench/bench_accuracy_score_internal.h"
#include "bench/fcl_peer.h"
#include "occlude/collision/collide.h"
#include "occlude/collision/oracle.h"

namespace occlude::app {

/// The oracle's contacts and penetrations as point claims (at the voxel level
/// each claim stands for its upper voxel; else it covers its sample spacing).
Answer OracleAnswer(const collision::JawOracle& oracle, const collision::OracleResult& result,
                    const Eigen::Isometry3d& X_LU, double spacing_mm);
/// The upper voxels of the voxel pairs, each a region claim within delta.
Answer PairsVoxelAnswer(const collision::SphereTree& upper, const collision::CollisionResult& r,
                        double delta_mm);
/// Per upper triangle of the exact pairs, its closest approach: a point claim
/// at the triangle pair's unsigned distance.
Answer PairsExactAnswer(const collision::CollisionResult& r);
/// FCL's intersecting pairs (lower, upper triangle): each upper triangle a
/// region claim at band 0.
Answer FclPairsAnswer(const std::vector<std::pair<std::size_t, std::size_t>>& pairs);
/// FCL's distance: one point claim, no contact list.
Answer FclDistanceAnswer(const FclQueryResult& r);

/// Voxel pairs sorted, and exact contacts' (lower, upper) triangles: what must
/// agree between sphere modes.
std::vector<collision::VoxelPair> SortedPairs(const collision::CollisionResult& r);
std::vector<std::pair<std::uint32_t, std::uint32_t>> ContactKeys(
    const collision::CollisionResult& r);

}  // namespace occlude::app
