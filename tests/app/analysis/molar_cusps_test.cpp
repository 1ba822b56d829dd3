// DetectToothLandmarks' molar cusps on analytic crowns seen as a segmented scan's tooth view (cut
// out of the jaw at its boundaries, not a whole crown): tooth coordinates are the 0.2 mm map's
// plane coordinates (u = x mesial, v = y buccal, w = z along the occlusal axis). A slope rising
// on into the neighbour tops out at the cut, a local maximum of the view that is no cusp: the
// mesiobuccal cusp is the real one inside. The lower first molar's buccal cusps fall into their
// slots by Wheeler's widths: the distobuccal one 0.2 of the length distal of the middle is the
// `middle_buccal_cusp`, not the distal cusp. The central fossa is the middle of a flat floor,
// not a shallow pit at its side. An inclined crown's cusps are found above the plane of its
// occlusal table, at their tips.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "analysis/tooth_landmarks.h"
#include "surface_view.h"

namespace occlude::analysis {
namespace {

constexpr double kMolarCellMm = 0.2;
constexpr double kMolarHalfLengthMm = 5.5;  // the cut ends: u = -5.5 (distal) and 5.5 (mesial)
constexpr double kMolarHalfWidthMm = 5.0;
constexpr double kMolarCuspTolMm = 0.3;  // a cusp's peak: within a cell or so of its design

// The segmented view of w = surface(u, v) over the span |u| <= 5.5, |v| <= 5: each cell's height
// the surface at its centre.
ToothView MolarView(int fdi, io::Jaw jaw, const std::function<double(double, double)>& surface) {
  return test::SurfaceView(fdi, jaw, kMolarHalfLengthMm, kMolarHalfWidthMm, kMolarCellMm, surface);
}

// A rounded cusp of height h at (u0, v0), 1.2 mm wide.
double MolarCusp(double u, double v, double u0, double v0, double h) {
  const double r2 = (u - u0) * (u - u0) + (v - v0) * (v - v0);
  return h * std::exp(-r2 / (2.0 * 1.2 * 1.2));
}

const ArchLandmark* FindCusp(const std::vector<ArchLandmark>& landmarks, io::LandmarkType type) {
  for (const ArchLandmark& l : landmarks) {
    if (l.landmark.type == type) return &l;
  }
  return nullptr;
}

// Upper first molar: four cusps 1.5 mm high on a 2 mm base, and from u = 4 mesially the
// neighbour's marginal ridge rising to 3.7 mm at the cut, above the cusps: the view's highest
// point, at its mesial end, is no cusp.
TEST(MolarCusps, AMesiobuccalCuspNotTheSlopeRisingToTheCut) {
  const auto crown = [](double u, double v) {
    const double cusps = MolarCusp(u, v, 2.5, 2.5, 1.5) + MolarCusp(u, v, -2.5, 2.5, 1.5) +
                         MolarCusp(u, v, 2.0, -2.5, 1.5) + MolarCusp(u, v, -2.5, -2.5, 1.5);
    return 2.0 + cusps + (u > 4.0 ? 1.5 * (u - 4.0) : 0.0);
  };
  const std::vector<ArchLandmark> found =
      DetectToothLandmarks(MolarView(16, io::Jaw::kUpper, crown), 1.0);
  const ArchLandmark* mb = FindCusp(found, io::LandmarkType::kMbCusp);
  ASSERT_NE(mb, nullptr);
  EXPECT_NEAR(mb->landmark.p.x(), 2.5, kMolarCuspTolMm) << mb->landmark.p.transpose();
  EXPECT_NEAR(mb->landmark.p.y(), 2.5, kMolarCuspTolMm) << mb->landmark.p.transpose();
}

// Lower first molar, 11 mm: buccal cusps at u_rel 0.27 (mesiobuccal), -0.2 (distobuccal) and
// -0.4 (distal), the distobuccal one the highest; with thirds for slots it would be taken for
// the distal cusp.
TEST(MolarCusps, LowerFirstMolarBuccalCuspsByTheirWidths) {
  const double length = 2.0 * kMolarHalfLengthMm;
  const double mb_u = 0.27 * length, mbc_u = -0.2 * length, db_u = -0.4 * length;
  const auto crown = [&](double u, double v) {
    return 2.0 + MolarCusp(u, v, mb_u, 2.0, 1.2) + MolarCusp(u, v, mbc_u, 2.0, 1.5) +
           MolarCusp(u, v, db_u, 0.5, 1.0) + MolarCusp(u, v, 2.0, -2.5, 1.4) +
           MolarCusp(u, v, -2.5, -2.5, 1.4);
  };
  const std::vector<ArchLandmark> found =
      DetectToothLandmarks(MolarView(46, io::Jaw::kLower, crown), 1.0);
  const ArchLandmark* mb = FindCusp(found, io::LandmarkType::kMbCusp);
  const ArchLandmark* mbc = FindCusp(found, io::LandmarkType::kMiddleBuccalCusp);
  ASSERT_NE(mb, nullptr);
  ASSERT_NE(mbc, nullptr);
  EXPECT_NEAR(mb->landmark.p.x(), mb_u, kMolarCuspTolMm) << mb->landmark.p.transpose();
  EXPECT_NEAR(mbc->landmark.p.x(), mbc_u, kMolarCuspTolMm) << mbc->landmark.p.transpose();
  // The buccal groove (their midpoint), which the molar relationship measures from.
  EXPECT_NEAR(0.5 * (mb->landmark.p.x() + mbc->landmark.p.x()), 0.5 * (mb_u + mbc_u),
              kMolarCuspTolMm);
}

// Lower first molar, 11 mm, whose mesiobuccal cusp is worn into the ridge running down mesially
// from the middle buccal cusp (0.03 mm per mm): its slot (u_rel above 1/6) has no local maximum
// and its highest cell is at the slot's distal end, next to the other cusp. The cusp stands in
// at the highest point of the slot's middle (u_rel 1/3), on the buccal ridge.
TEST(MolarCusps, AWornCuspWithoutAPeakAtItsSlotsMiddle) {
  constexpr double kRidgeV = 2.0;
  const double length = 2.0 * kMolarHalfLengthMm;
  const auto ridge = [](double u) {
    const double cusp = 1.5 * std::exp(-(u + 1.1) * (u + 1.1) / (2.0 * 1.2 * 1.2));
    return u > -1.1 ? std::max(cusp, 1.0 - 0.03 * u) : cusp;
  };
  const auto crown = [&](double u, double v) {
    return 2.0 + ridge(u) * std::exp(-(v - kRidgeV) * (v - kRidgeV) / 2.0) +
           MolarCusp(u, v, 2.0, -2.5, 1.4) + MolarCusp(u, v, -2.5, -2.5, 1.4);
  };
  const std::vector<ArchLandmark> found =
      DetectToothLandmarks(MolarView(46, io::Jaw::kLower, crown), 1.0);
  const ArchLandmark* mb = FindCusp(found, io::LandmarkType::kMbCusp);
  ASSERT_NE(mb, nullptr);
  // The slice is 0.4 mm either side of the middle; on the falling ridge its highest cell is at
  // the slice's distal side.
  EXPECT_NEAR(mb->landmark.p.x(), length / 3.0, 0.5) << mb->landmark.p.transpose();
  EXPECT_NEAR(mb->landmark.p.y(), kRidgeV, kMolarCuspTolMm) << mb->landmark.p.transpose();
  EXPECT_LT(mb->confidence, 0.5);
}

// Upper first molar whose occlusal basin (between four cusps) has a flat floor 3 mm across at
// w = 1, with a pit 0.25 mm deep and 0.8 mm wide at (1.2, 0.4) mm, off its middle: the single
// lowest cell is the pit, the fossa the floor's middle (the crown's middle fifth, 2.2 x 2 mm).
TEST(MolarCusps, CentralFossaTheMiddleOfAFlatFloorNotAPitAtItsSide) {
  constexpr double kFloorMm = 1.0, kPitMm = 0.25, kPitU = 1.2, kPitV = 0.4;
  const auto crown = [&](double u, double v) {
    const double basin = std::max(kFloorMm, 0.4 * std::hypot(u, v) - 0.2);
    const double pit = std::hypot(u - kPitU, v - kPitV) < 0.4 ? kPitMm : 0.0;
    return basin - pit + MolarCusp(u, v, 2.5, 2.5, 1.5) + MolarCusp(u, v, -2.5, 2.5, 1.5) +
           MolarCusp(u, v, 2.0, -2.5, 1.5) + MolarCusp(u, v, -2.5, -2.5, 1.5);
  };
  const std::vector<ArchLandmark> found =
      DetectToothLandmarks(MolarView(16, io::Jaw::kUpper, crown), 1.0);
  const ArchLandmark* fossa = FindCusp(found, io::LandmarkType::kCentralFossa);
  ASSERT_NE(fossa, nullptr);
  EXPECT_LT(fossa->landmark.p.head<2>().norm(), 0.5) << fossa->landmark.p.transpose();
}

// Upper first molar inclined buccally across the arch by 0.3 mm per mm (its buccal cusps 2.4 mm
// above its palatal ones along the occlusal axis, the curve of Wilson), four broad cusps 1 mm
// high: on the view the buccal cusps' local maxima lie 0.8 mm palatal of their tips. Above the
// plane of its occlusal table they are where the tips are.
TEST(MolarCusps, AnInclinedCrownsBuccalCuspAtItsTip) {
  constexpr double kIncline = -0.3, kCuspV = 2.5, kCuspU = 2.5;
  const auto broad = [](double u, double v, double u0, double v0) {
    const double r2 = (u - u0) * (u - u0) + (v - v0) * (v - v0);
    return std::exp(-r2 / (2.0 * 1.5 * 1.5));
  };
  const auto crown = [&](double u, double v) {
    return 3.0 + kIncline * v + broad(u, v, kCuspU, kCuspV) + broad(u, v, -kCuspU, kCuspV) +
           broad(u, v, kCuspU, -kCuspV) + broad(u, v, -kCuspU, -kCuspV);
  };
  const std::vector<ArchLandmark> found =
      DetectToothLandmarks(MolarView(16, io::Jaw::kUpper, crown), 1.0);
  const ArchLandmark* mb = FindCusp(found, io::LandmarkType::kMbCusp);
  ASSERT_NE(mb, nullptr);
  EXPECT_NEAR(mb->landmark.p.x(), kCuspU, kMolarCuspTolMm) << mb->landmark.p.transpose();
  EXPECT_NEAR(mb->landmark.p.y(), kCuspV, kMolarCuspTolMm) << mb->landmark.p.transpose();
  // On the surface: its height there.
  EXPECT_NEAR(mb->landmark.p.z(), crown(mb->landmark.p.x(), mb->landmark.p.y()), 0.1);
}

}  // namespace
}  // namespace occlude::analysis
