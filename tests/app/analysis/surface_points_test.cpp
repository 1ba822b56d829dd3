// DetectToothLandmarks' facial and lingual points on an analytic lower first molar whose side
// surfaces are coarse triangles (rings of vertices 2.5 mm and more apart in height, as on a
// decimated scan): tooth coordinates are the plane coordinates of its 0.2 mm view (u = x
// mesial, v = y buccal, w = z along the occlusal axis). Its occlusal table, a cusp ridge on each
// side of a central groove, tilts lingually (by 2 mm across its width, as lower molars incline),
// so each side's point lies half the clinical crown (0.4 of the typical 7.5 mm) below that side's
// own cusps, where the side surface crosses the crown's middle, between vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/tooth_landmarks.h"
#include "occlude/angles.h"
#include "surface_view.h"

namespace occlude::analysis {
namespace {

constexpr double kSideHalfLengthMm = 5.0, kSideHalfWidthMm = 4.0;  // the crown's elliptic outline
constexpr double kSideTableMm = 7.0, kSideTiltMm = 1.0;  // table height at v = 0, its rise per 4 mm
constexpr double kSideCuspV = 2.5;  // the cusp ridges' distance from the groove
constexpr int kSideRingPoints = 12;
constexpr double kSideClinicalHalfMm = 0.5 * 0.8 * 7.5;  // lower first molar: 3 mm
constexpr double kSidePointTolMm = 0.25;                 // a cell or so

// The occlusal table across the arch: tilted, with a cusp ridge 1 mm high on each side.
double SideTable(double v) {
  const double ridge = std::abs(v) - kSideCuspV;
  return kSideTableMm + kSideTiltMm * v / kSideHalfWidthMm +
         std::exp(-ridge * ridge / (2.0 * 0.8 * 0.8)) - 1.0;
}

// The highest point of the table on one side (sign +1 buccal, -1 lingual) of v = 0.
double SideCuspTop(double sign) {
  double top = -std::numeric_limits<double>::infinity();
  for (double v = 0.0; v <= kSideHalfWidthMm; v += 0.01) top = std::max(top, SideTable(sign * v));
  return top;
}

// The molar's view: its top (the table inside the outline) and its side surface as quads
// between vertex rings at w = 0, 2.5 and the table's rim, split into triangles.
ToothView TiltedMolarView() {
  ToothView view =
      test::SurfaceView(46, io::Jaw::kLower, kSideHalfLengthMm + 0.4, kSideHalfWidthMm + 0.4, 0.2,
                        [](double u, double v) {
                          const double r = std::hypot(u / kSideHalfLengthMm, v / kSideHalfWidthMm);
                          return r <= 1.0 ? SideTable(v) : std::numeric_limits<double>::quiet_NaN();
                        });
  view.u_mesial = kSideHalfLengthMm;
  view.u_distal = -kSideHalfLengthMm;
  for (int ring = 0; ring < 3; ++ring) {
    for (int k = 0; k < kSideRingPoints; ++k) {
      const double a = 2.0 * kPi * k / kSideRingPoints;
      const double u = kSideHalfLengthMm * std::cos(a), v = kSideHalfWidthMm * std::sin(a);
      const double w = ring == 2 ? SideTable(v) : 2.5 * ring;
      view.surface_J.emplace_back(u, v, w);
      view.surface_uvw.emplace_back(u, v, w);
    }
  }
  for (int ring = 0; ring < 2; ++ring) {
    for (int k = 0; k < kSideRingPoints; ++k) {
      const int a = ring * kSideRingPoints + k,
                b = ring * kSideRingPoints + (k + 1) % kSideRingPoints;
      view.surface_triangles.push_back({a, b, b + kSideRingPoints});
      view.surface_triangles.push_back({a, b + kSideRingPoints, a + kSideRingPoints});
    }
  }
  return view;
}

const ArchLandmark* FindSurfacePoint(const std::vector<ArchLandmark>& found,
                                     io::LandmarkType type) {
  for (const ArchLandmark& l : found) {
    if (l.landmark.type == type) return &l;
  }
  return nullptr;
}

TEST(SurfacePoints, HalfTheClinicalCrownBelowEachSidesCuspsBetweenVertices) {
  const std::vector<ArchLandmark> found = DetectToothLandmarks(TiltedMolarView(), 1.0);
  const ArchLandmark* facial = FindSurfacePoint(found, io::LandmarkType::kFacial);
  const ArchLandmark* lingual = FindSurfacePoint(found, io::LandmarkType::kLingual);
  ASSERT_NE(facial, nullptr);
  ASSERT_NE(lingual, nullptr);
  const Eigen::Vector3d want_facial(0.0, kSideHalfWidthMm, SideCuspTop(1.0) - kSideClinicalHalfMm);
  const Eigen::Vector3d want_lingual(0.0, -kSideHalfWidthMm,
                                     SideCuspTop(-1.0) - kSideClinicalHalfMm);
  EXPECT_LT((facial->landmark.p - want_facial).norm(), kSidePointTolMm)
      << facial->landmark.p.transpose();
  EXPECT_LT((lingual->landmark.p - want_lingual).norm(), kSidePointTolMm)
      << lingual->landmark.p.transpose();
}

}  // namespace
}  // namespace occlude::analysis
