// A conservative lower bound of the distance from any point to a tree's voxels,
// for pruning sphere-tree descents by "how far is this node from the whole
// other jaw" in O(1), instead of descending the other tree to find out.
//
// What it stores: for every voxel cell X within `max_voxels` cells (per axis)
// of a surface voxel, Q(X) = 4 m^2, where m is the exact Euclidean distance, in
// voxel units, from X's centre to the nearest surface voxel cube. Per axis the
// gap from a centre to a unit cube |d| cells away is max(0, |d| - 1/2), so 4 m^2
// is a sum of odd squares: an exact small integer (one byte), computed by three
// separable 1-D minimum passes (exact for a sum of per-axis terms). Values are
// capped at (2 max_voxels + 1)^2 ("at least max_voxels + 1/2"); cells beyond
// the band are not stored and read as the cap. Storage: 8x8x8-cell bricks of
// bytes, found through a hash of brick coordinates.
//
// The bound at a point p: m(X) - |p - centre(X)| for X the cell holding p
// (distance is 1-Lipschitz), in mm, so it is exact at cell centres and off by at
// most half a voxel diagonal elsewhere.
//
// Far from the surface one level of cells cannot certify much (the cap), so
// the bound keeps a few levels: voxels (cells of s), and coarser cells of
// s * 2^L holding the occupied octree cubes of level L (which contain the
// voxel cubes, so their distance is also a lower bound), each with the same
// cap in its own cells. A query reads the finest level first and a coarser one
// only where the finer is saturated.
//
// Frame and units: the grid's frame F, mm. Immutable after Build; thread-safe.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "occlude/collision/key_index_hash.h"
#include "occlude/collision/voxel_grid.h"

namespace occlude::collision {

class DistanceBound {
 public:
  /// Largest supported max_voxels (the capped value must fit in a byte).
  static constexpr int kMaxVoxels = 7;

  DistanceBound() = default;
  /// Builds the bound of `grid`'s surface voxels at the octree levels
  /// `levels` (increasing, 0 = voxels). Cost: about (2 max_voxels + 1) per cell
  /// of each level's band, three times. Throws std::invalid_argument when
  /// max_voxels is outside [1, kMaxVoxels] or the levels are not increasing in [0, 20].
  static DistanceBound Build(const VoxelGrid& grid, int max_voxels = kMaxVoxels,
                             const std::vector<int>& levels = {0, 1, 3});

  bool empty() const { return levels_.empty() || levels_[0].bricks.empty(); }
  /// Largest distance the bound can certify, mm (the coarsest level's cap).
  double max_mm() const { return levels_.empty() ? 0.0 : levels_.back().cap_mm; }

  /// Lower bound (mm, may be negative) of the distance from p_F to the union of
  /// the surface voxel cubes. An empty bound returns -inf (proves nothing).
  double LowerBound(const Eigen::Vector3d& p_F) const;

  /// True when every surface voxel cube is farther than `radius` (mm) from
  /// p_F, i.e. a ball of that radius about p_F misses them all. Conservative:
  /// false whenever in doubt (empty bound, NaN, far outside the key range).
  bool Excludes(const Eigen::Vector3d& p_F, double radius) const;
  /// The same for a point given as q0 = (p_F - origin()) / cell_mm(), its
  /// coordinates in the finest level's cells (lets a caller fold the division
  /// into its own transform).
  bool ExcludesAt(const Eigen::Vector3d& q0, double radius) const;
  const Eigen::Vector3d& origin() const { return origin_; }
  /// The finest level's cell edge (the voxel size), mm; 0 when empty.
  double cell_mm() const { return levels_.empty() ? 0.0 : levels_[0].s; }

  std::size_t num_bricks() const;
  std::size_t MemoryBytes() const;

 private:
  using Brick = std::array<std::uint8_t, 512>;  ///< cell x + 8 y + 64 z
  struct Level {
    double s = 0.0;  ///< cell edge, mm
    double inv_s = 0.0;
    double s2 = 0.0;  ///< s^2
    double scale = 1.0;  ///< the finest level's cell edge / s
    double cap_mm = 0.0;
    std::uint8_t cap = 0;
    std::array<double, 256> m_mm{};  ///< Q -> m in mm, rounded down
    std::vector<Brick> bricks;
    detail::KeyIndexHash index;  ///< brick key -> index into bricks
    /// Dense brick index over the bricks' bounding box (coordinates - table_lo,
    /// x fastest; kNotFound = no brick), one load instead of a hash probe;
    /// empty when the box is too sparse to afford (then `index` serves).
    std::vector<std::uint32_t> table;
    Eigen::Vector3i table_lo = Eigen::Vector3i::Zero();
    Eigen::Vector3i table_dims = Eigen::Vector3i::Zero();
    void BuildTable(const std::vector<Eigen::Vector3i>& coords);
    std::uint32_t BrickIndex(const Eigen::Vector3i& b) const;
    /// Q of the cell holding cell coordinates q (continuous), and q minus the
    /// cell's centre; false when q is out of the key range or NaN.
    bool CellQ(const Eigen::Vector3d& q, std::uint8_t* value, Eigen::Vector3d* offset) const;
  };
  static Level BuildLevel(const VoxelGrid& grid, int max_voxels, int level);

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  std::vector<Level> levels_;  ///< finest first
};

}  // namespace occlude::collision
