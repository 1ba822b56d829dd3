// EstimateArchFrame on the synthetic pair (occlusal axis +y, anterior +z by
// construction) seen in rotated frames: the interface plane fit recovers the
// rotated axes, also when the occlusal plane is tilted far from the frame's
// axes (intraoral scans come in arbitrary scanner frames), and the fallback
// without an interface (jaws pulled apart) still finds the axis.
#include "occlude/collision/arch_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "occlude/angles.h"
#include "occlude/io/synthetic_jaws.h"
#include "test_common.h"

namespace occlude::collision {
namespace {

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return DegreesFromRadians(std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)));
}

// The synthetic occlusal surfaces carry the curve-of-Spee-free design: the interface plane
// is the design's occlusal plane to within the cusp relief, 2 degrees.
constexpr double kOcclusalToleranceDeg = 2.0;
// Anterior comes from the arch outline (narrowing): within 5 degrees.
constexpr double kAnteriorToleranceDeg = 5.0;

TEST(ArchFrame, RecoversRotatedOcclusalAndAnteriorAxes) {
  io::SyntheticJawOptions o;
  o.triangles_per_jaw = 5000;
  const io::SyntheticJawPair jaws = io::MakeSyntheticJawPair(o);
  const io::TriangleMesh upper_L = jaws.upper_U.Transformed(jaws.X_LU);
  for (const Eigen::Vector3d& axis_angle_deg :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(25, 0, 0), Eigen::Vector3d(0, 0, -30),
        Eigen::Vector3d(20, 40, 10), Eigen::Vector3d(90, 0, 0)}) {
    const double angle = RadiansFromDegrees(axis_angle_deg.norm());
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    if (angle > 0)
      X.linear() = Eigen::AngleAxisd(angle, axis_angle_deg.normalized()).toRotationMatrix();
    X.translation() = Eigen::Vector3d(12, -40, 300);
    const ArchFrame f = EstimateArchFrame(jaws.lower_L.Transformed(X), upper_L.Transformed(X));
    EXPECT_LT(AngleDeg(f.occlusal_L, X.linear() * Eigen::Vector3d::UnitY()), kOcclusalToleranceDeg)
        << axis_angle_deg.transpose();
    EXPECT_LT(AngleDeg(f.anterior_L, X.linear() * Eigen::Vector3d::UnitZ()), kAnteriorToleranceDeg)
        << axis_angle_deg.transpose();
    EXPECT_NEAR(f.lateral_L.dot(f.occlusal_L), 0.0, 1e-9);
  }
}

TEST(ArchFrame, WithoutInterfaceFallsBackToTheLowerJawShape) {
  io::SyntheticJawOptions o;
  o.triangles_per_jaw = 5000;
  const io::SyntheticJawPair jaws = io::MakeSyntheticJawPair(o);
  Eigen::Isometry3d apart = jaws.X_LU;
  apart.pretranslate(Eigen::Vector3d(0, 20, 0));  // 20 mm open: no interface
  const ArchFrame f = EstimateArchFrame(jaws.lower_L, jaws.upper_U.Transformed(apart));
  // The lower slab's thinnest direction: its height, +y (looser: the slab is not flat).
  EXPECT_LT(AngleDeg(f.occlusal_L, Eigen::Vector3d::UnitY()), 10.0);
}

// A box [0, 10] x [0, 4] x [0, 6] as the upper jaw: its eight corners put the 5th lowest
// percentile at the lowest corner, so the centre is the centre of the face nearest the lower
// jaw (along -occlusal).
TEST(UpperOcclusalCentre, OfABoxIsTheCentreOfItsFaceTowardsTheLowerJaw) {
  const io::TriangleMesh box = test::MakeBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 4, 6));
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  EXPECT_TRUE(UpperOcclusalCentre(box, I, Eigen::Vector3d::UnitY())
                  .isApprox(Eigen::Vector3d(5, 0, 3), 1e-12));
  EXPECT_TRUE(UpperOcclusalCentre(box, I, -Eigen::Vector3d::UnitY())
                  .isApprox(Eigen::Vector3d(5, 4, 3), 1e-12));
  EXPECT_TRUE(UpperOcclusalCentre(io::TriangleMesh{}, I, Eigen::Vector3d::UnitY()).isZero());
}

// The centre is taken on the upper placed by X_LU: the same point as on the moved mesh, and a
// translation of the upper moves it by the translation.
TEST(UpperOcclusalCentre, IsTakenOnTheUpperJawAtThePose) {
  io::SyntheticJawOptions o;
  o.triangles_per_jaw = 5000;
  const io::SyntheticJawPair jaws = io::MakeSyntheticJawPair(o);
  Eigen::Isometry3d X = jaws.X_LU;
  X.prerotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  X.pretranslate(Eigen::Vector3d(4, -2, 7));
  const Eigen::Vector3d occlusal_L = Eigen::Vector3d(0.1, 1, -0.2).normalized();
  const Eigen::Vector3d at_pose = UpperOcclusalCentre(jaws.upper_U, X, occlusal_L);
  const Eigen::Vector3d moved =
      UpperOcclusalCentre(jaws.upper_U.Transformed(X), Eigen::Isometry3d::Identity(), occlusal_L);
  EXPECT_LT((at_pose - moved).norm(), 1e-9);
  const Eigen::Vector3d t(1.5, -0.5, 2.0);
  const Eigen::Vector3d shifted =
      UpperOcclusalCentre(jaws.upper_U, Eigen::Translation3d(t) * X, occlusal_L);
  EXPECT_LT((shifted - (at_pose + t)).norm(), 1e-9);
}

}  // namespace
}  // namespace occlude::collision
