// Sparse octree construction from hand-made voxel sets.
#include "occlude/collision/octree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "occlude/collision/morton.h"

namespace occlude::collision {
namespace {

VoxelGrid GridFromCoords(const std::vector<Eigen::Vector3i>& coords) {
  VoxelGrid g;
  g.voxel_size_mm = 0.5;
  for (const auto& c : coords) g.surface_keys.push_back(MortonEncode(c));
  std::sort(g.surface_keys.begin(), g.surface_keys.end());
  g.surface_keys.erase(std::unique(g.surface_keys.begin(), g.surface_keys.end()),
                       g.surface_keys.end());
  g.triangle_offsets.assign(g.surface_keys.size() + 1, 0);
  return g;
}

TEST(MortonTest, RoundTripAndParentShift) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> u(0, kMortonMaxCoord);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3i c(u(rng), u(rng), u(rng));
    ASSERT_EQ(MortonDecode(MortonEncode(c)), c);
    ASSERT_EQ(MortonDecode(MortonEncode(c) >> 3),
              Eigen::Vector3i(c.x() >> 1, c.y() >> 1, c.z() >> 1));
  }
}

TEST(OctreeTest, EmptyAndSingleVoxel) {
  EXPECT_TRUE(BuildOctree(GridFromCoords({})).empty());
  const Octree one = BuildOctree(GridFromCoords({{5, 6, 7}}));
  EXPECT_EQ(one.top_level, 0);
  EXPECT_EQ(one.num_nodes(), 1u);
  EXPECT_EQ(one.coord[0], Eigen::Vector3i(5, 6, 7));
}

TEST(OctreeTest, LevelsMatchShiftedCoordinatesOnRandomSparseSets) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    std::uniform_int_distribution<int> u(0, 37 + 13 * trial);  // not a power of two
    std::vector<Eigen::Vector3i> coords;
    for (int i = 0; i < 300; ++i) coords.emplace_back(u(rng), u(rng), u(rng));
    const VoxelGrid g = GridFromCoords(coords);
    const Octree t = BuildOctree(g);
    ASSERT_EQ(t.level_size(t.top_level), 1u);
    EXPECT_EQ(t.level_begin[static_cast<std::size_t>(t.top_level)], 0u);
    ASSERT_EQ(t.num_leaves(), g.surface_keys.size());
    for (std::size_t i = 0; i < g.surface_keys.size(); ++i) {
      ASSERT_EQ(MortonEncode(t.coord[t.leaf_begin() + i]),
                g.surface_keys[i]);  // leaf order = grid order
    }
    for (int level = 1; level <= t.top_level; ++level) {
      std::set<std::uint64_t> expected;
      for (const auto key : g.surface_keys) expected.insert(key >> (3 * level));
      ASSERT_EQ(t.level_size(level), expected.size()) << "level " << level;
      for (auto n = t.level_begin[level]; n < t.level_end[level]; ++n) {
        EXPECT_TRUE(expected.count(MortonEncode(t.coord[n])));
        ASSERT_NE(t.child_mask[n], 0);
        std::uint32_t child = t.first_child[n];
        for (int slot = 0; slot < 8; ++slot) {
          if (!(t.child_mask[n] & (1 << slot))) continue;
          ASSERT_GE(child, t.level_begin[level - 1]);
          ASSERT_LT(child, t.level_end[level - 1]);
          EXPECT_EQ(t.coord[child],
                    2 * t.coord[n] + Eigen::Vector3i(slot & 1, (slot >> 1) & 1, slot >> 2));
          ++child;
        }
      }
    }
  }
}

}  // namespace
}  // namespace occlude::collision
