// DistanceBound: the capped, exact cell-centre distances to the surface voxels
// by three separable 1-D minimum passes over sparse 8x8x8 bricks of bytes.
#include "occlude/collision/distance_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "occlude/collision/morton.h"

namespace occlude::collision {
namespace {

constexpr int kBrickBits = detail::kBoundBrickBits;
constexpr int kBrickEdge = detail::kBoundBrickEdge;

std::uint64_t BrickKey(const Eigen::Vector3i& b) { return detail::BoundBrickKey(b); }
int CellIndex(int x, int y, int z) { return detail::BoundCellIndex(x, y, z); }
int FloorInt(double x) { return detail::FloorInt(x); }

// Bricks under construction: a hash from brick key to index, every new brick
// filled with the cap. Indices stay valid as bricks are added (pointers do not).
struct BrickMap {
  detail::KeyIndexHash index;
  std::vector<std::array<std::uint8_t, 512>> bricks;
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
};

// One separable pass along `axis`: dst(c) = min over |d| <= K of src(c - d e_axis) + t(d),
// t(d) = (2|d| - 1)^2 (t(0) = 0), capped.
BrickMap Pass(const BrickMap& src, int axis, const std::vector<int>& t) {
  BrickMap dst;
  dst.cap = src.cap;
  dst.index.Reset(2 * src.bricks.size());
  const int cap = src.cap;
  for (std::size_t bi = 0; bi < src.bricks.size(); ++bi) {
    const Eigen::Vector3i b = src.coords[bi];
    std::int64_t neighbour[3] = {-1, -1, -1};  // dst bricks at b + (k - 1) e_axis, made on demand
    for (int z = 0; z < kBrickEdge; ++z) {
      for (int y = 0; y < kBrickEdge; ++y) {
        for (int x = 0; x < kBrickEdge; ++x) {
          const int v = src.bricks[bi][static_cast<std::size_t>(CellIndex(x, y, z))];
          if (v >= cap) continue;
          int local[3] = {x, y, z};
          const int along = local[axis];
          for (int d = 0; d < static_cast<int>(t.size()); ++d) {
            const int w = v + t[static_cast<std::size_t>(d)];
            if (w >= cap) break;  // t grows with |d|
            for (const int sd : {d, -d}) {
              const int pos = along + sd;
              const int k = pos < 0 ? 0 : (pos >= kBrickEdge ? 2 : 1);
              if (neighbour[k] < 0) {
                Eigen::Vector3i nb = b;
                nb[axis] += k - 1;
                neighbour[k] = dst.At(nb);
              }
              local[axis] = pos - (k - 1) * kBrickEdge;
              std::uint8_t& out =
                  dst.bricks[static_cast<std::size_t>(neighbour[k])]
                            [static_cast<std::size_t>(CellIndex(local[0], local[1], local[2]))];
              if (w < out) out = static_cast<std::uint8_t>(w);
              if (d == 0) break;
            }
          }
        }
      }
    }
  }
  return dst;
}

}  // namespace

DistanceBound DistanceBound::Build(const VoxelGrid& grid, int max_voxels,
                                   const std::vector<int>& levels) {
  if (max_voxels < 1 || max_voxels > kMaxVoxels) {
    throw std::invalid_argument("DistanceBound::Build: max_voxels must be in [1, " +
                                std::to_string(kMaxVoxels) + "]");
  }
  for (std::size_t i = 0; i < levels.size(); ++i) {
    if (levels[i] < 0 || levels[i] > 20 || (i > 0 && levels[i] <= levels[i - 1])) {
      throw std::invalid_argument("DistanceBound::Build: levels must be increasing, in [0, 20]");
    }
  }
  DistanceBound out;
  out.origin_ = grid.origin_F;
  if (grid.surface_keys.empty() || !(grid.voxel_size_mm > 0.0)) return out;
  for (const int level : levels) out.levels_.push_back(BuildLevel(grid, max_voxels, level));
  out.finest_level_ = levels.empty() ? 0 : levels[0];
  for (std::size_t l = 0; l < out.levels_.size(); ++l) {
    out.levels_[l].shift = levels[l] - levels[0];
    out.levels_[l].scale = std::ldexp(1.0, -out.levels_[l].shift);
  }
  return out;
}

DistanceBound::Level DistanceBound::BuildLevel(const VoxelGrid& grid, int max_voxels, int level) {
  Level out;
  out.s = std::ldexp(grid.voxel_size_mm, level);
  out.inv_s = 1.0 / out.s;
  out.s2 = out.s * out.s;
  out.cap = static_cast<std::uint8_t>((2 * max_voxels + 1) * (2 * max_voxels + 1));
  // Rounded down so that the bound never exceeds the exact distance.
  for (int q = 0; q < 256; ++q) {
    out.m_mm[static_cast<std::size_t>(q)] =
        0.5 * std::sqrt(static_cast<double>(std::min(q, static_cast<int>(out.cap)))) * out.s *
        (1.0 - 1e-12);
  }
  out.cap_mm = out.m_mm[out.cap];

  std::vector<int> t;  // per-axis term for |d| = 0..max_voxels
  for (int d = 0; d <= max_voxels; ++d) t.push_back(d == 0 ? 0 : (2 * d - 1) * (2 * d - 1));
  BrickMap occupied;
  occupied.cap = out.cap;
  occupied.index.Reset((grid.surface_keys.size() >> (2 * level)) / 16 + 16);
  const int m = kBrickEdge - 1;
  for (const std::uint64_t key : grid.surface_keys) {
    const Eigen::Vector3i v(MortonDecode(key >> (3 * level)));  // the level's cell
    const std::uint32_t b =
        occupied.At(Eigen::Vector3i(v.x() >> kBrickBits, v.y() >> kBrickBits, v.z() >> kBrickBits));
    occupied.bricks[b][static_cast<std::size_t>(CellIndex(v.x() & m, v.y() & m, v.z() & m))] = 0;
  }
  BrickMap field = Pass(Pass(Pass(occupied, 0, t), 1, t), 2, t);
  // Keep the bricks holding some value below the cap (others read as the cap anyway).
  out.index.Reset(field.bricks.size());
  std::vector<Eigen::Vector3i> kept;
  for (std::size_t i = 0; i < field.bricks.size(); ++i) {
    bool useful = false;
    for (const std::uint8_t v : field.bricks[i]) useful = useful || v < out.cap;
    if (!useful) continue;
    bool inserted = false;
    out.index.Insert(BrickKey(field.coords[i]), static_cast<std::uint32_t>(out.bricks.size()),
                     &inserted);
    out.bricks.push_back(field.bricks[i]);
    kept.push_back(field.coords[i]);
  }
  out.bricks.shrink_to_fit();
  out.BuildTable(kept);
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
