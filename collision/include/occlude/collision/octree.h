// Sparse octree over the surface voxels of a VoxelGrid, built bottom-up (the
// paper's "optimized octree": a node exists only if some voxel below it does,
// and only non-empty children are stored).
//
// Levels: level 0 = voxels (leaves), a node at level L covers the cube of
// 2^L x 2^L x 2^L voxels whose integer coordinates at that level are `coord`
// (voxel coordinates >> L). The top level holds exactly one node, the root.
//
// Storage is flat, top-down: the root is node 0, then every node of the next
// level in Morton order, down to the leaves. Children of a node are contiguous
// (in child-slot order, slot bit 0 = x, 1 = y, 2 = z) starting at first_child.
// Leaf n (level 0) is surface voxel (n - leaf_begin()) of the grid, so its
// triangles are the grid's CSR list for that voxel.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "occlude/collision/voxel_grid.h"

namespace occlude::collision {

struct Octree {
  int top_level = -1;                      ///< level of the root; -1 when empty
  std::vector<std::uint32_t> level_begin;  ///< nodes of level L: [level_begin[L], level_end[L])
  std::vector<std::uint32_t> level_end;
  std::vector<Eigen::Vector3i> coord;      ///< node coordinates at its own level
  std::vector<std::uint32_t> first_child;  ///< first child index (0 for leaves)
  std::vector<std::uint8_t> child_mask;    ///< bit k set = child slot k present (0 for leaves)

  bool empty() const { return coord.empty(); }
  std::size_t num_nodes() const { return coord.size(); }
  std::size_t num_leaves() const { return level_size(0); }
  std::uint32_t leaf_begin() const { return level_begin.empty() ? 0 : level_begin[0]; }
  std::size_t level_size(int level) const {
    const auto l = static_cast<std::size_t>(level);
    return l < level_begin.size() ? level_end[l] - level_begin[l] : 0;
  }
  std::size_t MemoryBytes() const;
};

/// Builds the octree of `grid`'s surface voxels. An empty grid gives an empty tree.
Octree BuildOctree(const VoxelGrid& grid);

}  // namespace occlude::collision
