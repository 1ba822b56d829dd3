// The exact signed distances at the narrow band's voxel corners, one 4x4x4
// brick of corners at a time: the closest triangle of one central corner x0
// (a full search) bounds every other corner's distance (d(x) <= d(x0) +
// |x - x0|), so the triangles of the surface voxels within that bound of the
// brick's corners are gathered once, deduplicated, and every corner of the
// brick scans only them. A scan rejects, in float, whole groups of eight
// candidates by their bounding sphere, then single ones by theirs and by the
// disc of it in the triangle's plane; what is left is tested exactly.
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

namespace detail {

/// The candidate triangles of one corner brick, with the bounds a corner's scan rejects them
/// by, in float, relative to the brick's origin (so that rounding stays far below the slacks
/// below whatever the mesh's coordinates): each triangle's bounding sphere and the unit normal
/// of its plane, and the bounding sphere of each run of kGroup consecutive candidates. A scan
/// visits the candidates in their order and only skips: it tests the same triangles a full
/// scan would test exactly, so it finds the same closest triangle.
class CornerCandidates {
 public:
  static constexpr std::size_t kGroup = 8;  ///< candidates per group (two SSE lanes of four)

  void Clear(const Eigen::Vector3d& origin) {
    origin_ = origin;
    count_ = 0;
  }
  /// Makes room for `more` candidates (Add writes without checking).
  void Reserve(std::size_t more) {
    if (count_ + more + kGroup > triangle_.size()) Grow(count_ + more + kGroup);
  }
  /// Adds triangle t with its bounding sphere (centre, radius) and unit plane normal (zero for a
  /// sliver or degenerate triangle: then only the sphere bounds it).
  void Add(std::uint32_t t, const Eigen::Vector3d& center, double radius,
           const Eigen::Vector3f& normal) {
    const Eigen::Vector3d c = center - origin_;
    const std::size_t k = count_++;
    triangle_[k] = t;
    cx_[k] = static_cast<float>(c.x());
    cy_[k] = static_cast<float>(c.y());
    cz_[k] = static_cast<float>(c.z());
    r_[k] = static_cast<float>(radius) * (1.0f + 1e-5f) + kSlackMm;  // float rounding
    nx_[k] = normal.x();
    ny_[k] = normal.y();
    nz_[k] = normal.z();
  }
  /// Pads the candidates to whole groups (padding is never within reach) and bounds each group.
  void Finish();

  /// Calls test(t) for every candidate t, in order, that the bounds cannot reject at the
  /// distance `best` (mm) from p; test returns the new best distance.
  template <class Test>
  void Scan(const Eigen::Vector3d& p, double best, Test&& test) const;

 private:
  static constexpr float kSlackMm = 1e-4f;  ///< float rounding of centres, radii and heights
  static constexpr float kFarMm = 1e18f;    ///< a padding centre: squared distances stay finite
  static constexpr float kRelative = 1.0f + 1e-6f;  ///< float rounding of a distance bound
  /// Calls visit(g) for every group g whose bounding sphere comes within `bound` of p (read
  /// again after each call: visit may lower it).
  template <class Visit>
  void ForGroupsWithin(float px, float py, float pz, const float& bound, Visit&& visit) const;
  /// Scans group g's candidates at the distance bound `best`; returns the bound after them.
  template <class Test>
  float ScanGroup(std::size_t g, float px, float py, float pz, float best, Test&& test) const;

  void Grow(std::size_t size);

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  std::size_t count_ = 0;   ///< candidates added
  std::size_t groups_ = 0;  ///< groups after Finish
  std::vector<std::uint32_t> triangle_;
  std::vector<float> cx_, cy_, cz_, r_;   ///< bounding spheres
  std::vector<float> nx_, ny_, nz_;       ///< unit plane normals
  std::vector<float> gx_, gy_, gz_, gr_;  ///< bounding spheres of the groups (padded to four)
};

void CornerCandidates::Grow(std::size_t size) {
  size = std::max(size, 2 * triangle_.size());
  triangle_.resize(size);
  for (auto* v : {&cx_, &cy_, &cz_, &r_, &nx_, &ny_, &nz_}) v->resize(size);
  const std::size_t slots = (size / kGroup + 3) / 4 * 4;
  for (auto* v : {&gx_, &gy_, &gz_, &gr_}) v->resize(slots);
}

void CornerCandidates::Finish() {
  groups_ = (count_ + kGroup - 1) / kGroup;
  for (std::size_t k = count_; k < groups_ * kGroup; ++k) {
    triangle_[k] = 0;
    cx_[k] = cy_[k] = cz_[k] = kFarMm;
    r_[k] = nx_[k] = ny_[k] = nz_[k] = 0.0f;
  }
  for (std::size_t g = 0; g < groups_; ++g) {
    const std::size_t begin = g * kGroup, end = std::min(count_, begin + kGroup);
    float lo[3] = {kFarMm, kFarMm, kFarMm}, hi[3] = {-kFarMm, -kFarMm, -kFarMm};
    for (std::size_t k = begin; k < end; ++k) {
      lo[0] = std::min(lo[0], cx_[k] - r_[k]);
      lo[1] = std::min(lo[1], cy_[k] - r_[k]);
      lo[2] = std::min(lo[2], cz_[k] - r_[k]);
      hi[0] = std::max(hi[0], cx_[k] + r_[k]);
      hi[1] = std::max(hi[1], cy_[k] + r_[k]);
      hi[2] = std::max(hi[2], cz_[k] + r_[k]);
    }
    const float gx = 0.5f * (lo[0] + hi[0]), gy = 0.5f * (lo[1] + hi[1]),
                gz = 0.5f * (lo[2] + hi[2]);
    float radius = 0.0f;
    for (std::size_t k = begin; k < end; ++k) {
      const float dx = cx_[k] - gx, dy = cy_[k] - gy, dz = cz_[k] - gz;
      radius = std::max(radius, std::sqrt(dx * dx + dy * dy + dz * dz) + r_[k]);
    }
    gx_[g] = gx;
    gy_[g] = gy;
    gz_[g] = gz;
    gr_[g] = radius * (1.0f + 1e-5f) + kSlackMm;  // float rounding
  }
  for (std::size_t g = groups_; g < (groups_ + 3) / 4 * 4; ++g) {  // never within reach
    gx_[g] = gy_[g] = gz_[g] = kFarMm;
    gr_[g] = 0.0f;
  }
}

// A candidate is tested unless its bounding sphere is beyond `best` of p, or the disc of that
// sphere in the triangle's plane is: the disc holds the triangle, so the distance to it (the
// height over the plane and the in-plane gap beyond the radius) bounds the triangle's from
// below. Both with slacks for float rounding: the height less kSlackMm, the squared in-plane
// distance less a relative 1e-5 (it is a difference of two squares, whose rounding the square
// root magnifies when the gap is small).
template <class Test>
float CornerCandidates::ScanGroup(std::size_t g, float px, float py, float pz, float best,
                                  Test&& test) const {
#if defined(__SSE2__)
  const __m128 x = _mm_set1_ps(px), y = _mm_set1_ps(py), z = _mm_set1_ps(pz);
  const __m128 zero = _mm_setzero_ps(), slack = _mm_set1_ps(kSlackMm);
  const __m128 relative = _mm_set1_ps(1e-5f), one = _mm_set1_ps(1.0f);
  for (std::size_t k = g * kGroup; k < (g + 1) * kGroup; k += 4) {
    const __m128 bound = _mm_set1_ps(best * kRelative);
    const __m128 dx = _mm_sub_ps(_mm_loadu_ps(&cx_[k]), x);
    const __m128 dy = _mm_sub_ps(_mm_loadu_ps(&cy_[k]), y);
    const __m128 dz = _mm_sub_ps(_mm_loadu_ps(&cz_[k]), z);
    const __m128 d2 =
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    const __m128 r = _mm_loadu_ps(&r_[k]);
    const __m128 reach = _mm_add_ps(r, bound);
    int hit = _mm_movemask_ps(_mm_cmple_ps(d2, _mm_mul_ps(reach, reach)));
    if (hit == 0) continue;
    const __m128 h = _mm_add_ps(
        _mm_add_ps(_mm_mul_ps(dx, _mm_loadu_ps(&nx_[k])), _mm_mul_ps(dy, _mm_loadu_ps(&ny_[k]))),
        _mm_mul_ps(dz, _mm_loadu_ps(&nz_[k])));
    const __m128 h2 = _mm_mul_ps(h, h);
    const __m128 abs_h = _mm_max_ps(h, _mm_sub_ps(zero, h));
    const __m128 height = _mm_max_ps(_mm_sub_ps(abs_h, slack), zero);
    const __m128 in_plane2 =
        _mm_max_ps(_mm_sub_ps(_mm_sub_ps(d2, h2), _mm_mul_ps(relative, _mm_add_ps(d2, one))), zero);
    const __m128 gap = _mm_max_ps(_mm_sub_ps(_mm_sqrt_ps(in_plane2), r), zero);
    const __m128 lower2 = _mm_add_ps(_mm_mul_ps(height, height), _mm_mul_ps(gap, gap));
    hit &= _mm_movemask_ps(_mm_cmple_ps(lower2, _mm_mul_ps(bound, bound)));
    for (; hit != 0; hit &= hit - 1) {
      const std::uint32_t t =
          triangle_[k + static_cast<std::size_t>(__builtin_ctz(static_cast<unsigned>(hit)))];
      best = std::min(best, static_cast<float>(test(t)));
    }
  }
#else
  for (std::size_t k = g * kGroup; k < (g + 1) * kGroup; ++k) {
    const float bound = best * kRelative;
    const float dx = cx_[k] - px, dy = cy_[k] - py, dz = cz_[k] - pz;
    const float d2 = dx * dx + dy * dy + dz * dz;
    const float reach = r_[k] + bound;
    if (d2 > reach * reach) continue;
    const float h = dx * nx_[k] + dy * ny_[k] + dz * nz_[k];
    const float height = std::max(std::abs(h) - kSlackMm, 0.0f);
    const float in_plane2 = std::max(d2 - h * h - 1e-5f * (d2 + 1.0f), 0.0f);
    const float gap = std::max(std::sqrt(in_plane2) - r_[k], 0.0f);
    if (height * height + gap * gap > bound * bound) continue;
    best = std::min(best, static_cast<float>(test(triangle_[k])));
  }
#endif
  return best;
}

template <class Visit>
void CornerCandidates::ForGroupsWithin(float px, float py, float pz, const float& bound,
                                       Visit&& visit) const {
#if defined(__SSE2__)
  const __m128 x = _mm_set1_ps(px), y = _mm_set1_ps(py), z = _mm_set1_ps(pz);
  for (std::size_t g4 = 0; g4 < groups_; g4 += 4) {
    const __m128 dx = _mm_sub_ps(_mm_loadu_ps(&gx_[g4]), x);
    const __m128 dy = _mm_sub_ps(_mm_loadu_ps(&gy_[g4]), y);
    const __m128 dz = _mm_sub_ps(_mm_loadu_ps(&gz_[g4]), z);
    const __m128 d2 =
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    const __m128 reach = _mm_add_ps(_mm_loadu_ps(&gr_[g4]), _mm_set1_ps(bound * kRelative));
    for (int hit = _mm_movemask_ps(_mm_cmple_ps(d2, _mm_mul_ps(reach, reach))); hit != 0;
         hit &= hit - 1)
      visit(g4 + static_cast<std::size_t>(__builtin_ctz(static_cast<unsigned>(hit))));
  }
#else
  for (std::size_t g = 0; g < groups_; ++g) {
    const float dx = gx_[g] - px, dy = gy_[g] - py, dz = gz_[g] - pz;
    const float reach = gr_[g] + bound * kRelative;
    if (dx * dx + dy * dy + dz * dz <= reach * reach) visit(g);
  }
#endif
}

// The groups within reach of p, then their candidates: every triangle a full scan would test
// exactly, in the same order (so the closest one, and the first of equally close ones).
template <class Test>
void CornerCandidates::Scan(const Eigen::Vector3d& p_F, double best_mm, Test&& test) const {
  const Eigen::Vector3d p = p_F - origin_;
  const float px = static_cast<float>(p.x()), py = static_cast<float>(p.y()),
              pz = static_cast<float>(p.z());
  float bound = static_cast<float>(best_mm);
  ForGroupsWithin(px, py, pz, bound,
                  [&](std::size_t g) { bound = ScanGroup(g, px, py, pz, bound, test); });
}

}  // namespace detail

struct NarrowBandSdf::CornerScratch {
  std::vector<std::uint32_t> seen;  ///< triangle t gathered for the brick when seen[t] == epoch
  std::uint32_t epoch = 0;
  std::uint32_t hint = kNoHint;  ///< the previous corner's closest triangle
  const std::vector<Eigen::Vector3f>* plane_normals = nullptr;  ///< per internal triangle
  detail::CornerCandidates candidates;
};

namespace {

// The unit normal of triangle (a, b, c)'s plane, zero for a sliver (corner-angle sine below
// 1e-6, as in ClosestPointOnTriangle) or a degenerate triangle, whose computed normal may tilt.
Eigen::Vector3f PlaneNormal(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a;
  const Eigen::Vector3d cross = ab.cross(ac);
  if (!(cross.squaredNorm() > 1e-12 * ab.squaredNorm() * ac.squaredNorm()))
    return Eigen::Vector3f::Zero();
  return cross.normalized().cast<float>();
}

}  // namespace

// Tests every candidate the bounds cannot reject at the best distance so far (exactly, in
// TestTriangle), in the candidates' order.
void NarrowBandSdf::ScanCandidates(const CornerScratch& sc, const Eigen::Vector3d& p, Nearest* best,
                                   bool* found) const {
  sc.candidates.Scan(p, best->distance, [&](std::uint32_t t) {
    TestTriangle(t, p, best, found);
    return best->distance;
  });
}

std::vector<float> NarrowBandSdf::CornerValues(const detail::BrickSet& corners, int threads) const {
  std::vector<float> value(corners.num_voxels());
  // Blocks of bricks, each starting without a hint: a corner's value is its exact distance
  // whatever the order, and the hint (the previous corner's triangle) only decides between
  // equidistant triangles, so fixed blocks keep the values independent of the thread count.
  constexpr std::size_t kBricksPerBlock = 64;
  const std::size_t bricks = corners.bricks().size();
  std::vector<Eigen::Vector3f> plane_normals(packed_.size(), Eigen::Vector3f::Zero());
  for (std::size_t t = 0; t < packed_.size(); ++t) {
    const PackedTriangle& pt = packed_[t];
    plane_normals[t] = PlaneNormal(pt.a, pt.b, pt.c);
  }
  std::vector<CornerScratch> scratch(static_cast<std::size_t>(std::max(1, threads)));
  for (CornerScratch& sc : scratch) sc.plane_normals = &plane_normals;
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

void NarrowBandSdf::AddVoxelCandidates(std::size_t voxel, CornerScratch* sc) const {
  sc->candidates.Reserve(tri_offsets_[voxel + 1] - tri_offsets_[voxel]);
  for (std::uint32_t i = tri_offsets_[voxel]; i < tri_offsets_[voxel + 1]; ++i) {
    const std::uint32_t t = tri_indices_[i];
    if (sc->seen[t] == sc->epoch) continue;
    sc->seen[t] = sc->epoch;
    sc->candidates.Add(t, packed_[t].center, packed_[t].radius, (*sc->plane_normals)[t]);
  }
}

void NarrowBandSdf::GatherCandidates(const Eigen::Vector3d& box_lo, const Eigen::Vector3d& box_hi,
                                     double R, CornerScratch* sc) const {
  ++sc->epoch;
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
  sc->candidates.Clear(corner_p(x0));
  GatherCandidates((base + lo).cast<double>(), (base + hi).cast<double>(), R, sc);
  sc->candidates.Finish();
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
    ScanCandidates(*sc, p, &best, &found);
    (*value)[slot] = static_cast<float>(Sign(p, best).distance);
    hint = best.triangle;
  }
  sc->hint = hint;
}

}  // namespace occlude::collision
