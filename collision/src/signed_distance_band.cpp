// NarrowBandSdf: exact signed distances at the corners of the voxels around
// the surface (closest triangle found through 4x4x4 bricks of surface voxels,
// signed by pseudo-normals), stored as 8 floats per band voxel found through a
// brick set (hash of 4x4x4 bricks + popcount rank), and trilinear queries with
// analytic gradients.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "occlude/collision/closest_point.h"
#include "occlude/collision/floor_int.h"
#include "occlude/collision/morton.h"
#include "occlude/collision/signed_distance.h"
#include "parallel.h"
#include "signed_distance_detail.h"

namespace occlude::collision {
namespace {

constexpr int kMaxDilation = 16;
constexpr std::uint64_t kLaneX = 0x1249249249249249ULL;  // Morton bits of x
constexpr std::uint64_t kLanes[3] = {kLaneX, kLaneX << 1, kLaneX << 2};

/// Morton code of a + b for codes of non-negative coordinates.
std::uint64_t MortonAdd(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r = 0;
  for (const std::uint64_t lane : kLanes) r |= ((a | ~lane) + (b & lane)) & lane;
  return r;
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

void CheckInputs(const std::shared_ptr<const io::TriangleMesh>& mesh, const VoxelGrid& grid,
                 const NarrowBandOptions& options) {
  if (!mesh) throw std::invalid_argument("NarrowBandSdf::Build: null mesh");
  if (!(grid.voxel_size_mm > 0.0) || !std::isfinite(grid.voxel_size_mm)) {
    throw std::invalid_argument("NarrowBandSdf::Build: grid voxel size must be > 0 mm");
  }
  if (options.dilation_voxels < 0 || options.dilation_voxels > kMaxDilation) {
    throw std::invalid_argument("NarrowBandSdf::Build: dilation_voxels must be in [0, " +
                                std::to_string(kMaxDilation) + "]");
  }
  if (grid.triangle_offsets.size() != grid.surface_keys.size() + 1 ||
      grid.triangle_offsets.back() != grid.triangle_indices.size()) {
    throw std::invalid_argument("NarrowBandSdf::Build: inconsistent grid CSR arrays");
  }
  for (const std::uint32_t t : grid.triangle_indices) {
    if (t >= mesh->num_triangles()) {
      throw std::invalid_argument("NarrowBandSdf::Build: grid lists triangle " + std::to_string(t) +
                                  " but the mesh has " + std::to_string(mesh->num_triangles()) +
                                  " (grid of another mesh?)");
    }
  }
  const long long span =
      static_cast<long long>(grid.dims.maxCoeff()) + 2LL * options.dilation_voxels + 3;
  if (span > kMortonMaxCoord) {
    throw std::invalid_argument("NarrowBandSdf::Build: grid too large for 21-bit Morton keys");
  }
}

}  // namespace

NarrowBandSdf NarrowBandSdf::Build(std::shared_ptr<const io::TriangleMesh> mesh,
                                   const VoxelGrid& grid, const NarrowBandOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  CheckInputs(mesh, grid, options);
  NarrowBandSdf sdf;
  sdf.mesh_ = std::move(mesh);
  sdf.normals_ = PseudoNormals(*sdf.mesh_);
  sdf.shift_ = options.dilation_voxels + 1;
  sdf.band_mm_ = options.dilation_voxels * grid.voxel_size_mm;
  sdf.CopyGrid(grid);
  sdf.PackTriangles();
  if (options.corner_values) {
    sdf.FillBlocks(sdf.BandVoxels(grid, options.dilation_voxels),
                   detail::ResolveThreads(options.threads));
  }
  sdf.build_seconds_ = Seconds(start);
  return sdf;
}

void NarrowBandSdf::CopyGrid(const VoxelGrid& grid) {
  s_ = grid.voxel_size_mm;
  inv_s_ = 1.0 / s_;
  origin_ = grid.origin_F;
  dims_ = grid.dims;
  tri_offsets_ = grid.triangle_offsets;
  tri_indices_ = grid.triangle_indices;
  surface_ = detail::BrickSet();
  for (const std::uint64_t k : grid.surface_keys) surface_.Add(k);
  surface_.Finish();  // ranks = positions in the sorted surface_keys = CSR rows
}

void NarrowBandSdf::PackTriangles() {
  const io::TriangleMesh& m = *mesh_;
  const std::size_t nt = m.num_triangles();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const Eigen::Vector3d c = (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0;
    const Eigen::Vector3d q = ((c - origin_) * inv_s_).cwiseMax(0.0).cwiseMin(kMortonMaxCoord);
    order[t] = {MortonEncode(q.cast<int>()), static_cast<std::uint32_t>(t)};
  }
  std::sort(order.begin(), order.end());
  std::vector<std::uint32_t> internal(nt);
  original_.resize(nt);
  packed_.resize(nt);
  for (std::size_t i = 0; i < nt; ++i) {
    const std::uint32_t t = order[i].second;
    original_[i] = t;
    internal[t] = static_cast<std::uint32_t>(i);
    PackedTriangle& pt = packed_[i];
    pt.a = m.corner(t, 0);
    pt.b = m.corner(t, 1);
    pt.c = m.corner(t, 2);
    pt.center = (pt.a + pt.b + pt.c) / 3.0;
    const double r2 = std::max({(pt.a - pt.center).squaredNorm(), (pt.b - pt.center).squaredNorm(),
                                (pt.c - pt.center).squaredNorm()});
    pt.radius = std::sqrt(r2) * (1.0 + 1e-12);
  }
  for (std::uint32_t& t : tri_indices_) t = internal[t];
}

detail::BrickSet NarrowBandSdf::BandVoxels(const VoxelGrid& grid, int dilation) const {
  const std::uint64_t shift = MortonEncode(shift_, shift_, shift_);
  detail::BrickSet band;
  for (const std::uint64_t k : grid.surface_keys) band.Add(MortonAdd(k, shift));
  // Separable dilation by [-d, d] along x, then y, then z (a cube of side 2d + 1).
  for (int axis = 0; axis < 3; ++axis) {
    for (int i = 0; i < dilation; ++i) band.Dilate(axis, true, true);
  }
  band.Finish();
  return band;
}

void NarrowBandSdf::FillBlocks(const detail::BrickSet& band, int threads) {
  // Corner (i, j, k) of a voxel is stored under the key of voxel (i, j, k):
  // the corner set is the band grown by one voxel upward along each axis.
  detail::BrickSet corners = band;
  for (int axis = 0; axis < 3; ++axis) corners.Dilate(axis, true, false);
  corners.Finish();
  const std::vector<float> value = CornerValues(corners, threads);
  corner_bricks_.assign(band.bricks().size(), CornerBrick{});
  constexpr std::size_t kBricksPerBlock = 256;
  const std::size_t bricks = band.bricks().size();
  detail::ParallelFor((bricks + kBricksPerBlock - 1) / kBricksPerBlock, threads,
                      [&](std::size_t block, int) {
                        const std::size_t end = std::min(bricks, (block + 1) * kBricksPerBlock);
                        for (std::size_t i = block * kBricksPerBlock; i < end; ++i)
                          FillCornerBrick(band.bricks()[i], corners, value, &corner_bricks_[i]);
                      });
  band_ = band;
}

void NarrowBandSdf::FillCornerBrick(const detail::BrickSet::Brick& brick,
                                    const detail::BrickSet& corners,
                                    const std::vector<float>& value, CornerBrick* out) {
  const Eigen::Vector3i base = 4 * MortonDecode(brick.key);
  out->mask = brick.mask;
  for (int z = 0; z < 5; ++z) {
    for (int y = 0; y < 5; ++y) {
      for (int x = 0; x < 5; ++x) {
        const std::uint32_t r = corners.Rank(MortonEncode(base + Eigen::Vector3i(x, y, z)));
        out->value[x + 5 * y + 25 * z] = r == detail::KeyIndexHash::kNotFound ? 0.0f : value[r];
      }
    }
  }
}

void NarrowBandSdf::TestTriangle(std::uint32_t t, const Eigen::Vector3d& p, Nearest* best,
                                 bool* found) const {
  if (best->seen != nullptr) {  // a triangle is listed by every voxel it touches
    std::uint32_t& mark = (*best->seen)[t];
    if (mark == best->epoch) return;
    mark = best->epoch;
  }
  const PackedTriangle& pt = packed_[t];
  const double r = pt.radius + best->distance;
  if ((p - pt.center).squaredNorm() > r * r) return;
  const TrianglePoint tp = ClosestPointOnTriangle(p, pt.a, pt.b, pt.c);
  if (tp.squared_distance < best->squared_distance ||
      (!*found && tp.squared_distance <= best->squared_distance)) {
    best->triangle = t;
    best->squared_distance = tp.squared_distance;
    best->distance = std::sqrt(tp.squared_distance);
    best->closest = tp.point;
    best->barycentric = tp.barycentric;
    *found = true;
  }
}

void NarrowBandSdf::ScanBrick(const Eigen::Vector3d& q, const Eigen::Vector3i& brick,
                              const detail::BrickSet::Brick& b, const Eigen::Vector3d& p,
                              Nearest* best, bool* found) const {
  const double inv_s2 = inv_s_ * inv_s_;
  // Keep only the voxels of the brick inside the cube of half-side best->distance around p.
  const double reach = best->distance * inv_s_;
  std::uint64_t candidates = b.mask;
  for (int a = 0; a < 3; ++a) {
    const double lo = std::max(std::floor(q[a] - reach) - 4.0 * brick[a], 0.0);
    const double hi = std::min(std::floor(q[a] + reach) - 4.0 * brick[a], 3.0);
    if (!(lo <= hi)) return;
    candidates &= detail::LayersMask(a, static_cast<int>(lo), static_cast<int>(hi));
  }
  for (std::uint64_t m = candidates; m != 0; m &= m - 1) {
    const int bit = __builtin_ctzll(m);
    const Eigen::Vector3i v = 4 * brick + detail::BrickLocal(bit);
    if (detail::BoxDistance2(q, v, v) > best->squared_distance * inv_s2) continue;
    const std::uint64_t below = (std::uint64_t{1} << bit) - 1;
    const std::size_t idx = b.first + detail::BrickSet::PopCount(b.mask & below);
    for (std::uint32_t i = tri_offsets_[idx]; i < tri_offsets_[idx + 1]; ++i) {
      TestTriangle(tri_indices_[i], p, best, found);
    }
  }
}

bool NarrowBandSdf::FindNearest(const Eigen::Vector3d& p, double bound2, std::uint32_t hint,
                                Nearest* best) const {
  bool found = false;
  best->squared_distance = bound2;
  best->distance = std::sqrt(bound2);
  if (hint != kNoHint) TestTriangle(hint, p, best, &found);
  if (surface_.bricks().empty()) return found;
  const Eigen::Vector3d q = (p - origin_) * inv_s_;
  const double reach = std::sqrt(best->squared_distance) * inv_s_;
  Eigen::Vector3i blo;
  Eigen::Vector3i bhi;
  for (int a = 0; a < 3; ++a) {
    const double lo = std::max(std::floor(q[a] - reach), 0.0);
    const double hi = std::min(std::floor(q[a] + reach), dims_[a] - 1.0);
    if (!(lo <= hi)) return found;  // also rejects NaN
    blo[a] = static_cast<int>(lo) >> 2;
    bhi[a] = static_cast<int>(hi) >> 2;
  }
  // Bricks nearest first (by box distance), so that the bound shrinks early.
  constexpr int kMaxSorted = 64;
  std::array<std::pair<double, Eigen::Vector3i>, kMaxSorted> order;
  const Eigen::Vector3i n = bhi - blo + Eigen::Vector3i::Ones();
  const bool sorted = n.prod() <= kMaxSorted;
  int count = 0;
  const double inv_s2 = inv_s_ * inv_s_;
  for (int z = blo.z(); z <= bhi.z(); ++z) {
    for (int y = blo.y(); y <= bhi.y(); ++y) {
      for (int x = blo.x(); x <= bhi.x(); ++x) {
        const Eigen::Vector3i brick(x, y, z);
        const double d2 =
            detail::BoxDistance2(q, 4 * brick, 4 * brick + Eigen::Vector3i::Constant(3));
        if (sorted) {
          order[static_cast<std::size_t>(count++)] = {d2, brick};
          continue;
        }
        if (d2 > best->squared_distance * inv_s2) continue;
        const auto* b =
            surface_.FindAt(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                            static_cast<std::uint32_t>(z));
        if (b != nullptr) ScanBrick(q, brick, *b, p, best, &found);
      }
    }
  }
  if (!sorted) return found;
  for (int i = 1; i < count; ++i) {  // stable insertion sort: few bricks
    const auto item = order[static_cast<std::size_t>(i)];
    int j = i;
    for (; j > 0 && order[static_cast<std::size_t>(j - 1)].first > item.first; --j) {
      order[static_cast<std::size_t>(j)] = order[static_cast<std::size_t>(j - 1)];
    }
    order[static_cast<std::size_t>(j)] = item;
  }
  for (int i = 0; i < count; ++i) {
    const auto& [d2, brick] = order[static_cast<std::size_t>(i)];
    if (d2 > best->squared_distance * inv_s2) break;
    const auto* b = surface_.FindAt(static_cast<std::uint32_t>(brick.x()),
                                    static_cast<std::uint32_t>(brick.y()),
                                    static_cast<std::uint32_t>(brick.z()));
    if (b != nullptr) ScanBrick(q, brick, *b, p, best, &found);
  }
  return found;
}

SignedDistanceSample NarrowBandSdf::Sign(const Eigen::Vector3d& p, const Nearest& n) const {
  SignedDistanceSample out;
  const std::uint32_t t = original_[n.triangle];
  out.distance = normals_.Signed(t, n.barycentric, p, n.closest, &out.normal);
  out.closest = n.closest;
  out.triangle = t;
  return out;
}

bool NarrowBandSdf::Exact(const Eigen::Vector3d& p_F, double max_distance,
                          SignedDistanceSample* out) const {
  if (!mesh_ || !(max_distance >= 0.0)) return false;
  Nearest n;
  if (!FindNearest(p_F, max_distance * max_distance, kNoHint, &n)) return false;
  *out = Sign(p_F, n);
  return true;
}

namespace {
/// Offset of corner o = x + 2y + 4z from corner 0 in a 5x5x5 corner brick.
constexpr int kCornerStep[8] = {0, 1, 5, 6, 25, 26, 30, 31};
}  // namespace

const float* NarrowBandSdf::Locate(const Eigen::Vector3d& p, Eigen::Vector3f* local) const {
  if (corner_bricks_.empty()) return nullptr;
  const Eigen::Vector3d q = (p - origin_) * inv_s_;
  // floor(q) in [lo, hi] (integers) is q in [lo, hi + 1); also false for NaN.
  const double lo = -shift_;
  const double hi = kMortonMaxCoord - shift_;
  for (int a = 0; a < 3; ++a) {
    if (!(q[a] >= lo && q[a] < hi + 1.0)) return nullptr;
  }
  const Eigen::Vector3i floor_q(detail::FloorInt(q.x()), detail::FloorInt(q.y()),
                                detail::FloorInt(q.z()));
  const Eigen::Vector3d g = floor_q.cast<double>();
  const Eigen::Vector3i ijk = floor_q + Eigen::Vector3i::Constant(shift_);
  const CornerBrick* brick =
      BrickAt(static_cast<std::uint32_t>(ijk.x()) >> 2, static_cast<std::uint32_t>(ijk.y()) >> 2,
              static_cast<std::uint32_t>(ijk.z()) >> 2);
  if (brick == nullptr) return nullptr;
  const CornerBrick& b = *brick;
  const Eigen::Vector3i l(ijk.x() & 3, ijk.y() & 3, ijk.z() & 3);
  const int bit = (l.x() & 1) | (l.y() & 1) << 1 | (l.z() & 1) << 2 | (l.x() >> 1) << 3 |
                  (l.y() >> 1) << 4 | (l.z() >> 1) << 5;
  if (((b.mask >> bit) & 1) == 0) return nullptr;
  *local = (q - g).cast<float>();
  return b.value + l.x() + 5 * l.y() + 25 * l.z();
}

bool NarrowBandSdf::Interpolate(const Eigen::Vector3d& p_F, double* distance,
                                Eigen::Vector3d* gradient) const {
  Eigen::Vector3f f;
  const float* v = Locate(p_F, &f);
  if (v == nullptr) return false;
  float c[8];
  for (int o = 0; o < 8; ++o) c[o] = v[kCornerStep[o]];
  const float x = f.x(), y = f.y(), z = f.z();
  // Along x on the four x-edges (y, z) = (0,0), (1,0), (0,1), (1,1).
  const float e0 = c[1] - c[0], e1 = c[3] - c[2], e2 = c[5] - c[4], e3 = c[7] - c[6];
  const float a0 = c[0] + x * e0, a1 = c[2] + x * e1, a2 = c[4] + x * e2, a3 = c[6] + x * e3;
  const float b0 = a0 + y * (a1 - a0), b1 = a2 + y * (a3 - a2);
  *distance = static_cast<double>(b0 + z * (b1 - b0));
  if (gradient != nullptr) {
    const float ddx = (1 - z) * ((1 - y) * e0 + y * e1) + z * ((1 - y) * e2 + y * e3);
    const float ddy = (1 - z) * (a1 - a0) + z * (a3 - a2);
    const float ddz = b1 - b0;
    *gradient = Eigen::Vector3d(static_cast<double>(ddx), static_cast<double>(ddy),
                                static_cast<double>(ddz)) *
                inv_s_;
  }
  return true;
}

VoxelGrid NarrowBandSdf::BandVoxelsWithin(float depth, float value, int threads) const {
  return BandCellsWithin(depth, value, 1, threads);
}

VoxelGrid NarrowBandSdf::BandCellsWithin(float depth, float value, int split, int threads) const {
  if (split < 1 || split > 8) throw std::invalid_argument("BandCellsWithin: split must be in 1..8");
  threads = detail::ResolveThreads(threads);
  VoxelGrid out;
  out.voxel_size_mm = s_ / split;
  out.origin_F = origin_ - static_cast<double>(shift_) * s_ * Eigen::Vector3d::Ones();
  out.dims = split * (dims_ + Eigen::Vector3i::Constant(2 * shift_));
  // Blocks of band bricks, their keys concatenated in block order: the same list for any
  // thread count (in Morton order for split 1 and 2, sorted below otherwise).
  constexpr std::size_t kBricksPerBlock = 256;
  const std::size_t bricks = band_.bricks().size();
  std::vector<std::vector<std::uint64_t>> keys((bricks + kBricksPerBlock - 1) / kBricksPerBlock);
  detail::ParallelFor(keys.size(), threads, [&](std::size_t block, int) {
    const std::size_t end = std::min(bricks, (block + 1) * kBricksPerBlock);
    for (std::size_t i = block * kBricksPerBlock; i < end; ++i) {
      for (std::uint64_t m = band_.bricks()[i].mask; m != 0; m &= m - 1)
        BandVoxelCells(i, __builtin_ctzll(m), depth, value, split, &keys[block]);
    }
  });
  std::size_t total = 0;
  for (const auto& k : keys) total += k.size();
  out.surface_keys.reserve(total);
  for (auto& k : keys) {
    out.surface_keys.insert(out.surface_keys.end(), k.begin(), k.end());
    std::vector<std::uint64_t>().swap(k);
  }
  if (!std::is_sorted(out.surface_keys.begin(), out.surface_keys.end()))
    std::sort(out.surface_keys.begin(), out.surface_keys.end());
  return out;
}

void NarrowBandSdf::BandVoxelCells(std::size_t brick, int bit, float depth, float value, int split,
                                   std::vector<std::uint64_t>* keys) const {
  // The bit is the voxel's 2x2x2-interleaved position in the brick (as Locate).
  const Eigen::Vector3i l((bit & 1) | ((bit >> 3) & 1) << 1,
                          ((bit >> 1) & 1) | ((bit >> 4) & 1) << 1,
                          ((bit >> 2) & 1) | ((bit >> 5) & 1) << 1);
  // The voxel's index in the result's voxels (shifted).
  const Eigen::Vector3i g = 4 * MortonDecode(band_.bricks()[brick].key) + l;
  const float* v = corner_bricks_[brick].value + l.x() + 5 * l.y() + 25 * l.z();
  std::array<float, 8> c{};
  for (int o = 0; o < 8; ++o) c[static_cast<std::size_t>(o)] = v[kCornerStep[o]];
  // A trilinear value lies between its voxel's smallest and largest corner.
  const bool in_range = *std::min_element(c.begin(), c.end()) <= value &&
                        *std::max_element(c.begin(), c.end()) >= -depth;
  // Surface voxels are kept whole (so that no cell found still means that
  // no upper voxel comes near the lower surface).
  const Eigen::Vector3i v_F = g - Eigen::Vector3i::Constant(shift_);
  const bool surface = (split > 1 || !in_range) && (v_F.array() >= 0).all() &&
                       surface_.Rank(MortonEncode(v_F)) != detail::KeyIndexHash::kNotFound;
  if (!in_range && !surface) return;
  if (surface || split == 1) {
    for (int o = 0; o < split * split * split; ++o) {
      keys->push_back(MortonEncode(
          split * g + Eigen::Vector3i(o % split, o / split % split, o / (split * split))));
    }
    return;
  }
  // The field on the cells' corners, then the cells whose corner range meets [-depth, value].
  const int n = split + 1;
  std::array<float, 9 * 9 * 9> at{};
  for (int z = 0; z < n; ++z) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const float fx = static_cast<float>(x) / static_cast<float>(split);
        const float fy = static_cast<float>(y) / static_cast<float>(split);
        const float fz = static_cast<float>(z) / static_cast<float>(split);
        const float a0 = c[0] + fx * (c[1] - c[0]), a1 = c[2] + fx * (c[3] - c[2]);
        const float a2 = c[4] + fx * (c[5] - c[4]), a3 = c[6] + fx * (c[7] - c[6]);
        const float b0 = a0 + fy * (a1 - a0), b1 = a2 + fy * (a3 - a2);
        at[static_cast<std::size_t>(x + n * (y + n * z))] = b0 + fz * (b1 - b0);
      }
    }
  }
  for (int z = 0; z < split; ++z) {
    for (int y = 0; y < split; ++y) {
      for (int x = 0; x < split; ++x) {
        float lowest = std::numeric_limits<float>::infinity(), highest = -lowest;
        for (int o = 0; o < 8; ++o) {
          const float f = at[static_cast<std::size_t>(
              (x + (o & 1)) + n * ((y + (o >> 1 & 1)) + n * (z + (o >> 2))))];
          lowest = std::min(lowest, f);
          highest = std::max(highest, f);
        }
        if (lowest <= value && highest >= -depth)
          keys->push_back(MortonEncode(split * g + Eigen::Vector3i(x, y, z)));
      }
    }
  }
}

bool NarrowBandSdf::CellValue(const Eigen::Vector3d& p_F, double* distance) const {
  Eigen::Vector3f f;
  const float* v = Locate(p_F, &f);
  if (v == nullptr) return false;
  double sum = 0.0;
  for (const int step : kCornerStep) sum += static_cast<double>(v[step]);
  *distance = sum / 8.0;
  return true;
}

std::size_t NarrowBandSdf::MemoryBytes() const {
  return normals_.MemoryBytes() + packed_.capacity() * sizeof(PackedTriangle) +
         original_.capacity() * sizeof(std::uint32_t) +
         (tri_offsets_.capacity() + tri_indices_.capacity()) * sizeof(std::uint32_t) +
         surface_.MemoryBytes() + band_.MemoryBytes() +
         corner_bricks_.capacity() * sizeof(CornerBrick);
}

}  // namespace occlude::collision
