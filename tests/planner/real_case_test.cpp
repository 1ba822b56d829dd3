// The planner on a real intraoral pair (c1: open scans with spikes): the
// outlier-robust measure meets the limit while the true maximum is reported,
// and the ignored points are listed. Skips when ../shared/data is absent.
#include <gtest/gtest.h>

#include "occlude/io/mesh_io.h"
#include "occlude/planner/plan.h"
#include "test_common.h"

namespace occlude::planner {
namespace {

TEST(PlanRealTest, IntraoralCaseSettlesWithOutliersListed) {
  OCCLUDE_REQUIRE_CASE(dir, "c1-ios-decimated");
  auto lower = std::make_shared<io::TriangleMesh>(io::LoadMesh(dir / "lower.stl"));
  auto upper = std::make_shared<io::TriangleMesh>(io::LoadMesh(dir / "upper.stl"));
  const OwnedSchedule schedule = BuildSchedule(lower, upper, {0.8}, false);
  PlanRequest req;
  req.solver = SolverKind::kCeres;
  req.num_starts = 1;
  req.num_threads = 1;
  req.outlier_area_mm2 = 0.5;
  PoseParameters perturb;
  perturb.translation_mm = Eigen::Vector3d(0.5, 0.5, -0.5);
  perturb.rotation_deg = Eigen::Vector3d(1.0, 0.0, 1.0);
  const Eigen::Vector3d pivot = collision::UpperOcclusalCentre(
      *upper, Eigen::Isometry3d::Identity(), schedule.stages[0].oracle->arch().occlusal_L);
  req.X_LU_start = ComposePose(perturb, pivot, Eigen::Isometry3d::Identity());
  const PlanResult res = Plan(schedule.stages, req);
  ASSERT_FALSE(res.proposals.empty());
  const Proposal& p = res.proposals.front();
  EXPECT_TRUE(p.X_LU.matrix().allFinite());
  EXPECT_TRUE(p.evaluation.feasible) << p.message;
  EXPECT_LE(p.evaluation.constrained_penetration_mm, req.max_penetration_mm + 1e-9);
  EXPECT_GE(p.evaluation.max_penetration_mm, p.evaluation.constrained_penetration_mm);
  double outlier_area = 0.0;
  for (const OutlierPoint& o : p.evaluation.outliers) {
    EXPECT_GT(o.depth_mm, 0.0);
    outlier_area += o.area_mm2;
  }
  EXPECT_LE(outlier_area, req.outlier_area_mm2 + 1e-9);
  if (p.evaluation.max_penetration_mm > req.max_penetration_mm) {
    EXPECT_FALSE(p.evaluation.outliers.empty());
  }
  EXPECT_GT(p.evaluation.contact_area_mm2, 0.0);
}

}  // namespace
}  // namespace occlude::planner
