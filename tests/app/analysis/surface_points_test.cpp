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

constexpr double kHalfLengthMm = 5.0, kHalfWidthMm = 4.0;  // the crown's elliptic outline
constexpr double kTableMm = 7.0, kTiltMm = 1.0;  // table height at v = 0, its rise per 4 mm
constexpr double kCuspV = 2.5;                   // the cusp ridges' distance from the groove
constexpr int kRingPoints = 12;
constexpr double kClinicalHalfMm = 0.5 * 0.8 * 7.5;  // lower first molar: 3 mm
constexpr double kPointTolMm = 0.25;                 // a cell or so

// The occlusal table across the arch: tilted, with a cusp ridge 1 mm high on each side.
double Table(double v) {
  const double ridge = std::abs(v) - kCuspV;
  return kTableMm + kTiltMm * v / kHalfWidthMm + std::exp(-ridge * ridge / (2.0 * 0.8 * 0.8)) - 1.0;
}

// The highest point of the table on one side (sign +1 buccal, -1 lingual) of v = 0.
double SideTop(double sign) {
  double top = -std::numeric_limits<double>::infinity();
  for (double v = 0.0; v <= kHalfWidthMm; v += 0.01) top = std::max(top, Table(sign * v));
  return top;
}

// The molar's view: its top (the table inside the outline) and its side surface as quads
// between vertex rings at w = 0, 2.5 and the table's rim, split into triangles.
ToothView TiltedMolar() {
  ToothView view = test::SurfaceView(
      46, io::Jaw::kLower, kHalfLengthMm + 0.4, kHalfWidthMm + 0.4, 0.2, [](double u, double v) {
        const double r = std::hypot(u / kHalfLengthMm, v / kHalfWidthMm);
        return r <= 1.0 ? Table(v) : std::numeric_limits<double>::quiet_NaN();
      });
  view.u_mesial = kHalfLengthMm;
  view.u_distal = -kHalfLengthMm;
  for (int ring = 0; ring < 3; ++ring) {
    for (int k = 0; k < kRingPoints; ++k) {
      const double a = 2.0 * kPi * k / kRingPoints;
      const double u = kHalfLengthMm * std::cos(a), v = kHalfWidthMm * std::sin(a);
      const double w = ring == 2 ? Table(v) : 2.5 * ring;
      view.surface_J.emplace_back(u, v, w);
      view.surface_uvw.emplace_back(u, v, w);
    }
  }
  for (int ring = 0; ring < 2; ++ring) {
    for (int k = 0; k < kRingPoints; ++k) {
      const int a = ring * kRingPoints + k, b = ring * kRingPoints + (k + 1) % kRingPoints;
      view.surface_triangles.push_back({a, b, b + kRingPoints});
      view.surface_triangles.push_back({a, b + kRingPoints, a + kRingPoints});
    }
  }
  return view;
}

const ArchLandmark* Find(const std::vector<ArchLandmark>& found, io::LandmarkType type) {
  for (const ArchLandmark& l : found) {
    if (l.landmark.type == type) return &l;
  }
  return nullptr;
}

TEST(SurfacePoints, HalfTheClinicalCrownBelowEachSidesCuspsBetweenVertices) {
  const std::vector<ArchLandmark> found = DetectToothLandmarks(TiltedMolar(), 1.0);
  const ArchLandmark* facial = Find(found, io::LandmarkType::kFacial);
  const ArchLandmark* lingual = Find(found, io::LandmarkType::kLingual);
  ASSERT_NE(facial, nullptr);
  ASSERT_NE(lingual, nullptr);
  const Eigen::Vector3d want_facial(0.0, kHalfWidthMm, SideTop(1.0) - kClinicalHalfMm);
  const Eigen::Vector3d want_lingual(0.0, -kHalfWidthMm, SideTop(-1.0) - kClinicalHalfMm);
  EXPECT_LT((facial->landmark.p - want_facial).norm(), kPointTolMm)
      << facial->landmark.p.transpose();
  EXPECT_LT((lingual->landmark.p - want_lingual).norm(), kPointTolMm)
      << lingual->landmark.p.transpose();
}

}  // namespace
}  // namespace occlude::analysis
