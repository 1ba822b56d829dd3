// DetectToothLandmarks' canine tip on analytic crowns (an upper canine, 13): its tooth view is
// built here as the 0.2 mm height map of a densely sampled surface, so tooth coordinates are the
// map's plane coordinates (u = x mesial, v = y labial, w = z along the occlusal axis). The tip
// is where the top of its region reaches farthest labially, not its single highest cell: a worn
// canine whose flat facet holds a small bump off its middle gives the facet's middle, one whose
// facet runs on distally gives the apex, and a crown tilted by 17 deg about the lateral axis (one
// cusp ridge steep, the other gentle) gives its apex.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "analysis/tooth_landmarks.h"
#include "occlude/angles.h"

namespace occlude::analysis {
namespace {

constexpr double kCanineCellMm = 0.2;
constexpr double kCanineHalfLengthMm = 4.0;  // the crown from u = -4 (distal) to 4 (mesial)
constexpr double kCanineHalfWidthMm = 3.0;
constexpr double kCanineSampleMm = 0.02;
constexpr double kCanineTipTolMm = 0.2;
// The apex: mesial of the crown's middle (u_rel 0.1) and labial of it.
const Eigen::Vector3d kCanineApex(0.8, 0.5, 0.0);

// The view of the crown surface w = surface(u, v) (|u| <= 4, |v| <= 3) turned by R: each cell
// of the map the highest sample in it.
ToothView CanineView(const std::function<double(double, double)>& surface,
                     const Eigen::Matrix3d& R) {
  ToothView view;
  view.fdi = 13;
  view.jaw = io::Jaw::kUpper;
  view.u_mesial = kCanineHalfLengthMm;
  view.u_distal = -kCanineHalfLengthMm;
  HeightMap& map = view.top;
  map.cell = kCanineCellMm;
  map.corner = {-kCanineHalfLengthMm - 1.0, -kCanineHalfWidthMm - 1.0};
  map.nx = static_cast<int>(std::lround(2.0 * (kCanineHalfLengthMm + 1.0) / map.cell));
  map.ny = static_cast<int>(std::lround(2.0 * (kCanineHalfWidthMm + 1.0) / map.cell));
  map.height.assign(static_cast<std::size_t>(map.nx * map.ny),
                    std::numeric_limits<double>::quiet_NaN());
  map.triangle.assign(map.height.size(), -1);
  const int nu = static_cast<int>(std::lround(2.0 * kCanineHalfLengthMm / kCanineSampleMm));
  const int nv = static_cast<int>(std::lround(2.0 * kCanineHalfWidthMm / kCanineSampleMm));
  for (int i = 0; i <= nu; ++i) {
    for (int j = 0; j <= nv; ++j) {
      const double u = -kCanineHalfLengthMm + i * kCanineSampleMm;
      const double v = -kCanineHalfWidthMm + j * kCanineSampleMm;
      const Eigen::Vector3d p = R * Eigen::Vector3d(u, v, surface(u, v));
      const int c = map.CellAt(p.head<2>());
      if (c < 0) continue;
      double& h = map.height[static_cast<std::size_t>(c)];
      if (std::isnan(h) || p.z() > h) h = p.z();
    }
  }
  view.top_uvw.assign(map.height.size(), Eigen::Vector3d::Zero());
  for (int c = 0; c < map.nx * map.ny; ++c) {
    if (map.Filled(c)) {
      view.top_uvw[static_cast<std::size_t>(c)] << map.Centre(c),
          map.height[static_cast<std::size_t>(c)];
    }
  }
  return view;
}

// Four straight ridges from the apex: mesial, distal, labial and lingual slopes (rise / run).
double CaninePyramid(double u, double v, double mesial, double distal, double labial,
                     double lingual) {
  const double du = u - kCanineApex.x(), dv = v - kCanineApex.y();
  return kCanineApex.z() - (du > 0 ? mesial * du : -distal * du) -
         (dv > 0 ? labial * dv : -lingual * dv);
}

// The canine tip detected on `view` (a default landmark, tooth 0, when there is none).
ArchLandmark CanineTip(const ToothView& view) {
  for (ArchLandmark& l : DetectToothLandmarks(view, 1.0)) {
    if (l.landmark.type == io::LandmarkType::kCuspTip) return l;
  }
  ADD_FAILURE() << "no canine tip";
  return {};
}

// Worn flat 0.8 mm below its apex, with a bump 0.05 mm high 0.8 mm distal of the facet's middle:
// the bump is the crown's single highest point and the only local maximum, the facet's middle
// (above the apex) is the tip.
TEST(CanineTip, MiddleOfAWornFacetNotItsHighestBump) {
  constexpr double kWearMm = 0.8, kBumpMm = 0.05, kBumpRadiusMm = 0.3, kBumpDistalMm = 0.8;
  const auto worn = [&](double u, double v) {
    const double facet = -kWearMm;
    const double w = std::min(CaninePyramid(u, v, 0.7, 0.7, 0.8, 0.8), facet);
    const double r = std::hypot(u - (kCanineApex.x() - kBumpDistalMm), v - kCanineApex.y());
    return w >= facet && r < kBumpRadiusMm ? facet + kBumpMm * (1.0 - r / kBumpRadiusMm) : w;
  };
  const ArchLandmark tip = CanineTip(CanineView(worn, Eigen::Matrix3d::Identity()));
  const Eigen::Vector3d want = kCanineApex - Eigen::Vector3d(0.0, 0.0, kWearMm);
  EXPECT_LT((tip.landmark.p - want).norm(), kCanineTipTolMm) << tip.landmark.p.transpose();
  EXPECT_EQ(tip.landmark.tooth_fdi, 13);
  EXPECT_GT(tip.confidence, 0.5);
}

// Cusp ridges of 40 deg (mesial) and 35 deg (distal) tilted by 17 deg about the lateral axis,
// the distal side raised: 57 deg and 18 deg in the view. The apex, turned with the crown, is
// still the top, but the cells near it spread distally down the gentle ridge; their middle
// along the arch and across it is within 0.2 mm of the apex.
TEST(CanineTip, ApexOfACrownTiltedAboutTheLateralAxis) {
  const double tilt = RadiansFromDegrees(17.0);
  const auto pyramid = [](double u, double v) {
    return CaninePyramid(u, v, std::tan(RadiansFromDegrees(40.0)),
                         std::tan(RadiansFromDegrees(35.0)), 1.0, 0.6);
  };
  // About v (the lateral axis of the tooth): a point at u < 0 (distal) rises.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()).toRotationMatrix();
  ASSERT_GT((R * Eigen::Vector3d(-1.0, 0.0, 0.0)).z(), 0.0);
  const ArchLandmark tip = CanineTip(CanineView(pyramid, R));
  const Eigen::Vector3d want = R * kCanineApex;
  EXPECT_LT((tip.landmark.p - want).norm(), kCanineTipTolMm) << tip.landmark.p.transpose();
}

// Worn flat 0.6 mm below its apex with a steep mesial ridge (0.7) and a gentle distal one (0.35):
// the facet runs on 1.7 mm distally of the apex but only 0.9 mm mesially, so its middle lies
// 0.43 mm distal of the apex, while its labial outline (and that of the cells below it) still
// bulges most at the apex's position along the arch: the tip is there.
TEST(CanineTip, TopOfTheLabialRidgeNotTheMiddleOfACrestRunningOnDistally) {
  constexpr double kWearMm = 0.6, kMesialSlope = 0.7, kDistalSlope = 0.35;
  const auto worn = [&](double u, double v) {
    return std::min(CaninePyramid(u, v, kMesialSlope, kDistalSlope, 0.8, 0.8), -kWearMm);
  };
  const double facet_middle =
      kCanineApex.x() + 0.5 * (kWearMm / kMesialSlope - kWearMm / kDistalSlope);
  ASSERT_LT(facet_middle, kCanineApex.x() - 2.0 * kCanineTipTolMm);
  const ArchLandmark tip = CanineTip(CanineView(worn, Eigen::Matrix3d::Identity()));
  EXPECT_NEAR(tip.landmark.p.x(), kCanineApex.x(), kCanineTipTolMm) << tip.landmark.p.transpose();
  EXPECT_NEAR(tip.landmark.p.z(), -kWearMm, kCanineTipTolMm) << tip.landmark.p.transpose();
}

}  // namespace
}  // namespace occlude::analysis
