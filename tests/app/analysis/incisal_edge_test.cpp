// DetectToothLandmarks' incisal edge on an analytic incisor seen as a segmented scan's tooth
// view: tooth coordinates are the 0.2 mm map's plane coordinates (u = x mesial, v = y labial,
// w = z along the occlusal axis). The edge is the middle of the crown's span along the arch,
// also when it slopes towards one corner (its highest cells all at that end).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "analysis/tooth_landmarks.h"
#include "surface_view.h"

namespace occlude::analysis {
namespace {

constexpr double kIncisorCellMm = 0.2;
constexpr double kIncisorHalfLengthMm = 4.0;  // the span: u from -4 (distal) to 4 (mesial)
constexpr double kIncisorHalfWidthMm = 3.5;
// The slice is a tenth of the length either side of the middle; the highest cells of a slice
// on a slope sit towards its higher end, at most 0.8 mm off the middle.
constexpr double kIncisorEdgeTolMm = 0.5;

ToothView IncisorView(int fdi, io::Jaw jaw, const std::function<double(double, double)>& surface) {
  return test::SurfaceView(fdi, jaw, kIncisorHalfLengthMm, kIncisorHalfWidthMm, kIncisorCellMm,
                           surface);
}

// An upper central incisor whose edge (a ridge along v = 0.5, falling 1.5 mm per mm across)
// rises by 0.15 mm per mm towards its mesial corner: its cells within 0.5 mm of the top span
// u = 0.7 to 4, whose middle is 2.3 mm mesial of the crown's.
TEST(IncisalEdge, MiddleOfTheSpanOnAnEdgeSlopingToOneCorner) {
  constexpr double kSlope = 0.15, kRidgeV = 0.5;
  const auto crown = [&](double u, double v) {
    return 5.0 + kSlope * u - 1.5 * std::abs(v - kRidgeV);
  };
  const std::vector<ArchLandmark> found =
      DetectToothLandmarks(IncisorView(11, io::Jaw::kUpper, crown), 1.0);
  const ArchLandmark* edge = nullptr;
  for (const ArchLandmark& l : found) {
    if (l.landmark.type == io::LandmarkType::kIncisalEdge) edge = &l;
  }
  ASSERT_NE(edge, nullptr);
  EXPECT_NEAR(edge->landmark.p.x(), 0.0, kIncisorEdgeTolMm) << edge->landmark.p.transpose();
  EXPECT_NEAR(edge->landmark.p.y(), kRidgeV, 2.0 * kIncisorCellMm) << edge->landmark.p.transpose();
  EXPECT_NEAR(edge->landmark.p.z(), 5.0 + kSlope * edge->landmark.p.x(), 2.0 * kIncisorCellMm);
}

}  // namespace
}  // namespace occlude::analysis
