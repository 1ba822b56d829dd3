// The oracle's culling of cells and voxels (OracleRequest::cull) against the
// unculled query on seeded poses: every total, per-part figure, point list and
// residual is identical (same samples, same order, same arithmetic), the
// minimum distance is exact within the outer band, and culling really skips
// work. Scenes: two open wavy surfaces through contact (both accuracy levels
// that cull, with and without residuals), nested closed spheres (deep
// samples), and the real registered bite when ../shared/data exists.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "occlude/angles.h"
#include "occlude/collision/oracle.h"
#include "occlude/io/mesh_io.h"
#include "test_common.h"

namespace occlude::collision {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

void ExpectSamePoints(const std::vector<SurfacePoint>& a, const std::vector<SurfacePoint>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].p_L, b[i].p_L) << i;
    EXPECT_EQ(a[i].distance_mm, b[i].distance_mm) << i;
    EXPECT_EQ(a[i].area_mm2, b[i].area_mm2) << i;
    EXPECT_EQ(a[i].part, b[i].part) << i;
  }
}

struct Work {
  std::size_t culled_samples = 0, full_samples = 0;
  std::size_t culled_cells = 0, full_cells = 0;
};

/// Culled and unculled answers at X; returns the work of each. The culled query
/// prunes with the field bound when the oracle has one and the request allows
/// (OracleOptions::field_bound_mm), the unculled one never: the same answers,
/// from fewer cells.
Work CompareAt(const JawOracle& oracle, const Isometry3d& X, OracleRequest req) {
  OracleResult culled, full;
  req.cull = true;
  oracle.Query(X, req, &culled);
  req.cull = false;
  oracle.Query(X, req, &full);
  // The same additions in the same order: equal to the last bit.
  EXPECT_EQ(culled.max_penetration_mm, full.max_penetration_mm);
  EXPECT_EQ(culled.penetration_area_mm2, full.penetration_area_mm2);
  EXPECT_EQ(culled.deepest_p_L, full.deepest_p_L);
  EXPECT_EQ(culled.deep_samples, full.deep_samples);
  EXPECT_EQ(culled.contact_area_mm2, full.contact_area_mm2);
  EXPECT_EQ(culled.contact_samples, full.contact_samples);
  EXPECT_EQ(culled.left_share, full.left_share);
  EXPECT_EQ(culled.anterior_share, full.anterior_share);
  EXPECT_EQ(culled.parts.size(), full.parts.size());
  for (std::size_t p = 0; p < std::min(culled.parts.size(), full.parts.size()); ++p) {
    EXPECT_EQ(culled.parts[p].contact_area_mm2, full.parts[p].contact_area_mm2) << p;
    EXPECT_EQ(culled.parts[p].contact_samples, full.parts[p].contact_samples) << p;
    EXPECT_EQ(culled.parts[p].penetration_area_mm2, full.parts[p].penetration_area_mm2) << p;
    EXPECT_EQ(culled.parts[p].max_penetration_mm, full.parts[p].max_penetration_mm) << p;
  }
  ExpectSamePoints(culled.contacts, full.contacts);
  ExpectSamePoints(culled.penetrations, full.penetrations);
  ExpectSamePoints(culled.deep_points, full.deep_points);
  EXPECT_EQ(culled.residuals.size(), full.residuals.size());
  for (std::size_t i = 0; i < std::min(culled.residuals.size(), full.residuals.size()); ++i) {
    EXPECT_EQ(culled.residuals[i].distance_mm, full.residuals[i].distance_mm) << i;
    EXPECT_EQ(culled.residuals[i].gradient, full.residuals[i].gradient) << i;
  }
  // The minimum: exact within the outer band, else an upper bound above it.
  const double outer = std::max(req.contact_band_mm, req.residuals ? req.residual_band_mm : 0.0);
  if (full.min_distance_mm <= outer) {
    EXPECT_EQ(culled.min_distance_mm, full.min_distance_mm);
  } else {
    EXPECT_GE(culled.min_distance_mm, full.min_distance_mm);
    EXPECT_GT(culled.min_distance_mm, outer);
  }
  EXPECT_LE(culled.samples_evaluated, full.samples_evaluated);
  return {culled.samples_evaluated, full.samples_evaluated, culled.cells, full.cells};
}

/// The indices and depths of the penetrating points no deeper than `depth`.
std::vector<std::pair<std::size_t, double>> ShallowPoints(const std::vector<SurfacePoint>& points,
                                                          double depth) {
  std::vector<std::pair<std::size_t, double>> out;
  for (const SurfacePoint& p : points) {
    if (-p.distance_mm <= depth) out.emplace_back(out.size(), p.distance_mm);
  }
  return out;
}

/// Poses along the occlusal axis through X_ref, with a seeded jitter of up
/// to 0.3 degrees about `pivot` and 0.05 mm across.
std::vector<Isometry3d> Sweep(const Isometry3d& X_ref, const Vector3d& axis, const Vector3d& pivot,
                              const std::vector<double>& offsets, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Isometry3d> poses;
  for (const double offset : offsets) {
    const double angle = RadiansFromDegrees(0.3) * u(rng);
    const Isometry3d jitter =
        Eigen::Translation3d(pivot + 0.05 * Vector3d(u(rng), 0.0, u(rng))) *
        Eigen::AngleAxisd(angle, Vector3d(u(rng), u(rng), u(rng)).normalized()) *
        Eigen::Translation3d(-pivot);
    poses.push_back(Eigen::Translation3d(offset * axis) * jitter * X_ref);
  }
  return poses;
}

/// An open, wavy height field z = h(x, y) (+ lift) over [0, 8]^2 mm in two
/// parts (x below / above 4), facing +z (up) or -z: a stand-in for two occlusal
/// surfaces that interdigitate, open like a scan.
io::TriangleMesh WavySurface(bool up, double phase, double lift) {
  constexpr int kN = 40;
  constexpr double kStep = 8.0 / kN;
  io::TriangleMesh m;
  for (int j = 0; j <= kN; ++j) {
    for (int i = 0; i <= kN; ++i) {
      const double x = i * kStep, y = j * kStep;
      const double z = 0.4 * std::sin(1.3 * x + phase) * std::cos(0.9 * y) +
                       0.15 * std::sin(0.7 * x + 1.7 * y) + lift;
      m.vertices.emplace_back(x, y, z);
    }
  }
  m.parts = {{"left", 0}, {"right", 0}};
  for (int j = 0; j < kN; ++j) {
    for (int i = 0; i < kN; ++i) {
      const int v = j * (kN + 1) + i;
      const Eigen::Vector3i t0(v, v + 1, v + kN + 2), t1(v, v + kN + 2, v + kN + 1);
      m.triangles.push_back(up ? t0 : Eigen::Vector3i(t0.x(), t0.z(), t0.y()));
      m.triangles.push_back(up ? t1 : Eigen::Vector3i(t1.x(), t1.z(), t1.y()));
      m.triangle_part.insert(m.triangle_part.end(), 2, i < kN / 2 ? 0 : 1);
    }
  }
  m.ComputeFaceNormals();
  return m;
}

TEST(OracleCull, WavySurfacesThroughContactMatchTheUnculledQuery) {
  // The upper surface is the lower's shape shifted by a phase, so that the gap
  // varies: lowered along z it touches, then interpenetrates in places.
  auto lower = std::make_shared<io::TriangleMesh>(WavySurface(true, 0.0, 0.0));
  auto upper = std::make_shared<io::TriangleMesh>(WavySurface(false, 0.25, 0.0));
  OracleOptions options;
  options.voxel_size_mm = 0.2;
  options.sample_spacing_mm = 0.15;
  const JawOracle oracle(lower, upper, options);
  const Vector3d pivot(4, 4, 0);
  std::size_t culled = 0, full = 0, culled_cells = 0, full_cells = 0;
  for (const Isometry3d& X : Sweep(Isometry3d::Identity(), Vector3d::UnitZ(), pivot,
                                   {0.8, 0.5, 0.35, 0.25, 0.15, 0.05, -0.1}, 17)) {
    for (const AccuracyLevel level : {AccuracyLevel::kVoxel, AccuracyLevel::kSubVoxel}) {
      for (const bool residuals : {false, true}) {
        OracleRequest req;
        req.level = level;
        req.residuals = residuals;
        req.pivot_L = pivot;
        const Work w = CompareAt(oracle, X, req);
        if (!residuals && level == AccuracyLevel::kSubVoxel) {
          culled += w.culled_samples;
          full += w.full_samples;
        }
        // The field bound serves contact-only requests; the residual band (0.5 mm) is wider.
        if (residuals) {
          EXPECT_EQ(w.culled_cells, w.full_cells);
        } else {
          culled_cells += w.culled_cells;
          full_cells += w.full_cells;
        }
      }
    }
  }
  // Culling must actually skip samples on this sweep (else it tests nothing);
  // the surfaces are close everywhere, so a quarter is a clear margin.
  EXPECT_LT(4 * culled, 3 * full) << culled << " of " << full;
  // The field bound (no cell wholly beyond the contact band) must report fewer cells.
  EXPECT_LT(20 * culled_cells, 19 * full_cells) << culled_cells << " of " << full_cells;
}

TEST(OracleCull, DeepSamplesInsideAClosedJawAreCountedTheSame) {
  // A closed lower sphere (interior voxels) and a smaller upper sphere placed
  // around its surface and well inside it: unknown samples beyond the band
  // are deep only inside.
  auto lower = std::make_shared<io::TriangleMesh>(test::MakeSphere({0, 0, 0}, 3.0, 24, 32));
  auto upper = std::make_shared<io::TriangleMesh>(test::MakeSphere({0, 0, 0}, 1.0, 16, 24));
  OracleOptions options;
  options.voxel_size_mm = 0.2;
  options.sample_spacing_mm = 0.2;
  // Penetration reaches beyond the search depth here, where each broad phase
  // measures only part of it (OracleRequest::penetration_search_mm): culling
  // is compared without the field bound; the field bound is compared on the
  // samples within the search depth, which both broad phases find.
  options.field_bound_mm = -1.0;
  const JawOracle oracle(lower, upper, options);
  options.field_bound_mm = 0.1;
  const JawOracle bounded(lower, upper, options);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::size_t deep = 0;
  for (int i = 0; i < 24; ++i) {
    const Vector3d dir = Vector3d(u(rng), u(rng), u(rng)).normalized();
    Isometry3d X = Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(3.0 * u(rng), Vector3d(u(rng), u(rng), u(rng)).normalized())
                     .toRotationMatrix();
    X.translation() =
        (i % 3 == 0 ? 0.5 : 1.6 + 0.9 * u(rng)) * dir;  // nested, or across the surface
    for (const AccuracyLevel level : {AccuracyLevel::kVoxel, AccuracyLevel::kSubVoxel}) {
      OracleRequest req;
      req.level = level;
      CompareAt(oracle, X, req);
      OracleResult r, b;
      oracle.Query(X, req, &r);
      bounded.Query(X, req, &b);
      deep += r.deep_samples;
      EXPECT_EQ(ShallowPoints(r.penetrations, req.penetration_search_mm),
                ShallowPoints(b.penetrations, req.penetration_search_mm));
      EXPECT_EQ(r.contact_samples, b.contact_samples);
      EXPECT_EQ(r.contact_area_mm2, b.contact_area_mm2);
      ExpectSamePoints(r.contacts, b.contacts);
      if (i % 3 == 0) {
        EXPECT_EQ(r.deep_samples, b.deep_samples);  // nested: every sample of the piece
      }
    }
  }
  EXPECT_GT(deep, 0u);  // the scene does exercise the deep count
}

TEST(OracleCull, RealRegisteredBiteMatchesTheUnculledQuery) {
  OCCLUDE_REQUIRE_CASE(dir, "a-bite-3shape");
  const auto lower = std::make_shared<const io::TriangleMesh>(io::LoadMesh(dir / "lower.stl"));
  const auto upper = std::make_shared<const io::TriangleMesh>(io::LoadMesh(dir / "upper.stl"));
  OracleOptions options;
  options.voxel_size_mm = 0.4;  // keeps the build short (the sanitizer lane too)
  const JawOracle oracle(lower, upper, options);
  Vector3d pivot = Vector3d::Zero();
  for (const auto& v : lower->vertices) pivot += v;
  pivot /= static_cast<double>(lower->vertices.size());
  std::size_t culled = 0, full = 0;
  for (const Isometry3d& X :
       Sweep(Isometry3d::Identity(), Vector3d::UnitY(), pivot, {0.5, 0.1, 0.0, -0.2}, 23)) {
    for (const bool residuals : {false, true}) {
      OracleRequest req;
      req.residuals = residuals;
      req.pivot_L = pivot;
      const Work w = CompareAt(oracle, X, req);
      if (!residuals) {
        culled += w.culled_samples;
        full += w.full_samples;
      }
    }
  }
  EXPECT_LT(2 * culled, full) << culled << " of " << full;
}

}  // namespace
}  // namespace occlude::collision
