// EstimateArchFrame on the synthetic pair (occlusal axis +y, anterior +z by
// construction) seen in rotated frames: the interface plane fit recovers the
// rotated axes, also when the occlusal plane is tilted far from the frame's
// axes (intraoral scans come in arbitrary scanner frames), and the fallback
// without an interface (jaws pulled apart) still finds the axis.
#include <gtest/gtest.h>

#include <cmath>

#include "occlude/collision/oracle.h"
#include "occlude/io/synthetic_jaws.h"

namespace occlude::collision {
namespace {

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
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
    const double angle = axis_angle_deg.norm() * M_PI / 180.0;
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

}  // namespace
}  // namespace occlude::collision
