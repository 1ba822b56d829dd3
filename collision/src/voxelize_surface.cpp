// Surface stage of Voxelize: every triangle is tested exactly against the voxels
// of its bounding box, the (Morton key, triangle) pairs that overlap are radix
// sorted once, and the sorted pairs become the CSR arrays of the grid. Cost and
// memory are proportional to the number of (voxel, triangle) pairs.
#include <cmath>

#include "occlude/collision/morton.h"
#include "occlude/collision/triangle_box.h"
#include "voxelize_detail.h"

namespace occlude::collision::detail {
namespace {

/// (key, triangle) packed in one word: key in the high bits, triangle in the low
/// `tri_bits`. Used when key_bits + tri_bits <= 64 (every realistic grid).
struct PackedPairs {
  using Pair = std::uint64_t;
  int tri_bits;
  int key_bits;
  Pair Make(std::uint64_t key, std::uint32_t tri) const { return key << tri_bits | tri; }
  std::uint64_t Key(Pair p) const { return p >> tri_bits; }
  std::uint32_t Tri(Pair p) const {
    return static_cast<std::uint32_t>(p & ((std::uint64_t{1} << tri_bits) - 1));
  }
  void Sort(std::vector<Pair>& pairs) const {
    std::vector<Pair> scratch;
    RadixSort(
        pairs, scratch, [](Pair p) { return p; }, tri_bits, tri_bits + key_bits);
  }
};

/// (key, triangle) as a struct, for grids whose keys leave no room for a triangle index.
struct WidePairs {
  struct Pair {
    std::uint64_t key;
    std::uint32_t tri;
  };
  int key_bits;
  Pair Make(std::uint64_t key, std::uint32_t tri) const { return {key, tri}; }
  std::uint64_t Key(const Pair& p) const { return p.key; }
  std::uint32_t Tri(const Pair& p) const { return p.tri; }
  void Sort(std::vector<Pair>& pairs) const {
    std::vector<Pair> scratch;
    RadixSort(
        pairs, scratch, [](const Pair& p) { return p.key; }, 0, key_bits);
  }
};

/// Voxel index range [lo, hi] along `axis` whose closed cubes can touch [min, max];
/// widened by a hair so rounding never drops a touching voxel (the exact test decides).
void CandidateRange(const GridFrame& f, int axis, double min, double max, std::int32_t* lo,
                    std::int32_t* hi) {
  constexpr double kSlack = 1e-6;  // voxel units; covers kSurfaceSlack and rounding
  const double a = std::floor((min - f.origin[axis]) / f.s - kSlack);
  const double b = std::floor((max - f.origin[axis]) / f.s + kSlack);
  const double top = static_cast<double>(f.dims[axis] - 1);
  *lo = static_cast<std::int32_t>(std::clamp(a, 0.0, top));
  *hi = static_cast<std::int32_t>(std::clamp(b, 0.0, top));
}

/// Tests the voxels (i, j, k) with k in [k0, k1] along `axis` d and the other
/// two indices fixed in ijk; appends the overlapping ones. Returns the tests done.
template <class Codec>
std::size_t TestColumn(const GridFrame& f, const TriangleBoxTester& tester, const Codec& codec,
                       std::uint32_t t, int d, std::int32_t k0, std::int32_t k1,
                       Eigen::Vector3i ijk, std::vector<typename Codec::Pair>* pairs) {
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(f.SurfaceHalfSize());
  Eigen::Vector3d center;
  for (int a = 0; a < 3; ++a) center[a] = f.Center(a, ijk[a]);
  for (std::int32_t k = k0; k <= k1; ++k) {
    ijk[d] = k;
    center[d] = f.Center(d, k);
    if (tester.Overlaps(center, half)) pairs->push_back(codec.Make(MortonEncode(ijk), t));
  }
  return k1 >= k0 ? static_cast<std::size_t>(k1 - k0 + 1) : 0;
}

/// Appends the pairs of triangle t to `pairs`; returns the number of exact tests.
/// Candidates: the voxel columns of the triangle's bounding box along the axis d
/// where its normal is largest, each cut to the few voxels whose centres lie in
/// the slab |n . (x - a)| <= h |n|_1 around the triangle's plane (a necessary
/// condition of overlap, so the cost is ~ area / s^2, not bounding volume / s^3).
template <class Codec>
std::size_t TrianglePairs(const io::TriangleMesh& mesh, const GridFrame& f, const Codec& codec,
                          std::uint32_t t, std::vector<typename Codec::Pair>* pairs) {
  const auto p = Corners(mesh, t);
  const TriangleBoxTester tester(p[0], p[1], p[2]);
  std::int32_t lo[3], hi[3];
  for (int axis = 0; axis < 3; ++axis) {
    const double mn = std::min(p[0][axis], std::min(p[1][axis], p[2][axis]));
    const double mx = std::max(p[0][axis], std::max(p[1][axis], p[2][axis]));
    CandidateRange(f, axis, mn, mx, &lo[axis], &hi[axis]);
  }
  const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
  int d = 0;
  n.cwiseAbs().maxCoeff(&d);
  const int u = (d + 1) % 3, w = (d + 2) % 3;
  const double r = f.SurfaceHalfSize() * n.cwiseAbs().sum();
  constexpr double kSlack = 1e-6;  // voxel units
  std::size_t tests = 0;
  Eigen::Vector3i ijk;
  for (ijk[w] = lo[w]; ijk[w] <= hi[w]; ++ijk[w]) {
    for (ijk[u] = lo[u]; ijk[u] <= hi[u]; ++ijk[u]) {
      std::int32_t k0 = lo[d], k1 = hi[d];
      if (n[d] != 0.0) {  // else degenerate: the whole bounding-box column
        const double q =
            n[u] * (f.Center(u, ijk[u]) - p[0][u]) + n[w] * (f.Center(w, ijk[w]) - p[0][w]);
        const double e0 = (-q - r) / n[d], e1 = (-q + r) / n[d];
        const double c0 = (p[0][d] + std::min(e0, e1) - f.origin[d]) / f.s - 0.5;
        const double c1 = (p[0][d] + std::max(e0, e1) - f.origin[d]) / f.s - 0.5;
        k0 = static_cast<std::int32_t>(
            std::clamp(std::ceil(c0 - kSlack), double(lo[d]), double(hi[d]) + 1.0));
        k1 = static_cast<std::int32_t>(
            std::clamp(std::floor(c1 + kSlack), double(lo[d]) - 1.0, double(hi[d])));
      }
      tests += TestColumn(f, tester, codec, t, d, k0, k1, ijk, pairs);
    }
  }
  return tests;
}

/// Turns key-sorted pairs into surface_keys and the CSR triangle lists.
template <class Codec>
void BuildCsr(const std::vector<typename Codec::Pair>& pairs, const Codec& codec, VoxelGrid* grid) {
  std::size_t num_keys = 0;
  for (std::size_t n = 0; n < pairs.size(); ++n) {
    if (n == 0 || codec.Key(pairs[n]) != codec.Key(pairs[n - 1])) ++num_keys;
  }
  grid->surface_keys.reserve(num_keys);
  grid->triangle_offsets.reserve(num_keys + 1);
  grid->triangle_indices.reserve(pairs.size());
  for (std::size_t n = 0; n < pairs.size(); ++n) {
    const std::uint64_t key = codec.Key(pairs[n]);
    if (n == 0 || key != codec.Key(pairs[n - 1])) {
      grid->surface_keys.push_back(key);
      grid->triangle_offsets.push_back(static_cast<std::uint32_t>(n));
    }
    grid->triangle_indices.push_back(codec.Tri(pairs[n]));
  }
  grid->triangle_offsets.push_back(static_cast<std::uint32_t>(pairs.size()));
}

template <class Codec>
void RunSurface(const io::TriangleMesh& mesh, const GridFrame& f, const Codec& codec,
                std::size_t expected_pairs, VoxelGrid* grid, VoxelizeStats* stats) {
  std::vector<typename Codec::Pair> pairs;
  pairs.reserve(expected_pairs);
  std::size_t tests = 0;
  const auto num_triangles = static_cast<std::uint32_t>(mesh.num_triangles());
  for (std::uint32_t t = 0; t < num_triangles; ++t)
    tests += TrianglePairs(mesh, f, codec, t, &pairs);
  codec.Sort(pairs);  // stable: triangles stay ascending within a voxel
  BuildCsr(pairs, codec, grid);
  stats->triangle_voxel_tests = tests;
}

}  // namespace

void BuildSurface(const io::TriangleMesh& mesh, const GridFrame& frame, std::size_t expected_pairs,
                  VoxelGrid* grid, VoxelizeStats* stats) {
  const int tri_bits = std::max(1, BitWidth(mesh.num_triangles() - 1));
  if (frame.key_bits() + tri_bits <= 64) {
    RunSurface(mesh, frame, PackedPairs{tri_bits, frame.key_bits()}, expected_pairs, grid, stats);
  } else {
    RunSurface(mesh, frame, WidePairs{frame.key_bits()}, expected_pairs, grid, stats);
  }
}

}  // namespace occlude::collision::detail
