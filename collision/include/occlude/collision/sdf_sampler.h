// Fast repeated lookups in a NarrowBandSdf for points that arrive in spatial
// order (the samples of one upper cell, one after the other): the sampler
// remembers the last 4x4x4 brick it found, so a lookup in the same brick costs
// no hash probe, and points are given in float voxel units relative to an
// integer base voxel, so a caller can transform small offsets in float without
// losing precision far from the origin.
//
// Same answers as NarrowBandSdf::Interpolate / CellValue (the same float corner
// values and the same trilinear formula) up to float rounding of the local
// coordinates (~1e-7 voxel). Not thread-safe: one sampler per thread or query;
// the field must outlive it.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "occlude/collision/morton.h"
#include "occlude/collision/signed_distance.h"

namespace occlude::collision {

class SdfSampler {
 public:
  explicit SdfSampler(const NarrowBandSdf& sdf)
      : sdf_(&sdf), inv_s_(static_cast<float>(sdf.inv_s_)) {}

  /// Local coordinates are kept at least this far above 0, so that floor is a
  /// plain truncation; offsets added to a GridPoint's local must stay within
  /// +-kBias voxels (a level-3 cell's radius is below 7).
  static constexpr int kBias = 8;

  /// A point as an integer voxel (of the field's key space: shifted, minus
  /// kBias) plus a local offset in voxel units, in [kBias, kBias + 1) from
  /// GridPointOf; lanes x, y, z (the fourth is 0). Opaque to callers except
  /// that local may be moved (4 lanes, so that the arithmetic is one SIMD
  /// register where the target has them).
  struct GridPoint {
    Eigen::Array4i base = Eigen::Array4i::Zero();
    Eigen::Array4f local = Eigen::Array4f::Zero();
  };
  /// p_F in the field's voxel units. Points beyond the key range (or NaN)
  /// get a base that no lookup finds.
  GridPoint GridPointOf(const Eigen::Vector3d& p_F) const {
    return GridPointAt((p_F - sdf_->origin_) * sdf_->inv_s_);
  }
  /// The same for q = (p_F - origin()) / voxel size, the field's voxel coordinates.
  GridPoint GridPointAt(const Eigen::Vector3d& q) const {
    // Below kBias + 1 in float: q just below the next voxel stays in this one.
    constexpr float kTop = static_cast<float>(kBias + 1) - 0x1p-20f;
    GridPoint g;
    constexpr double kFar = 1 << 22;  // beyond every key, still an int
    for (int a = 0; a < 3; ++a) {
      if (!(std::abs(q[a]) < kFar)) {  // also NaN
        g.base[a] = static_cast<int>(kFar);
        g.local[a] = static_cast<float>(kBias);
        continue;
      }
      int i = static_cast<int>(q[a]);  // floor without a libm call
      i -= q[a] < static_cast<double>(i) ? 1 : 0;
      const double f = static_cast<double>(i);
      g.base[a] = i + sdf_->shift_ - kBias;
      g.local[a] = std::min(static_cast<float>(q[a] - f + kBias), kTop);
    }
    return g;
  }

  /// The field's grid origin (frame F, mm) and inverse voxel size.
  const Eigen::Vector3d& origin() const { return sdf_->origin_; }
  double inv_voxel_size() const { return sdf_->inv_s_; }

  /// Corner values of the band voxel holding base + local, with the local
  /// coordinates in that voxel (*f); null outside the band. Precondition:
  /// every local coordinate in (0, 2^20).
  const float* Locate(const Eigen::Array4i& base, const Eigen::Array4f& local, Eigen::Array4f* f) {
#if defined(__SSE2__)
    // The same four lanes with SSE2 (every x86-64): Eigen's all() is scalar.
    const __m128 p = _mm_load_ps(local.data());
    const __m128i floor = _mm_cvttps_epi32(p);  // truncation: local > 0
    _mm_store_ps(f->data(), _mm_sub_ps(p, _mm_cvtepi32_ps(floor)));
    const __m128i key =
        _mm_add_epi32(_mm_load_si128(reinterpret_cast<const __m128i*>(base.data())), floor);
    const __m128i last = _mm_load_si128(reinterpret_cast<const __m128i*>(voxel_key_.data()));
    if (_mm_movemask_epi8(_mm_cmpeq_epi32(key, last)) == 0xffff)
      return voxel_;  // the previous point's voxel
    _mm_store_si128(reinterpret_cast<__m128i*>(voxel_key_.data()), key);
    const Eigen::Array4i& voxel = voxel_key_;
#else
    const Eigen::Array4i floor = local.cast<int>();  // truncation: local > 0
    *f = local - floor.cast<float>();
    const Eigen::Array4i voxel = base + floor;
    if ((voxel == voxel_key_).all()) return voxel_;  // the previous point's voxel
    voxel_key_ = voxel;
#endif
    voxel_ = nullptr;
    const auto ix = static_cast<std::uint32_t>(voxel[0]);
    const auto iy = static_cast<std::uint32_t>(voxel[1]);
    const auto iz = static_cast<std::uint32_t>(voxel[2]);
    constexpr auto kLimit = static_cast<std::uint32_t>(kMortonMaxCoord) + 1u;
    if ((ix >= kLimit) | (iy >= kLimit) | (iz >= kLimit)) return nullptr;  // also negative
    const std::uint32_t bx = ix >> 2, by = iy >> 2, bz = iz >> 2;
    if (bx != bx_ || by != by_ || bz != bz_) {
      bx_ = bx;
      by_ = by;
      bz_ = bz;
      brick_ = sdf_->BrickAt(bx, by, bz);
    }
    if (brick_ == nullptr) return nullptr;
    const std::uint32_t l = (ix & 3) | (iy & 3) << 2 | (iz & 3) << 4;
    if (((brick_->mask >> kMortonBit[l]) & 1) == 0) return nullptr;
    voxel_ = brick_->value + (ix & 3) + 5 * (iy & 3) + 25 * (iz & 3);
    return voxel_;
  }

  /// Two stages of a prefetch for a lookup at g some lookups ahead: first the
  /// brick's index entry (PrefetchIndex, the earlier), then, once that entry is
  /// in the cache, the brick's mask and the corner values of g's voxel
  /// (PrefetchCorners). Neither changes what a lookup returns.
  void PrefetchIndex(const GridPoint& g) const {
    std::uint32_t b[3];
    if (BrickOf(g, b)) sdf_->band_.PrefetchIndexAt(b[0], b[1], b[2]);
  }
  void PrefetchCorners(const GridPoint& g) const {
    std::uint32_t b[3];
    if (!BrickOf(g, b)) return;
    const NarrowBandSdf::CornerBrick* brick = sdf_->BrickAt(b[0], b[1], b[2]);
    if (brick == nullptr) return;
    const Eigen::Array4i v = g.base + g.local.cast<int>();
    const float* corner = brick->value + (v[0] & 3) + 5 * (v[1] & 3) + 25 * (v[2] & 3);
    __builtin_prefetch(brick);
    __builtin_prefetch(corner);
    __builtin_prefetch(corner + 30);
  }

  /// Trilinear signed distance (mm) at base + local; false outside the band.
  bool Value(const Eigen::Array4i& base, const Eigen::Array4f& local, float* distance) {
    Eigen::Array4f f;
    const float* v = Locate(base, local, &f);
    if (v == nullptr) return false;
    *distance = Trilinear(v, f, nullptr);
    return true;
  }
  /// Same, with the gradient (per mm) of the interpolant.
  bool ValueAndGradient(const Eigen::Array4i& base, const Eigen::Array4f& local, float* distance,
                        Eigen::Vector3f* gradient) {
    Eigen::Array4f f;
    const float* v = Locate(base, local, &f);
    if (v == nullptr) return false;
    *distance = Trilinear(v, f, gradient);
    *gradient *= inv_s_;
    return true;
  }
  /// Voxel-level value: the mean of the 8 corners of the voxel (mm).
  bool CellValue(const Eigen::Array4i& base, const Eigen::Array4f& local, double* distance) {
    Eigen::Array4f f;
    const float* v = Locate(base, local, &f);
    if (v == nullptr) return false;
    double sum = 0.0;
    for (const int step : kCornerStep) sum += static_cast<double>(v[step]);
    *distance = sum / 8.0;
    return true;
  }

 private:
  /// Brick coordinates of g's voxel; false beyond the key range.
  static bool BrickOf(const GridPoint& g, std::uint32_t* b) {
    constexpr auto kLimit = static_cast<std::uint32_t>(kMortonMaxCoord) + 1u;
    for (int a = 0; a < 3; ++a) {
      const auto i = static_cast<std::uint32_t>(g.base[a] + static_cast<int>(g.local[a]));
      if (i >= kLimit) return false;
      b[a] = i >> 2;
    }
    return true;
  }
  /// Offset of corner o = x + 2y + 4z from corner 0 in a 5x5x5 corner brick.
  static constexpr int kCornerStep[8] = {0, 1, 5, 6, 25, 26, 30, 31};
  /// Bit of local voxel x + 4y + 16z (each 0..3) in a brick's Morton-ordered mask.
  static constexpr std::array<std::uint8_t, 64> kMortonBit = [] {
    std::array<std::uint8_t, 64> t{};
    for (int l = 0; l < 64; ++l) {
      const int x = l & 3, y = (l >> 2) & 3, z = l >> 4;
      t[static_cast<std::size_t>(l)] = static_cast<std::uint8_t>(
          (x & 1) | (y & 1) << 1 | (z & 1) << 2 | (x >> 1) << 3 | (y >> 1) << 4 | (z >> 1) << 5);
    }
    return t;
  }();

  /// The trilinear interpolant of the corners at v (and its gradient per voxel
  /// unit when `gradient` is not null), in the order of NarrowBandSdf::Interpolate.
  static float Trilinear(const float* v, const Eigen::Array4f& f, Eigen::Vector3f* gradient) {
    const float x = f[0], y = f[1], z = f[2];
    const float e0 = v[1] - v[0], e1 = v[6] - v[5], e2 = v[26] - v[25], e3 = v[31] - v[30];
    const float a0 = v[0] + x * e0, a1 = v[5] + x * e1, a2 = v[25] + x * e2, a3 = v[30] + x * e3;
    const float b0 = a0 + y * (a1 - a0), b1 = a2 + y * (a3 - a2);
    if (gradient != nullptr) {
      *gradient = Eigen::Vector3f((1 - z) * ((1 - y) * e0 + y * e1) + z * ((1 - y) * e2 + y * e3),
                                  (1 - z) * (a1 - a0) + z * (a3 - a2), b1 - b0);
    }
    return b0 + z * (b1 - b0);
  }

  const NarrowBandSdf* sdf_;
  float inv_s_;
  // The previous point's voxel (key-space coordinates) and its corners (null:
  // not in the band), and the last brick looked up.
  Eigen::Array4i voxel_key_ = Eigen::Array4i(-1, -1, -1, 0);
  const float* voxel_ = nullptr;
  std::uint32_t bx_ = ~0u, by_ = ~0u, bz_ = ~0u;
  const NarrowBandSdf::CornerBrick* brick_ = nullptr;
};

}  // namespace occlude::collision
