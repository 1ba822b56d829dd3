// Small helpers shared by the narrow-band field's sources: coordinates and
// layer masks of 4x4x4 bricks in Morton bit order, and box distances in voxel
// units.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

namespace occlude::collision::detail {

/// Coordinates (0..3 each) of bit i of a brick's 64-bit Morton-ordered mask.
inline Eigen::Vector3i BrickLocal(int i) {
  return Eigen::Vector3i((i & 1) | ((i >> 2) & 2), ((i >> 1) & 1) | ((i >> 3) & 2),
                         ((i >> 2) & 1) | ((i >> 4) & 2));
}

/// Bits of a brick mask whose local coordinate along `axis` is in [lo, hi] (0..3).
constexpr std::uint64_t ComputeLayersMask(int axis, int lo, int hi) {
  std::uint64_t m = 0;
  for (int i = 0; i < 64; ++i) {
    const int local = ((i >> axis) & 1) | (((i >> (axis + 3)) & 1) << 1);
    if (local >= lo && local <= hi) m |= std::uint64_t{1} << i;
  }
  return m;
}
/// The same from a table (index axis * 16 + lo * 4 + hi).
inline constexpr std::array<std::uint64_t, 48> kLayersMasks = [] {
  std::array<std::uint64_t, 48> t{};
  for (int axis = 0; axis < 3; ++axis) {
    for (int lo = 0; lo < 4; ++lo) {
      for (int hi = 0; hi < 4; ++hi)
        t[static_cast<std::size_t>(axis * 16 + lo * 4 + hi)] = ComputeLayersMask(axis, lo, hi);
    }
  }
  return t;
}();
inline std::uint64_t LayersMask(int axis, int lo, int hi) {
  return kLayersMasks[static_cast<std::size_t>(axis * 16 + lo * 4 + hi)];
}

/// Squared distance, in voxel units, from continuous voxel coordinates q to the
/// box [lo, hi + 1) of voxel indices.
inline double BoxDistance2(const Eigen::Vector3d& q, const Eigen::Vector3i& lo,
                           const Eigen::Vector3i& hi) {
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double below = lo[a] - q[a];
    const double above = q[a] - (hi[a] + 1.0);
    const double gap = below > 0.0 ? below : (above > 0.0 ? above : 0.0);
    d2 += gap * gap;
  }
  return d2;
}

}  // namespace occlude::collision::detail
