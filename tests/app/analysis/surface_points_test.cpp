// DetectToothLandmarks' facial and lingual points on an analytic lower first molar whose side
// surfaces are coarse triangles (rings of vertices 2.5 mm and more apart in height, as on a
// decimated scan): tooth coordinates are the plane coordinates of its 0.2 mm view (u = x
// mesial, v = y buccal, w = z along the occlusal axis). Its occlusal table, a cusp ridge on each
// side of a central groove, tilts lingually (by 2 mm across its width, as lower molars incline),
// so each side's point lies half the clinical crown (0.4 of the typical 7.5 mm) below that side's
// own cusps, where the side surface crosses the crown's middle, between vertices; on a line across
// turned square to the row of teeth when that runs turned from the curve (SetArchSlopes, whose
// slopes come from the neighbours' crown centres).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/arch_curve.h"
#include "analysis/arch_geometry.h"
#include "analysis/tooth_landmarks.h"
#include "analysis/tooth_view.h"
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

// The row of teeth turned from the curve (SetArchSlopes gives the tooth's arch_slope, dv/du): the
// line across the crown is square to the row, so at slope 0.25 (14 deg) the facial point lies
// distal and the lingual point mesial of the crown's middle by 0.25 of half the crown's width
// (3.2-4 mm: the middle 90 % of its cells across), on the crown's surface as before.
TEST(SurfacePoints, TheLineAcrossIsSquareToTheRowOfTeethNotToTheCurve) {
  constexpr double kSlope = 0.25;
  ToothView view = TiltedMolarView();
  view.arch_slope = kSlope;
  const std::vector<ArchLandmark> found = DetectToothLandmarks(view, 1.0);
  const ArchLandmark* facial = FindSurfacePoint(found, io::LandmarkType::kFacial);
  const ArchLandmark* lingual = FindSurfacePoint(found, io::LandmarkType::kLingual);
  ASSERT_NE(facial, nullptr);
  ASSERT_NE(lingual, nullptr);
  const Eigen::Vector3d& f = facial->landmark.p;
  const Eigen::Vector3d& l = lingual->landmark.p;
  EXPECT_GT(f.x(), -kSlope * kSideHalfWidthMm - 1e-9) << f.transpose();
  EXPECT_LT(f.x(), -kSlope * 0.8 * kSideHalfWidthMm) << f.transpose();
  EXPECT_LT(l.x(), kSlope * kSideHalfWidthMm + 1e-9) << l.transpose();
  EXPECT_GT(l.x(), kSlope * 0.8 * kSideHalfWidthMm) << l.transpose();
  // On the crown's elliptic side surface (between its vertex rings: within a few tenths).
  for (const Eigen::Vector3d& p : {f, l}) {
    EXPECT_NEAR(std::hypot(p.x() / kSideHalfLengthMm, p.y() / kSideHalfWidthMm), 1.0, 0.05)
        << p.transpose();
  }
  EXPECT_NEAR(f.z(), SideCuspTop(1.0) - kSideClinicalHalfMm, kSidePointTolMm) << f.transpose();
  EXPECT_NEAR(l.z(), SideCuspTop(-1.0) - kSideClinicalHalfMm, kSidePointTolMm) << l.transpose();
}

// SetArchSlopes on dome crowns along a straight curve (v = y, u along x towards each tooth's
// mesial): a crown between neighbours whose centres step 1 mm across per 8 mm along the arch has
// the row's slope 1/8, one at the end of the row from its own centre and its one neighbour's; a
// crown whose neighbours stand on the curve has none; a crown without neighbours keeps 0.
TEST(SurfacePoints, ArchSlopesFromTheNeighboursCrownCentres) {
  ArchGeometry g;
  g.curve.step = 0.25;
  g.curve.centre = {0.0, -1000.0};  // far inside: the polar angles of the stations decrease
  for (double x = -30.0; x <= 30.0 + 1e-9; x += g.curve.step) {
    g.curve.q.emplace_back(x, 0.0);
    g.curve.top.push_back(5.0);
    g.curve.angle.push_back(ArchAngle(g.curve.centre, g.curve.q.back()));
  }
  const auto crown = [](int fdi, double x0, double y0) {
    ToothView view = test::SurfaceView(fdi, io::Jaw::kLower, 3.6, 3.6, 0.2, [](double u, double v) {
      return std::hypot(u, v) <= 3.5 ? 5.0 - 0.1 * (u * u + v * v)
                                     : std::numeric_limits<double>::quiet_NaN();
    });
    view.top.corner += Eigen::Vector2d(x0, y0);
    view.s_mid = x0 + 30.0;
    view.mesial_sign = MesialSign(fdi);
    return view;
  };
  // Right to left (x to the patient's left): 44-41 mesial towards +x (u = x - x0), 31 towards -x.
  std::vector<ToothView> views = {crown(44, -24.0, 0.0), crown(43, -16.0, -1.0),
                                  crown(42, -8.0, 0.0),  crown(41, 0.0, 1.0),
                                  crown(31, 8.0, 2.0),   crown(35, 20.0, 0.0)};
  SetArchSlopes(g, {true, true, true, true, false}, &views);
  // 44 and 43: from the centre of 44 (x -24, y 0) to that of 43 (-16, -1), resp. 42 (-8, 0).
  EXPECT_NEAR(views[0].arch_slope, -0.125, 1e-6);
  EXPECT_NEAR(views[1].arch_slope, 0.0, 1e-9);
  // 42: from 43 (-16, -1) to 41 (0, 1): v rises 2 mm over 16 mm of u.
  EXPECT_NEAR(views[2].arch_slope, 0.125, 1e-6);
  // 41: from 42 (-8, 0) to 31 (8, 2).
  EXPECT_NEAR(views[3].arch_slope, 0.125, 1e-6);
  // 31 (u = 8 - x): from 41 (0, 1) to itself (8, 2): u falls 8 mm while v rises 1 mm.
  EXPECT_NEAR(views[4].arch_slope, -0.125, 1e-6);
  // 35: no neighbour.
  EXPECT_EQ(views[5].arch_slope, 0.0);
}

}  // namespace
}  // namespace occlude::analysis
