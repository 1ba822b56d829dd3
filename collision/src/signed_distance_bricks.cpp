// Sparse voxel sets of the narrow band: the open-addressing key hash and the
// 4x4x4 brick sets (occupancy masks in Morton order, ranks by popcount, and
// dilation by one voxel with mask shifts).
#include <algorithm>
#include <utility>
#include <vector>

#include "occlude/collision/morton.h"
#include "occlude/collision/signed_distance.h"

namespace occlude::collision {
namespace detail {

void KeyIndexHash::Reset(std::size_t n) {
  std::size_t capacity = 16;
  while (capacity * 3 < n * 4) capacity *= 2;
  slots_.assign(capacity, Slot{});
  mask_ = capacity - 1;
  size_ = 0;
}

std::uint32_t KeyIndexHash::Insert(std::uint64_t key, std::uint32_t value, bool* inserted) {
  if ((size_ + 1) * 4 > slots_.size() * 3) {  // grow, keeping load <= 3/4
    std::vector<Slot> old = std::move(slots_);
    Reset(2 * (size_ + 1));
    for (const Slot& s : old) {
      if (s.key == kEmpty) continue;
      bool unused = false;
      Insert(s.key, s.value, &unused);
    }
  }
  for (std::size_t i = Mix(key) & mask_;; i = (i + 1) & mask_) {
    Slot& s = slots_[i];
    if (s.key == key) {
      *inserted = false;
      return s.value;
    }
    if (s.key == kEmpty) {
      s.key = key;
      s.value = value;
      ++size_;
      *inserted = true;
      return value;
    }
  }
}

namespace {

constexpr std::uint64_t kLaneX = 0x1249249249249249ULL;  // Morton bits of x

/// Bits of a brick mask whose local coordinate along `axis` equals `c` (0..3).
std::uint64_t LayerMask(int axis, int c) {
  std::uint64_t m = 0;
  for (int i = 0; i < 64; ++i) {
    const int local = ((i >> axis) & 1) | (((i >> (axis + 3)) & 1) << 1);
    if (local == c) m |= std::uint64_t{1} << i;
  }
  return m;
}

/// Brick key one brick up/down along `axis`.
std::uint64_t Step(std::uint64_t key, int axis, bool up) {
  const std::uint64_t lane = kLaneX << axis;
  const std::uint64_t moved = up ? ((key | ~lane) + 1) & lane : ((key & lane) - 1) & lane;
  return moved | (key & ~lane);
}

}  // namespace

BrickSet::Brick& BrickSet::At(std::uint64_t brick_key) {
  bool inserted = false;
  const std::uint32_t i =
      index_.Insert(brick_key, static_cast<std::uint32_t>(bricks_.size()), &inserted);
  if (inserted) bricks_.push_back({brick_key, 0, 0});
  return bricks_[i];
}

void BrickSet::Add(std::uint64_t key) { At(key >> 6).mask |= std::uint64_t{1} << (key & 63); }

void BrickSet::Dilate(int axis, bool up, bool down) {
  // Moving +1 along `axis` inside a brick: local 0->1 and 2->3 shift the bit by
  // 1 << axis, 1->2 by 7 << axis; 3 leaves for the next brick (as 0, -(9 << axis)).
  const int one = 1 << axis, seven = 7 << axis, nine = 9 << axis;
  const std::uint64_t l0 = LayerMask(axis, 0), l1 = LayerMask(axis, 1);
  const std::uint64_t l2 = LayerMask(axis, 2), l3 = LayerMask(axis, 3);
  std::vector<std::uint64_t> source(bricks_.size());
  for (std::size_t i = 0; i < bricks_.size(); ++i) source[i] = bricks_[i].mask;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const std::uint64_t m = source[i];
    const std::uint64_t key = bricks_[i].key;
    if (up) {
      bricks_[i].mask |= ((m & l0) << one) | ((m & l1) << seven) | ((m & l2) << one);
      if ((m & l3) != 0) At(Step(key, axis, true)).mask |= (m & l3) >> nine;
    }
    if (down) {
      bricks_[i].mask |= ((m & l1) >> one) | ((m & l2) >> seven) | ((m & l3) >> one);
      if ((m & l0) != 0) At(Step(key, axis, false)).mask |= (m & l0) << nine;
    }
  }
}

void BrickSet::Finish() {
  std::sort(bricks_.begin(), bricks_.end(),
            [](const Brick& a, const Brick& b) { return a.key < b.key; });
  index_.Reset(bricks_.size());
  voxels_ = 0;
  for (std::size_t i = 0; i < bricks_.size(); ++i) {
    bricks_[i].first = static_cast<std::uint32_t>(voxels_);
    voxels_ += PopCount(bricks_[i].mask);
    bool inserted = false;
    index_.Insert(bricks_[i].key, static_cast<std::uint32_t>(i), &inserted);
  }
  BuildDense();
}

void BrickSet::BuildDense() {
  dense_.clear();
  if (bricks_.empty()) return;
  Eigen::Vector3i lo = MortonDecode(bricks_[0].key), hi = lo;
  for (const Brick& b : bricks_) {
    const Eigen::Vector3i c = MortonDecode(b.key);
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const Eigen::Vector3i dims = hi - lo + Eigen::Vector3i::Ones();
  const std::size_t cells = static_cast<std::size_t>(dims.x()) *
                            static_cast<std::size_t>(dims.y()) * static_cast<std::size_t>(dims.z());
  // 4 bytes per box cell against >= 16 per brick record: affordable up to 32
  // cells per brick (the box of a jaw's band holds about 5 to 10), else the hash.
  constexpr std::size_t kMaxCellsPerBrick = 32;
  if (cells > kMaxCellsPerBrick * bricks_.size() + (std::size_t{1} << 16)) return;
  for (int a = 0; a < 3; ++a) {
    dense_lo_[a] = static_cast<std::uint32_t>(lo[a]);
    dense_dims_[a] = static_cast<std::uint32_t>(dims[a]);
  }
  dense_.assign(cells, KeyIndexHash::kNotFound);
  for (std::size_t i = 0; i < bricks_.size(); ++i) {
    const Eigen::Vector3i c = MortonDecode(bricks_[i].key) - lo;
    dense_[static_cast<std::size_t>(c.x()) +
           dense_dims_[0] * (static_cast<std::size_t>(c.y()) +
                             dense_dims_[1] * static_cast<std::size_t>(c.z()))] =
        static_cast<std::uint32_t>(i);
  }
}

}  // namespace detail
}  // namespace occlude::collision
