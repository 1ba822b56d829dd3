// Private helpers shared by the voxelization stages (voxelize_*.cpp): the grid
// frame, an LSD radix sort over a bit range, and the stage entry points. Not
// installed; nothing outside collision/src includes it.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "occlude/collision/voxel_grid.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::collision::detail {

/// Placement of the grid: voxel (i, j, k) is the cube origin + s * [(i,j,k), (i,j,k) + 1].
struct GridFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double s = 0.0;
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  int coord_bits = 1;  ///< bits needed by the largest coordinate (dims - 1), >= 1

  /// Centre of voxel (i, j, k), computed exactly as VoxelGrid::VoxelCenter does.
  double Center(int axis, std::int32_t index) const {
    return origin[axis] + s * (static_cast<double>(index) + 0.5);
  }
  /// As VoxelGrid::SurfaceHalfSize.
  double SurfaceHalfSize() const { return 0.5 * s * (1.0 + kSurfaceSlack); }
  /// Bits used by a Morton key of this grid.
  int key_bits() const { return 3 * coord_bits; }
};

/// Number of bits needed to write v (0 for v = 0).
inline int BitWidth(std::uint64_t v) {
  int n = 0;
  while (v != 0) {
    ++n;
    v >>= 1;
  }
  return n;
}

/// Stable LSD radix sort of `v` by bits [lo_bit, hi_bit) of key(element), 11 bits
/// per pass; passes in which every element has the same digit are skipped.
/// `scratch` is working storage (resized to v.size()).
template <class T, class KeyFn>
void RadixSort(std::vector<T>& v, std::vector<T>& scratch, KeyFn key, int lo_bit, int hi_bit) {
  constexpr int kDigitBits = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;
  if (v.size() < 2) return;
  scratch.resize(v.size());
  std::vector<std::size_t> count(kBuckets);
  for (int shift = lo_bit; shift < hi_bit; shift += kDigitBits) {
    const int width = std::min(kDigitBits, hi_bit - shift);
    const std::uint64_t mask = (std::uint64_t{1} << width) - 1;
    std::fill(count.begin(), count.end(), 0);
    for (const T& x : v) ++count[(key(x) >> shift) & mask];
    if (count[(key(v[0]) >> shift) & mask] == v.size()) continue;  // one digit: nothing to do
    std::size_t sum = 0;
    for (std::size_t& c : count) {
      const std::size_t n = c;
      c = sum;
      sum += n;
    }
    for (const T& x : v) scratch[count[(key(x) >> shift) & mask]++] = x;
    v.swap(scratch);
  }
}

/// Sorts plain 64-bit keys by bits [0, bits) and removes duplicates.
inline void SortUnique(std::vector<std::uint64_t>& keys, int bits) {
  std::vector<std::uint64_t> scratch;
  RadixSort(
      keys, scratch, [](std::uint64_t k) { return k; }, 0, bits);
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
}

/// Keys of sorted `a` that are not in sorted `b`, exactly sized.
inline std::vector<std::uint64_t> SortedDifference(const std::vector<std::uint64_t>& a,
                                                   const std::vector<std::uint64_t>& b) {
  std::vector<std::uint64_t> out;
  for (int pass = 0; pass < 2; ++pass) {  // count, then fill the exact size
    std::size_t count = 0;
    for (std::size_t i = 0, j = 0; i < a.size(); ++i) {
      while (j < b.size() && b[j] < a[i]) ++j;
      if (j < b.size() && b[j] == a[i]) continue;
      if (pass == 1) out.push_back(a[i]);
      ++count;
    }
    if (pass == 0) out.reserve(count);
  }
  return out;
}

/// Corners of triangle t.
inline std::array<Eigen::Vector3d, 3> Corners(const io::TriangleMesh& mesh, std::size_t t) {
  return {mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)};
}

/// True when run r contains voxel (x, y, z); runs sorted by (z, y, x_begin), disjoint.
bool RunsContain(const std::vector<VoxelRun>& runs, std::int32_t x, std::int32_t y, std::int32_t z);

/// Surface stage: fills surface_keys and the CSR triangle lists of `grid`.
void BuildSurface(const io::TriangleMesh& mesh, const GridFrame& frame, std::size_t expected_pairs,
                  VoxelGrid* grid, VoxelizeStats* stats);

/// Proximity stage (needs the surface): fills proximity_keys.
void BuildProximity(const io::TriangleMesh& mesh, const GridFrame& frame, int layers,
                    VoxelGrid* grid);

/// Interior stage (needs the surface): fills interior_runs and the component counts,
/// then removes Interior voxels from proximity_keys so the classes are disjoint.
void BuildInterior(const io::TriangleMesh& mesh, const GridFrame& frame, VoxelGrid* grid,
                   VoxelizeStats* stats);

/// Per triangle, the closed component it belongs to as the interior stage finds them (dense
/// ids), or -1 when its component is open: for cutting a mesh without opening a closed one.
std::vector<std::int32_t> ClosedComponentOfTriangle(const io::TriangleMesh& mesh);

/// Per triangle, its connected component as the interior stage finds them (dense ids,
/// every component, open or closed): each is one connected piece of surface.
std::vector<std::int32_t> ComponentOfTriangle(const io::TriangleMesh& mesh);

}  // namespace occlude::collision::detail
