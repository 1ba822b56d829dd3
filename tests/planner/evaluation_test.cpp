// EvaluatePose's penetration measure (evaluation.h) on analytic shapes: an
// upper needle pressed deeper than the oracle measures (its tip's samples are
// deep, listed one by one in OracleResult::deep_points) is still a spike patch,
// so an outlier of the measure, as EvaluateSet treats it; a post 2 mm wide
// pressed as deep is real interpenetration, and so is the needle with spike
// patches off.
#include "occlude/planner/evaluation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "occlude/collision/oracle.h"
#include "test_common.h"

namespace occlude::planner {
namespace {

using Eigen::Vector3d;

// The lower a slab with its top face at z = 0; the upper a plate resting 0.03 mm above it
// (in contact) with a post of `width_mm` square section reaching `depth_mm` below z = 0. The
// lower's field has a band of one voxel (0.4 mm), so the oracle measures depths up to 0.4 mm
// and counts the post's samples deeper than that in the cells it evaluates as deep.
struct NeedleScene {
  std::shared_ptr<const io::TriangleMesh> lower, upper;
  std::unique_ptr<collision::JawOracle> oracle;
};

NeedleScene MakeNeedleScene(double width_mm, double depth_mm) {
  NeedleScene s;
  s.lower = std::make_shared<io::TriangleMesh>(occlude::test::MakeBox({-8, -8, -6}, {8, 8, 0}));
  auto upper =
      std::make_shared<io::TriangleMesh>(occlude::test::MakeBox({-5, -5, 0.03}, {5, 5, 2}));
  const double h = 0.5 * width_mm;
  upper->Append(occlude::test::MakeBox({-h, -h, -depth_mm}, {h, h, 0.5}));
  s.upper = upper;
  collision::OracleOptions options;
  options.voxel_size_mm = 0.4;
  options.sdf_dilation_voxels = 1;
  s.oracle = std::make_unique<collision::JawOracle>(s.lower, s.upper, options);
  return s;
}

collision::OracleResult QueryNeedleScene(const collision::JawOracle& oracle,
                                         const PlanRequest& request) {
  collision::OracleRequest q;
  q.level = collision::AccuracyLevel::kSubVoxel;
  q.contact_band_mm = request.contact_band_mm;
  q.penetration_search_mm = std::max(0.3, 4.0 * request.max_penetration_mm);  // as EvaluatePose
  q.keep_points = true;
  collision::OracleResult r;
  oracle.Query(Eigen::Isometry3d::Identity(), q, &r);
  return r;
}

TEST(EvaluatePose, ANeedlePressedBeyondTheMeasuredDepthStaysASpike) {
  const PlanRequest request;  // outlier area and spike patches up to 5 mm^2 (the defaults)
  const NeedleScene s = MakeNeedleScene(0.4, 2.4);
  const collision::OracleResult r = QueryNeedleScene(*s.oracle, request);
  // The needle's tip is deeper than the oracle measures: deep samples, listed with their points.
  const double deep_mm =
      std::max(0.3, 4.0 * request.max_penetration_mm) + s.oracle->lower_sdf().band_mm();
  ASSERT_GT(r.deep_samples, 0u);
  ASSERT_FALSE(r.deep_points.empty());
  EXPECT_LE(r.deep_points.size(), r.deep_samples);
  for (const collision::SurfacePoint& p : r.deep_points) {
    EXPECT_DOUBLE_EQ(p.distance_mm, -deep_mm);
    EXPECT_LT(p.p_L.z(), 0.0) << "a deep point lies inside the lower";
    EXPECT_LT(p.p_L.z(), -s.oracle->lower_sdf().band_mm() + 0.2) << "deeper than the band";
    EXPECT_LE(std::max(std::abs(p.p_L.x()), std::abs(p.p_L.y())), 0.2 + 1e-6)
        << "a deep point lies on the needle";
    EXPECT_GT(p.area_mm2, 0.0);
  }
  // The needle is a spike patch: its measured and its deep samples are outliers, the plate
  // resting on the slab meets the limit.
  const PoseEvaluation e = EvaluatePose({s.oracle.get(), collision::AccuracyLevel::kSubVoxel},
                                        Eigen::Isometry3d::Identity(), request);
  EXPECT_TRUE(e.feasible) << "constrained penetration " << e.constrained_penetration_mm;
  EXPECT_LE(e.constrained_penetration_mm, request.max_penetration_mm);
  EXPECT_GT(e.contact_area_mm2, 50.0) << "the plate rests on the slab";
  const auto deep_outliers =
      std::count_if(e.outliers.begin(), e.outliers.end(),
                    [&](const OutlierPoint& o) { return o.spike && o.depth_mm == deep_mm; });
  EXPECT_EQ(static_cast<std::size_t>(deep_outliers), r.deep_points.size());
  EXPECT_GE(e.max_penetration_mm, deep_mm);
}

TEST(EvaluatePose, AWidePostPressedAsDeepIsNoSpike) {
  const PlanRequest request;
  const NeedleScene s = MakeNeedleScene(2.0, 2.4);
  ASSERT_GT(QueryNeedleScene(*s.oracle, request).deep_points.size(), 0u);
  const PoseEvaluation e = EvaluatePose({s.oracle.get(), collision::AccuracyLevel::kSubVoxel},
                                        Eigen::Isometry3d::Identity(), request);
  EXPECT_FALSE(e.feasible);
  EXPECT_GT(e.constrained_penetration_mm, 0.5);
}

TEST(EvaluatePose, WithoutSpikePatchesTheDeepNeedleCounts) {
  PlanRequest request;
  request.spike_patch_max_mm2 = 0.0;  // spike patches off: the deep tip is interpenetration
  const NeedleScene s = MakeNeedleScene(0.4, 2.4);
  const PoseEvaluation e = EvaluatePose({s.oracle.get(), collision::AccuracyLevel::kSubVoxel},
                                        Eigen::Isometry3d::Identity(), request);
  EXPECT_FALSE(e.feasible);
}

}  // namespace
}  // namespace occlude::planner
