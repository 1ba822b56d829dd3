// The exact signed distances at the narrow band's voxel corners, one 4x4x4
// brick of corners at a time: the closest triangle of one central corner x0
// (a full search) bounds every other corner's distance (d(x) <= d(x0) +
// |x - x0|), so the triangles of the surface voxels within that bound of the
// brick's corners are gathered once, deduplicated, and every corner of the
// brick scans only them, nearest-sphere first rejected in float.
//
// Why the candidates suffice: corner x's closest point q lies on some
// triangle T listed by a surface voxel V that holds q, so V's cube is within
// |x - q| = d(x) <= R = d(x0) + max |x - x0| of x, hence of the corners' box.
// Values are the same as a search per corner (the exact closest triangle,
// signed by pseudo-normals), up to the choice between equidistant triangles.
#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include "occlude/collision/closest_point.h"
#include "occlude/collision/morton.h"
#include "occlude/collision/signed_distance.h"
#include "parallel.h"
#include "signed_distance_detail.h"

namespace occlude::collision {

struct NarrowBandSdf::CornerScratch {
  std::vector<std::uint32_t> seen;  ///< triangle t gathered for the brick when seen[t] == epoch
  std::uint32_t epoch = 0;
  std::uint32_t hint = kNoHint;  ///< the previous corner's closest triangle
  // Candidates of the current brick: internal triangle index and bounding
  // sphere (float, radius rounded up).
  std::vector<std::uint32_t> triangle;
  std::vector<float> cx, cy, cz, r;
};

namespace {
constexpr float kFarMm =
    1e18f;  // a padding candidate's centre: its squared distance is still finite
}  // namespace

// Tests every candidate whose bounding sphere reaches within the best
// distance so far of p (the sphere test in float, four at a time where SSE2
// is there, the exact test in TestTriangle). Candidates are padded to a
// multiple of four.
void NarrowBandSdf::ScanCandidates(const CornerScratch& sc, std::size_t count,
                                   const Eigen::Vector3d& p, Nearest* best, bool* found) const {
  const float px = static_cast<float>(p.x()), py = static_cast<float>(p.y()),
              pz = static_cast<float>(p.z());
  constexpr float kRelative = 1.0f + 1e-6f;  // float rounding of the best distance
#if defined(__SSE2__)
  const __m128 x = _mm_set1_ps(px), y = _mm_set1_ps(py), z = _mm_set1_ps(pz);
  __m128 bestv = _mm_set1_ps(static_cast<float>(best->distance) * kRelative);
  for (std::size_t k = 0; k < count; k += 4) {
    const __m128 dx = _mm_sub_ps(_mm_loadu_ps(&sc.cx[k]), x);
    const __m128 dy = _mm_sub_ps(_mm_loadu_ps(&sc.cy[k]), y);
    const __m128 dz = _mm_sub_ps(_mm_loadu_ps(&sc.cz[k]), z);
    const __m128 d2 =
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    const __m128 reach = _mm_add_ps(_mm_loadu_ps(&sc.r[k]), bestv);
    for (int hit = _mm_movemask_ps(_mm_cmple_ps(d2, _mm_mul_ps(reach, reach))); hit != 0;
         hit &= hit - 1) {
      TestTriangle(
          sc.triangle[k + static_cast<std::size_t>(__builtin_ctz(static_cast<unsigned>(hit)))], p,
          best, found);
      bestv = _mm_set1_ps(static_cast<float>(best->distance) * kRelative);
    }
  }
#else
  for (std::size_t k = 0; k < count; ++k) {
    const float dx = sc.cx[k] - px, dy = sc.cy[k] - py, dz = sc.cz[k] - pz;
    const float reach = sc.r[k] + static_cast<float>(best->distance) * kRelative;
    if (dx * dx + dy * dy + dz * dz > reach * reach) continue;
    TestTriangle(sc.triangle[k], p, best, found);
  }
#endif
}

std::vector<float> NarrowBandSdf::CornerValues(const detail::BrickSet& corners, int threads) const {
  std::vector<float> value(corners.num_voxels());
  // Blocks of bricks, each starting without a hint: a corner's value is its exact distance
  // whatever the order, and the hint (the previous corner's triangle) only decides between
  // equidistant triangles, so fixed blocks keep the values independent of the thread count.
  constexpr std::size_t kBricksPerBlock = 64;
  const std::size_t bricks = corners.bricks().size();
  std::vector<CornerScratch> scratch(static_cast<std::size_t>(std::max(1, threads)));
  detail::ParallelFor((bricks + kBricksPerBlock - 1) / kBricksPerBlock, threads,
                      [&](std::size_t block, int worker) {
                        CornerScratch& sc = scratch[static_cast<std::size_t>(worker)];
                        if (sc.seen.empty()) sc.seen.assign(mesh_->num_triangles(), 0);
                        sc.hint = kNoHint;
                        const std::size_t end = std::min(bricks, (block + 1) * kBricksPerBlock);
                        for (std::size_t bi = block * kBricksPerBlock; bi < end; ++bi)
                          BrickCornerValues(corners, bi, &sc, &value);
                      });
  return value;
}

namespace {

// The index box [lo, hi] of a corner brick's corners (mask bits), the corner nearest the box's
// centre (*centre, a bit) and the largest squared distance of a corner from it (voxel units).
void CornerBox(std::uint64_t mask, Eigen::Vector3i* lo, Eigen::Vector3i* hi, int* centre,
               double* spread2) {
  *lo = Eigen::Vector3i::Constant(4);
  *hi = Eigen::Vector3i::Constant(-1);
  for (std::uint64_t m = mask; m != 0; m &= m - 1) {
    const Eigen::Vector3i l = detail::BrickLocal(__builtin_ctzll(m));
    *lo = lo->cwiseMin(l);
    *hi = hi->cwiseMax(l);
  }
  const Eigen::Vector3d mid = 0.5 * (*lo + *hi).cast<double>();
  *centre = -1;
  double best_mid = std::numeric_limits<double>::infinity();
  for (std::uint64_t m = mask; m != 0; m &= m - 1) {
    const int bit = __builtin_ctzll(m);
    const double d2 = (detail::BrickLocal(bit).cast<double>() - mid).squaredNorm();
    if (d2 < best_mid) {
      best_mid = d2;
      *centre = bit;
    }
  }
  *spread2 = 0.0;
  for (std::uint64_t m = mask; m != 0; m &= m - 1) {
    *spread2 =
        std::max(*spread2, (detail::BrickLocal(__builtin_ctzll(m)) - detail::BrickLocal(*centre))
                               .cast<double>()
                               .squaredNorm());
  }
}

// Squared gap between voxel cube [v, v + 1] and the box [lo, hi] (voxel units).
double BoxGap2(const Eigen::Vector3i& v, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  double g2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double gap = std::max({0.0, v[a] - hi[a], lo[a] - (v[a] + 1.0)});
    g2 += gap * gap;
  }
  return g2;
}

}  // namespace

void NarrowBandSdf::ClearCandidates(CornerScratch* sc) {
  sc->triangle.clear();
  sc->cx.clear();
  sc->cy.clear();
  sc->cz.clear();
  sc->r.clear();
  ++sc->epoch;
}

void NarrowBandSdf::PadCandidates(CornerScratch* sc) {
  while (sc->triangle.size() % 4 != 0) {  // padding, never within reach
    sc->triangle.push_back(0);
    sc->cx.push_back(kFarMm);
    sc->cy.push_back(kFarMm);
    sc->cz.push_back(kFarMm);
    sc->r.push_back(0.0f);
  }
}

void NarrowBandSdf::AddVoxelCandidates(std::size_t voxel, CornerScratch* sc) const {
  for (std::uint32_t i = tri_offsets_[voxel]; i < tri_offsets_[voxel + 1]; ++i) {
    const std::uint32_t t = tri_indices_[i];
    if (sc->seen[t] == sc->epoch) continue;
    sc->seen[t] = sc->epoch;
    const PackedTriangle& pt = packed_[t];
    sc->triangle.push_back(t);
    sc->cx.push_back(static_cast<float>(pt.center.x()));
    sc->cy.push_back(static_cast<float>(pt.center.y()));
    sc->cz.push_back(static_cast<float>(pt.center.z()));
    sc->r.push_back(static_cast<float>(pt.radius) * (1.0f + 1e-5f) + 1e-4f);  // float rounding
  }
}

void NarrowBandSdf::GatherCandidates(const Eigen::Vector3d& box_lo, const Eigen::Vector3d& box_hi,
                                     double R, CornerScratch* sc) const {
  ClearCandidates(sc);
  const double Rv = R * inv_s_, Rv2 = Rv * Rv;
  Eigen::Vector3i vlo, vhi;  // surface voxel index range that can be within R
  for (int a = 0; a < 3; ++a) {
    vlo[a] = std::max(0, static_cast<int>(std::floor(box_lo[a] - Rv)) - 1);
    vhi[a] = std::min(dims_[a] - 1, static_cast<int>(std::floor(box_hi[a] + Rv)));
  }
  for (int bz = vlo.z() >> 2; bz <= vhi.z() >> 2; ++bz) {
    for (int by = vlo.y() >> 2; by <= vhi.y() >> 2; ++by) {
      for (int bx = vlo.x() >> 2; bx <= vhi.x() >> 2; ++bx) {
        const auto* b =
            surface_.FindAt(static_cast<std::uint32_t>(bx), static_cast<std::uint32_t>(by),
                            static_cast<std::uint32_t>(bz));
        if (b == nullptr) continue;
        const Eigen::Vector3i bb(bx, by, bz);
        std::uint64_t mask = b->mask;
        for (int a = 0; a < 3; ++a) {
          mask &= detail::LayersMask(a, std::max(0, vlo[a] - 4 * bb[a]),
                                     std::min(3, vhi[a] - 4 * bb[a]));
        }
        for (std::uint64_t m = mask; m != 0; m &= m - 1) {
          const int bit = __builtin_ctzll(m);
          if (BoxGap2(4 * bb + detail::BrickLocal(bit), box_lo, box_hi) > Rv2) continue;
          AddVoxelCandidates(
              b->first + detail::BrickSet::PopCount(b->mask & ((std::uint64_t{1} << bit) - 1)), sc);
        }
      }
    }
  }
}

void NarrowBandSdf::BrickCornerValues(const detail::BrickSet& corners, std::size_t bi,
                                      CornerScratch* sc, std::vector<float>* value) const {
  // A band corner is within d + 1 voxels (per axis) of a surface voxel, so a
  // triangle lies within sqrt(3) (d + 2) s: the full search always succeeds.
  const double reach = std::sqrt(3.0) * (shift_ + 1) * s_;
  const auto& brick = corners.bricks()[bi];
  const Eigen::Vector3i base = 4 * MortonDecode(brick.key) - Eigen::Vector3i::Constant(shift_);
  auto corner_p = [&](int bit) {
    return Eigen::Vector3d(origin_ + s_ * (base + detail::BrickLocal(bit)).cast<double>());
  };
  Eigen::Vector3i lo, hi;
  int x0 = -1;
  double spread2 = 0.0;
  CornerBox(brick.mask, &lo, &hi, &x0, &spread2);
  Nearest n0;
  if (!FindNearest(corner_p(x0), reach * reach, sc->hint, &n0)) {  // unreachable
    std::uint32_t slot = brick.first;
    for (std::uint64_t m = brick.mask; m != 0; m &= m - 1, ++slot)
      (*value)[slot] = static_cast<float>(reach);
    return;
  }
  // The triangles of surface voxels whose cubes are within R of the corners' box.
  const double R = std::sqrt(n0.squared_distance) + s_ * std::sqrt(spread2) * (1.0 + 1e-9) + 1e-9;
  GatherCandidates((base + lo).cast<double>(), (base + hi).cast<double>(), R, sc);
  const std::size_t count = sc->triangle.size();
  PadCandidates(sc);
  // Every corner against the candidates, seeded with the previous corner's
  // triangle (x0's for the first).
  std::uint32_t hint = n0.triangle;
  std::uint32_t slot = brick.first;
  for (std::uint64_t m = brick.mask; m != 0; m &= m - 1, ++slot) {
    const int bit = __builtin_ctzll(m);
    const Eigen::Vector3d p = corner_p(bit);
    Nearest best;
    bool found = false;
    best.squared_distance = std::numeric_limits<double>::infinity();
    best.distance = std::numeric_limits<double>::infinity();
    if (bit == x0) {
      best = n0;
      found = true;
    } else {
      TestTriangle(hint, p, &best, &found);
    }
    ScanCandidates(*sc, count, p, &best, &found);
    (*value)[slot] = static_cast<float>(Sign(p, best).distance);
    hint = best.triangle;
  }
  sc->hint = hint;
}

}  // namespace occlude::collision
