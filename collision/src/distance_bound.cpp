// DistanceBound: the capped, exact cell-centre distances to the surface voxels
// by three separable 1-D minimum passes over sparse 8x8x8 bricks of bytes, each
// pass a gather per destination brick (rows of 64 cells, saturating byte adds and
// minima), the bricks in fixed blocks on the build's threads.
#include "occlude/collision/distance_bound.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "occlude/collision/morton.h"
#include "parallel.h"

namespace occlude::collision {
namespace {

constexpr int kBrickBits = detail::kBoundBrickBits;
constexpr int kBrickEdge = detail::kBoundBrickEdge;

std::uint64_t BrickKey(const Eigen::Vector3i& b) { return detail::BoundBrickKey(b); }
int CellIndex(int x, int y, int z) { return detail::BoundCellIndex(x, y, z); }
int FloorInt(double x) { return detail::FloorInt(x); }

using Brick = std::array<std::uint8_t, 512>;  // cell x + 8 y + 64 z

// Bricks under construction: a hash from brick key to index, every new brick
// filled with the cap. Indices stay valid as bricks are added (pointers do not).
struct BrickMap {
  detail::KeyIndexHash index;
  std::vector<Brick> bricks;
  std::vector<Eigen::Vector3i> coords;
  std::uint8_t cap = 0;

  std::uint32_t At(const Eigen::Vector3i& b) {
    bool inserted = false;
    const std::uint32_t i =
        index.Insert(BrickKey(b), static_cast<std::uint32_t>(bricks.size()), &inserted);
    if (inserted) {
      bricks.emplace_back();
      bricks.back().fill(cap);
      coords.push_back(b);
    }
    return i;
  }
  const Brick* Find(const Eigen::Vector3i& b) const {
    const std::uint32_t i = index.Find(BrickKey(b));
    return i == detail::KeyIndexHash::kNotFound ? nullptr : &bricks[i];
  }
};

// Index of cell (along, rest) of a brick, `along` the coordinate on `axis` and `rest` = u + 8 w
// for the other two in increasing axis order: the layout a pass reads rows of.
constexpr int PassCell(int axis, int along, int rest) {
  const int u = rest & 7, w = rest >> 3;
  constexpr int kY = kBrickBits, kZ = 2 * kBrickBits;  // as detail::BoundCellIndex
  if (axis == 0) return along | u << kY | w << kZ;
  if (axis == 1) return u | along << kY | w << kZ;
  return u | w << kY | along << kZ;
}
// PassCell(axis, i >> 6, i & 63) for every row index i = 64 along + rest, per axis.
constexpr std::array<std::array<std::uint16_t, 512>, 3> kPassCells = [] {
  std::array<std::array<std::uint16_t, 512>, 3> t{};
  for (int axis = 0; axis < 3; ++axis) {
    for (int i = 0; i < 512; ++i) {
      t[static_cast<std::size_t>(axis)][static_cast<std::size_t>(i)] =
          static_cast<std::uint16_t>(PassCell(axis, i >> 6, i & 63));
    }
  }
  return t;
}();

// Three bricks along `axis` (below, the brick, above; null = all at the cap) as 24 rows of 64
// cells, row = the coordinate along the axis + 8.
void GatherRows(const std::array<const Brick*, 3>& bricks, int axis, std::uint8_t cap,
                std::uint8_t* rows) {
  const auto& cell = kPassCells[static_cast<std::size_t>(axis)];
  for (int k = 0; k < 3; ++k) {
    std::uint8_t* out = rows + 512 * k;
    const Brick* b = bricks[static_cast<std::size_t>(k)];
    if (b == nullptr) {
      std::fill(out, out + 512, cap);
    } else if (axis == 2) {
      std::copy(b->begin(), b->end(), out);
    } else {
      for (std::size_t i = 0; i < 512; ++i) out[i] = (*b)[cell[i]];
    }
  }
}

// out[i] = min(out[i], row[i] + add) over 64 cells, saturating at 255 (above every cap).
void MinRow(const std::uint8_t* row, std::uint8_t add, std::uint8_t* out) {
#if defined(__SSE2__)
  const __m128i a = _mm_set1_epi8(static_cast<char>(add));
  for (int i = 0; i < 64; i += 16) {
    const __m128i v = _mm_adds_epu8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i)), a);
    auto* o = reinterpret_cast<__m128i*>(out + i);
    _mm_storeu_si128(o, _mm_min_epu8(_mm_loadu_si128(o), v));
  }
#else
  for (int i = 0; i < 64; ++i) {
    out[i] = static_cast<std::uint8_t>(std::min(255, std::min<int>(out[i], row[i] + add)));
  }
#endif
}

// One brick of a pass: dst(c) = min(cap, min over |d| <= K of src(c - d e_axis) + t(d)) from
// the source bricks below, at and above it. False when every cell stays at the cap.
bool PassBrick(const std::array<const Brick*, 3>& src, int axis, const std::vector<int>& t,
               std::uint8_t cap, Brick* dst) {
  std::array<std::uint8_t, 3 * 512> rows{};
  GatherRows(src, axis, cap, rows.data());
  std::array<std::uint8_t, 512> out{};
  out.fill(cap);
  const int reach = static_cast<int>(t.size()) - 1;  // K < 8: the neighbours suffice
  for (int along = 0; along < kBrickEdge; ++along) {
    for (int d = -reach; d <= reach; ++d) {
      MinRow(rows.data() + 64 * (kBrickEdge + along + d),
             static_cast<std::uint8_t>(std::min(255, t[static_cast<std::size_t>(std::abs(d))])),
             out.data() + 64 * along);
    }
  }
  const auto& cell = kPassCells[static_cast<std::size_t>(axis)];
  std::uint8_t lowest = cap;
  for (std::size_t i = 0; i < 512; ++i) {
    lowest = std::min(lowest, out[i]);
    (*dst)[cell[i]] = out[i];
  }
  return lowest < cap;
}

// The bricks a pass along `axis` may fill: every source brick and its two neighbours along
// the axis, each once, in a fixed order (so that the result does not depend on threads).
std::vector<Eigen::Vector3i> PassCandidates(const BrickMap& src, int axis) {
  detail::KeyIndexHash seen;
  seen.Reset(3 * src.coords.size());
  std::vector<Eigen::Vector3i> out;
  out.reserve(3 * src.coords.size());
  for (const Eigen::Vector3i& b : src.coords) {
    for (int k = -1; k <= 1; ++k) {
      Eigen::Vector3i c = b;
      c[axis] += k;
      bool inserted = false;
      seen.Insert(BrickKey(c), 0, &inserted);
      if (inserted) out.push_back(c);
    }
  }
  return out;
}

// One separable pass along `axis` (a gather per destination brick, in blocks on `threads`):
// dst(c) = min over |d| <= K of src(c - d e_axis) + t(d), t(d) = (2|d| - 1)^2 (t(0) = 0),
// capped; bricks left all at the cap are dropped.
BrickMap Pass(const BrickMap& src, int axis, const std::vector<int>& t, int threads) {
  const std::vector<Eigen::Vector3i> candidates = PassCandidates(src, axis);
  constexpr std::size_t kBlock = 256;  // bricks per work item
  const std::size_t blocks = (candidates.size() + kBlock - 1) / kBlock;
  std::vector<std::vector<Brick>> kept(blocks);  // per block: the bricks below the cap
  std::vector<std::vector<std::uint32_t>> which(blocks);
  detail::ParallelFor(blocks, threads, [&](std::size_t block, int) {
    const std::size_t end = std::min(candidates.size(), (block + 1) * kBlock);
    Brick brick;
    for (std::size_t i = block * kBlock; i < end; ++i) {
      std::array<const Brick*, 3> near{};
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3i b = candidates[i];
        b[axis] += k - 1;
        near[static_cast<std::size_t>(k)] = src.Find(b);
      }
      if (!PassBrick(near, axis, t, src.cap, &brick)) continue;
      kept[block].push_back(brick);
      which[block].push_back(static_cast<std::uint32_t>(i));
    }
  });
  BrickMap dst;
  dst.cap = src.cap;
  std::size_t total = 0;
  for (const auto& k : kept) total += k.size();
  dst.index.Reset(total);
  dst.bricks.reserve(total);
  dst.coords.reserve(total);
  for (std::size_t block = 0; block < blocks; ++block) {
    for (std::size_t j = 0; j < kept[block].size(); ++j) {
      const Eigen::Vector3i& c = candidates[which[block][j]];
      bool inserted = false;
      dst.index.Insert(BrickKey(c), static_cast<std::uint32_t>(dst.bricks.size()), &inserted);
      dst.bricks.push_back(kept[block][j]);
      dst.coords.push_back(c);
    }
    std::vector<Brick>().swap(kept[block]);
  }
  return dst;
}

// The level's occupied cells (value 0) in bricks filled with the cap: the cells of the
// surface voxels' keys >> 3 level (sorted keys: consecutive ones mostly share a brick).
BrickMap OccupiedCells(const VoxelGrid& grid, int level, std::uint8_t cap) {
  BrickMap occupied;
  occupied.cap = cap;
  occupied.index.Reset((grid.surface_keys.size() >> (2 * level)) / 16 + 16);
  const int m = kBrickEdge - 1;
  Eigen::Vector3i last_brick(-1, -1, -1);
  std::uint32_t last = 0;
  std::uint64_t last_cell = ~std::uint64_t{0};
  for (const std::uint64_t key : grid.surface_keys) {
    const std::uint64_t cell = key >> (3 * level);  // the level's cell
    if (cell == last_cell) continue;                // sorted keys: its cell is already set
    last_cell = cell;
    const Eigen::Vector3i v(MortonDecode(cell));
    const Eigen::Vector3i b(v.x() >> kBrickBits, v.y() >> kBrickBits, v.z() >> kBrickBits);
    if (b != last_brick || occupied.bricks.empty()) {
      last = occupied.At(b);
      last_brick = b;
    }
    occupied.bricks[last][static_cast<std::size_t>(CellIndex(v.x() & m, v.y() & m, v.z() & m))] = 0;
  }
  return occupied;
}

}  // namespace

DistanceBound DistanceBound::Build(const VoxelGrid& grid, int max_voxels,
                                   const std::vector<int>& levels, int threads) {
  return Build(grid, max_voxels, levels, threads, nullptr);
}

DistanceBound DistanceBound::Build(VoxelGrid&& grid, int max_voxels, const std::vector<int>& levels,
                                   int threads) {
  return Build(grid, max_voxels, levels, threads, &grid);
}

DistanceBound DistanceBound::Build(const VoxelGrid& grid, int max_voxels,
                                   const std::vector<int>& levels, int threads,
                                   VoxelGrid* release) {
  if (max_voxels < 1 || max_voxels > kMaxVoxels) {
    throw std::invalid_argument("DistanceBound::Build: max_voxels must be in [1, " +
                                std::to_string(kMaxVoxels) + "]");
  }
  for (std::size_t i = 0; i < levels.size(); ++i) {
    if (levels[i] < 0 || levels[i] > 20 || (i > 0 && levels[i] <= levels[i - 1])) {
      throw std::invalid_argument("DistanceBound::Build: levels must be increasing, in [0, 20]");
    }
  }
  const int workers = detail::ResolveThreads(threads);
  DistanceBound out;
  out.origin_ = grid.origin_F;
  const double voxel_mm = grid.voxel_size_mm;
  if (grid.surface_keys.empty() || !(voxel_mm > 0.0)) return out;
  // Every level's occupied cells first: then the keys (the largest input) can go before the
  // passes, the build's largest part.
  const auto cap = static_cast<std::uint8_t>((2 * max_voxels + 1) * (2 * max_voxels + 1));
  std::vector<BrickMap> occupied(levels.size());
  detail::ParallelFor(levels.size(), workers, [&](std::size_t l, int) {
    occupied[l] = OccupiedCells(grid, levels[l], cap);
  });
  if (release != nullptr) *release = VoxelGrid();
  std::vector<int> t;  // per-axis term for |d| = 0..max_voxels
  for (int d = 0; d <= max_voxels; ++d) t.push_back(d == 0 ? 0 : (2 * d - 1) * (2 * d - 1));
  for (std::size_t l = 0; l < levels.size(); ++l) {
    BrickMap field = std::move(occupied[l]);
    for (int axis = 0; axis < 3; ++axis) field = Pass(field, axis, t, workers);
    // Every brick left holds some value below the cap (the others read as the cap anyway).
    out.levels_.push_back(LevelOf(std::move(field.index), std::move(field.bricks), field.coords,
                                  voxel_mm, cap, levels[l]));
  }
  out.finest_level_ = levels.empty() ? 0 : levels[0];
  for (std::size_t l = 0; l < out.levels_.size(); ++l) {
    out.levels_[l].shift = levels[l] - levels[0];
    out.levels_[l].scale = std::ldexp(1.0, -out.levels_[l].shift);
  }
  return out;
}

DistanceBound::Level DistanceBound::LevelOf(detail::KeyIndexHash index, std::vector<Brick> bricks,
                                            const std::vector<Eigen::Vector3i>& coords,
                                            double voxel_mm, std::uint8_t cap, int level) {
  Level out;
  out.s = std::ldexp(voxel_mm, level);
  out.inv_s = 1.0 / out.s;
  out.s2 = out.s * out.s;
  out.cap = cap;
  // Rounded down so that the bound never exceeds the exact distance.
  for (int q = 0; q < 256; ++q) {
    out.m_mm[static_cast<std::size_t>(q)] =
        0.5 * std::sqrt(static_cast<double>(std::min(q, static_cast<int>(out.cap)))) * out.s *
        (1.0 - 1e-12);
  }
  out.cap_mm = out.m_mm[out.cap];
  out.index = std::move(index);
  out.bricks = std::move(bricks);
  out.bricks.shrink_to_fit();
  out.BuildTable(coords);
  return out;
}

void DistanceBound::Level::BuildTable(const std::vector<Eigen::Vector3i>& coords) {
  table.clear();
  if (coords.empty()) return;
  Eigen::Vector3i lo = coords[0], hi = coords[0];
  for (const auto& c : coords) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const Eigen::Vector3i dims = hi - lo + Eigen::Vector3i::Ones();
  const std::size_t cells = static_cast<std::size_t>(dims.x()) *
                            static_cast<std::size_t>(dims.y()) * static_cast<std::size_t>(dims.z());
  // 4 bytes per box cell against 512 per brick: affordable up to 32 cells per brick.
  constexpr std::size_t kMaxCellsPerBrick = 32;
  if (cells > kMaxCellsPerBrick * coords.size() + (std::size_t{1} << 16)) return;
  table_lo = lo;
  table_dims = dims;
  table.assign(cells, detail::KeyIndexHash::kNotFound);
  for (std::size_t i = 0; i < coords.size(); ++i) {
    const Eigen::Vector3i c = coords[i] - lo;
    table[static_cast<std::size_t>(c.x()) +
          static_cast<std::size_t>(dims.x()) *
              (static_cast<std::size_t>(c.y()) +
               static_cast<std::size_t>(dims.y()) * static_cast<std::size_t>(c.z()))] =
        static_cast<std::uint32_t>(i);
  }
}

bool DistanceBound::Level::CellQ(const Eigen::Vector3d& q, std::uint8_t* value,
                                 Eigen::Vector3d* offset) const {
  constexpr double kRange = 1 << 22;  // cell coordinates whose bricks have keys
  if (!(std::abs(q.x()) < kRange && std::abs(q.y()) < kRange && std::abs(q.z()) < kRange))
    return false;  // also NaN
  const int cx = FloorInt(q.x()), cy = FloorInt(q.y()), cz = FloorInt(q.z());
  *offset = Eigen::Vector3d(q.x() - cx - 0.5, q.y() - cy - 0.5, q.z() - cz - 0.5);
  const std::uint32_t i =
      BrickIndex(Eigen::Vector3i(cx >> kBrickBits, cy >> kBrickBits, cz >> kBrickBits));
  if (i == detail::KeyIndexHash::kNotFound) {
    *value = cap;
    return true;
  }
  const int m = kBrickEdge - 1;
  *value = bricks[i][static_cast<std::size_t>(CellIndex(cx & m, cy & m, cz & m))];
  return true;
}

double DistanceBound::LowerBound(const Eigen::Vector3d& p_F) const {
  if (levels_.empty()) return -std::numeric_limits<double>::infinity();
  return LowerBoundAt((p_F - origin_) * levels_[0].inv_s);
}

double DistanceBound::LowerBoundAt(const Eigen::Vector3d& q0) const {
  double best = -std::numeric_limits<double>::infinity();
  for (const Level& level : levels_) {
    std::uint8_t value = 0;
    Eigen::Vector3d offset;
    if (!level.CellQ(q0 * level.scale, &value, &offset)) return best;
    best = std::max(best, level.m_mm[value] - level.s * offset.norm() * (1.0 + 1e-12));
    if (value < level.cap) break;  // unsaturated: a coarser level is no tighter
  }
  return best;
}

bool DistanceBound::VoxelOccupied(int x, int y, int z) const {
  if (levels_.empty()) return false;
  const Level& level = levels_[0];
  const std::uint32_t i =
      level.BrickIndex(Eigen::Vector3i(x >> kBrickBits, y >> kBrickBits, z >> kBrickBits));
  constexpr int m = kBrickEdge - 1;
  return i != detail::KeyIndexHash::kNotFound &&
         level.bricks[i][static_cast<std::size_t>(CellIndex(x & m, y & m, z & m))] == 0;
}

bool DistanceBound::ExcludesAt(const Eigen::Vector3d& q0, double radius) const {
  return Probe3<false>(q0, radius).excluded;
}

bool DistanceBound::Excludes(const Eigen::Vector3d& p_F, double radius) const {
  return !levels_.empty() && ExcludesAt((p_F - origin_) * levels_[0].inv_s, radius);
}

std::size_t DistanceBound::num_bricks() const {
  std::size_t n = 0;
  for (const Level& level : levels_) n += level.bricks.size();
  return n;
}

std::size_t DistanceBound::MemoryBytes() const {
  std::size_t bytes = levels_.capacity() * sizeof(Level);
  for (const Level& level : levels_) {
    bytes += level.bricks.capacity() * sizeof(Brick) + level.index.MemoryBytes() +
             level.table.capacity() * sizeof(std::uint32_t);
  }
  return bytes;
}

}  // namespace occlude::collision
