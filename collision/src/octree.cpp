// Bottom-up sparse octree construction: parents are the unique Morton codes
// >> 3 of the level below, so each level is one linear pass over sorted codes.
// Cost is linear in the number of surface voxels; no dense grid is visited.
#include "occlude/collision/octree.h"

#include "occlude/collision/morton.h"

namespace occlude::collision {
namespace {

struct LevelBuild {
  std::vector<std::uint64_t> keys;
  std::vector<std::uint8_t> mask;
  std::vector<std::uint32_t> first_child;  // index within the level below
};

LevelBuild ParentLevel(const std::vector<std::uint64_t>& child_keys) {
  LevelBuild up;
  for (std::size_t i = 0; i < child_keys.size(); ++i) {
    const std::uint64_t parent = child_keys[i] >> 3;
    const auto slot_bit = static_cast<std::uint8_t>(1u << (child_keys[i] & 7u));
    if (up.keys.empty() || up.keys.back() != parent) {
      up.keys.push_back(parent);
      up.mask.push_back(slot_bit);
      up.first_child.push_back(static_cast<std::uint32_t>(i));
    } else {
      up.mask.back() = static_cast<std::uint8_t>(up.mask.back() | slot_bit);
    }
  }
  return up;
}

}  // namespace

std::size_t Octree::MemoryBytes() const {
  return level_begin.capacity() * sizeof(std::uint32_t) +
         level_end.capacity() * sizeof(std::uint32_t) + coord.capacity() * sizeof(Eigen::Vector3i) +
         first_child.capacity() * sizeof(std::uint32_t) +
         child_mask.capacity() * sizeof(std::uint8_t);
}

Octree BuildOctree(const VoxelGrid& grid) {
  Octree tree;
  if (grid.surface_keys.empty()) return tree;

  std::vector<LevelBuild> levels;  // bottom-up: levels[0] = voxels
  levels.push_back({grid.surface_keys, std::vector<std::uint8_t>(grid.surface_keys.size(), 0),
                    std::vector<std::uint32_t>(grid.surface_keys.size(), 0)});
  while (levels.back().keys.size() > 1) levels.push_back(ParentLevel(levels.back().keys));

  tree.top_level = static_cast<int>(levels.size()) - 1;
  tree.level_begin.assign(levels.size(), 0);
  tree.level_end.assign(levels.size(), 0);
  std::uint32_t next = 0;
  for (int level = tree.top_level; level >= 0; --level) {
    const auto l = static_cast<std::size_t>(level);
    tree.level_begin[l] = next;
    next += static_cast<std::uint32_t>(levels[l].keys.size());
    tree.level_end[l] = next;
  }
  tree.coord.resize(next);
  tree.first_child.resize(next);
  tree.child_mask.resize(next);
  for (int level = tree.top_level; level >= 0; --level) {
    const auto l = static_cast<std::size_t>(level);
    const LevelBuild& lb = levels[l];
    const std::uint32_t below = level > 0 ? tree.level_begin[l - 1] : 0;
    for (std::size_t i = 0; i < lb.keys.size(); ++i) {
      const std::size_t n = tree.level_begin[l] + i;
      tree.coord[n] = MortonDecode(lb.keys[i]);
      tree.child_mask[n] = lb.mask[i];
      tree.first_child[n] = level > 0 ? below + lb.first_child[i] : 0;
    }
  }
  return tree;
}

}  // namespace occlude::collision
