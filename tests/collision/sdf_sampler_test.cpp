// SdfSampler against NarrowBandSdf: the same voxel (known or not) and the same
// trilinear value and gradient at seeded points near and far from a sphere,
// from absolute points and from float offsets about a cell's grid point (the
// oracle's hot path), and the remembered brick and voxel never going stale.
#include "occlude/collision/sdf_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_common.h"

namespace occlude::collision {
namespace {

using V = Eigen::Vector3d;

/// Corner values are floats of distances < 2 mm and local coordinates floats
/// of at most 9 voxels: rounding stays below this.
constexpr double kSamplerFloatMm = 2e-6;
/// A point from a float offset lands within ~1e-7 voxel of the double one;
/// times a gradient of at most sqrt(3), plus the corners' rounding.
constexpr double kOffsetMm = 1e-5;
/// The gradient is a difference of corners over s = 0.2 mm.
constexpr double kFloatGradient = 1e-4;

NarrowBandSdf SphereField(double s) {
  auto mesh =
      std::make_shared<const io::TriangleMesh>(test::MakeSphere(V(0.3, -0.2, 0.1), 2.0, 24, 48));
  VoxelizeOptions options;
  options.voxel_size_mm = s;
  options.classify_proximity = false;
  options.classify_interior = false;
  return NarrowBandSdf::Build(mesh, Voxelize(*mesh, options));
}

TEST(SdfSampler, AbsolutePointsMatchInterpolateAndCellValue) {
  const NarrowBandSdf sdf = SphereField(0.2);
  SdfSampler sampler(sdf);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  int known = 0;
  for (int i = 0; i < 20000; ++i) {
    // Every other point repeats its predecessor's neighbourhood (cache hits).
    const V p = V(u(rng), u(rng), u(rng));
    double d_ref = 0.0, c_ref = 0.0;
    V g_ref = V::Zero();
    const bool k_ref = sdf.Interpolate(p, &d_ref, &g_ref);
    ASSERT_EQ(sdf.CellValue(p, &c_ref), k_ref);
    const SdfSampler::GridPoint g = sampler.GridPointOf(p);
    float d = 0.0f;
    Eigen::Vector3f grad = Eigen::Vector3f::Zero();
    ASSERT_EQ(sampler.ValueAndGradient(g.base, g.local, &d, &grad), k_ref) << i;
    double c = 0.0;
    ASSERT_EQ(sampler.CellValue(g.base, g.local, &c), k_ref) << i;
    if (!k_ref) continue;
    ++known;
    EXPECT_NEAR(static_cast<double>(d), d_ref, kSamplerFloatMm) << i;
    EXPECT_NEAR(c, c_ref, kSamplerFloatMm) << i;
    EXPECT_LT((grad.cast<double>() - g_ref).norm(), kFloatGradient) << i;
  }
  EXPECT_GT(known, 2000);  // the band around the sphere is hit often
}

TEST(SdfSampler, OffsetsAboutAGridPointMatchAbsolutePoints) {
  const double s = 0.2;
  const NarrowBandSdf sdf = SphereField(s);
  SdfSampler sampler(sdf);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int known = 0;
  for (int cell = 0; cell < 400; ++cell) {
    // A cell centre on the sphere's surface and a random rotation, like the
    // oracle's upper cells: samples within 0.35 mm of it.
    const V centre = V(0.3, -0.2, 0.1) + 2.0 * V(u(rng), u(rng), u(rng)).normalized();
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(3.0 * u(rng), V(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    const SdfSampler::GridPoint c = sampler.GridPointOf(centre);
    const Eigen::Matrix3f M = (R / s).cast<float>();
    for (int j = 0; j < 12; ++j) {
      const V o = 0.35 * V(u(rng), u(rng), u(rng)) / std::sqrt(3.0);
      Eigen::Array4f local = c.local;
      local.head<3>() += (M * o.cast<float>()).array();
      const V p = centre + R * o;
      double d_ref = 0.0;
      const bool k_ref = sdf.Interpolate(p, &d_ref);
      float d = 0.0f;
      const bool k = sampler.Value(c.base, local, &d);
      // Float offsets can put a point within ~1e-6 voxel of a face into the
      // neighbouring voxel; away from faces the voxel is the same.
      const V q = (p - centre) / s + c.local.head<3>().cast<double>().matrix();
      const V frac = q - q.array().floor().matrix();
      if ((frac.array().min(1.0 - frac.array())).minCoeff() < 1e-4) continue;
      ASSERT_EQ(k, k_ref) << cell << " " << j;
      if (!k) continue;
      ++known;
      EXPECT_NEAR(static_cast<double>(d), d_ref, kOffsetMm) << cell << " " << j;
    }
  }
  EXPECT_GT(known, 2000);
}

TEST(SdfSampler, FarAndNonFinitePointsAreUnknown) {
  const NarrowBandSdf sdf = SphereField(0.25);
  SdfSampler sampler(sdf);
  float d = 0.0f;
  for (const V& p : {V(1e9, 0, 0), V(-1e9, 0, 0), V(0.3, -0.2, 0.1), V(std::nan(""), 0, 0),
                     V(0, std::numeric_limits<double>::infinity(), 0)}) {
    const SdfSampler::GridPoint g = sampler.GridPointOf(p);
    EXPECT_FALSE(sampler.Value(g.base, g.local, &d)) << p.transpose();
  }
}

}  // namespace
}  // namespace occlude::collision
