// Morton (Z-order) codes of non-negative integer voxel coordinates, 21 bits per
// axis (0 .. 2,097,151), bit order ... z1 y1 x1 z0 y0 x0. A parent octree node's
// code is its child's code >> 3, and the low 3 bits are the child slot
// (bit 0 = x, bit 1 = y, bit 2 = z), so sorted codes group siblings together.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace occlude::collision {

inline constexpr std::int32_t kMortonMaxCoord = (1 << 21) - 1;

namespace detail {
inline std::uint64_t SpreadBits3(std::uint64_t v) {
  v &= 0x1fffffULL;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}
inline std::uint32_t CompactBits3(std::uint64_t v) {
  v &= 0x1249249249249249ULL;
  v = (v ^ (v >> 2)) & 0x10c30c30c30c30c3ULL;
  v = (v ^ (v >> 4)) & 0x100f00f00f00f00fULL;
  v = (v ^ (v >> 8)) & 0x1f0000ff0000ffULL;
  v = (v ^ (v >> 16)) & 0x1f00000000ffffULL;
  v = (v ^ (v >> 32)) & 0x1fffffULL;
  return static_cast<std::uint32_t>(v);
}
}  // namespace detail

/// Code of (x, y, z); each must be in [0, kMortonMaxCoord].
inline std::uint64_t MortonEncode(std::int32_t x, std::int32_t y, std::int32_t z) {
  return detail::SpreadBits3(static_cast<std::uint64_t>(x)) |
         detail::SpreadBits3(static_cast<std::uint64_t>(y)) << 1 |
         detail::SpreadBits3(static_cast<std::uint64_t>(z)) << 2;
}
inline std::uint64_t MortonEncode(const Eigen::Vector3i& c) {
  return MortonEncode(c.x(), c.y(), c.z());
}

inline Eigen::Vector3i MortonDecode(std::uint64_t code) {
  return Eigen::Vector3i(static_cast<int>(detail::CompactBits3(code)),
                         static_cast<int>(detail::CompactBits3(code >> 1)),
                         static_cast<int>(detail::CompactBits3(code >> 2)));
}

}  // namespace occlude::collision
