// FindToothCut on analytic jaws seen from the occlusal side (plane coordinates x along a
// straight arch curve, so s = x + kCutCurveStartMm, and y across it, t = y): the cut follows a
// valley between crowns running obliquely across the arch, and lies in the middle of a
// flat-floored gap between crowns (a diastema). DetectToothLandmarks then takes a segmented
// tooth's contact at its oblique cut, not square to the curve at the cut's middle.
#include "analysis/tooth_cut.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "analysis/tooth_landmarks.h"
#include "surface_view.h"

namespace occlude::analysis {
namespace {

constexpr double kCutCellMm = 0.2;
constexpr double kCutCurveStartMm = 12.0;  // the curve runs along x from -12 to 12 mm
constexpr double kCutCrownHalfWidthMm = 4.0;
constexpr double kCutCrownMm = 2.0, kCutGingivaMm = -3.0;
constexpr double kCutReachMm = 2.0;

// The jaw w = surface(x, y) on 0.2 mm cells over |x| <= 10, |y| <= 7, with a straight curve
// along y = 0 (normal +y).
ArchGeometry StraightCurveJaw(const std::function<double(double, double)>& surface) {
  ArchGeometry g;
  HeightMap& map = g.top;
  map.cell = kCutCellMm;
  map.corner = {-10.0, -7.0};
  map.nx = 100;
  map.ny = 70;
  map.height.resize(static_cast<std::size_t>(map.nx * map.ny));
  map.triangle.assign(map.height.size(), -1);
  for (int c = 0; c < map.nx * map.ny; ++c) {
    const Eigen::Vector2d q = map.Centre(c);
    map.height[static_cast<std::size_t>(c)] = surface(q.x(), q.y());
  }
  g.curve.step = 0.25;
  for (double x = -kCutCurveStartMm; x <= kCutCurveStartMm + 1e-9; x += g.curve.step) {
    g.curve.q.emplace_back(x, 0.0);
    g.curve.top.push_back(kCutCrownMm);
  }
  return g;
}

// Two crowns (a plateau kCutCrownMm high over |y| <= 4, gingiva beyond) meeting along the valley
// x = kSlope * y, 2 mm deep: the boundary the segmentation found is square to the curve at
// x = 0, the cut follows the valley (27 deg across the curve) to within a cell.
TEST(ToothCut, FollowsAValleyRunningObliquelyAcrossTheArch) {
  constexpr double kSlope = 0.5;
  const ArchGeometry g = StraightCurveJaw([&](double x, double y) {
    if (std::abs(y) > kCutCrownHalfWidthMm) return kCutGingivaMm;
    const double d = x - kSlope * y;
    return kCutCrownMm - 2.0 * std::exp(-d * d / (2.0 * 0.4 * 0.4));
  });
  const ToothCut cut = FindToothCut(g, kCutCurveStartMm, kCutReachMm);
  for (double t = -3.4; t <= 3.4; t += 0.2) {
    EXPECT_NEAR(cut.At(t), kCutCurveStartMm + kSlope * t, kCutCellMm) << "t " << t;
  }
}

// A gap 1 mm wide with a flat floor between two plateaus, centred on the boundary: every path
// through the gap is as low; the cut keeps to its middle.
TEST(ToothCut, MiddleOfAFlatGapBetweenCrowns) {
  constexpr double kGapMiddleMm = 0.3, kGapHalfMm = 0.5;
  const ArchGeometry g = StraightCurveJaw([&](double x, double y) {
    const bool gap = std::abs(x - kGapMiddleMm) <= kGapHalfMm;
    return std::abs(y) > kCutCrownHalfWidthMm || gap ? kCutGingivaMm : kCutCrownMm;
  });
  const ToothCut cut = FindToothCut(g, kCutCurveStartMm + kGapMiddleMm, kCutReachMm);
  for (double t = -4.8; t <= 4.8; t += 0.4) {
    EXPECT_NEAR(cut.At(t), kCutCurveStartMm + kGapMiddleMm, 0.5 * kCutCellMm) << "t " << t;
  }
}

// A lower first premolar's view (44: u = x mesial) whose mesial cut runs obliquely,
// u = 2.5 + 0.4 v, its distal one square at u = -3.5, its crown a dome about the middle. The
// mesial contact is the highest cell within 0.5 mm of the cut: where the cut comes nearest the
// dome's top (v = -0.69), not at v = 0 where a band square to the curve at the cut's middle
// (u >= 2.0) is highest.
TEST(ToothCut, ASegmentedToothsContactLiesAtItsObliqueCut) {
  constexpr double kCutU = 2.5, kCutSlope = 0.4, kBandMm = 0.5;
  ToothView view =
      test::SurfaceView(44, io::Jaw::kLower, 3.5 + kCutSlope * 4.0, 4.0, kCutCellMm,
                        [](double u, double v) { return 3.0 - 0.1 * (u * u + v * v); });
  view.s_mid = 0.0;
  view.mesial_sign = 1.0;
  view.u_mesial = kCutU;
  view.u_distal = -3.5;
  view.right_cut = StraightCut(-3.5);
  view.left_cut.t0 = -4.0;
  view.left_cut.step = kCutCellMm;
  for (double v = -4.0; v <= 4.0 + 1e-9; v += kCutCellMm)
    view.left_cut.s.push_back(kCutU + kCutSlope * v);
  for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
    const Eigen::Vector3d& x = view.top_uvw[static_cast<std::size_t>(c)];
    if (x.x() > view.left_cut.At(x.y()) || x.x() < -3.5)
      view.top.height[static_cast<std::size_t>(c)] = std::numeric_limits<double>::quiet_NaN();
  }
  const ArchLandmark* mesial = nullptr;
  const std::vector<ArchLandmark> found = DetectToothLandmarks(view, 1.0);
  for (const ArchLandmark& l : found) {
    if (l.landmark.type == io::LandmarkType::kMesial) mesial = &l;
  }
  ASSERT_NE(mesial, nullptr);
  const Eigen::Vector3d& p = mesial->landmark.p;
  EXPECT_LE(EndU(view, p.y(), true) - p.x(), kBandMm + 1e-9) << p.transpose();
  // The nearest point to the dome's top on the band's inner edge u = 2.0 + 0.4 v.
  EXPECT_NEAR(p.y(), -0.69, 1.5 * kCutCellMm) << p.transpose();
}

}  // namespace
}  // namespace occlude::analysis
