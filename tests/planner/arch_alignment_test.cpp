// The coarse alignment of two arches against analytic answers (an upper arch
// built as the lower's curve offset outward by the overjet and lowered by the
// overbite, then expressed in an arbitrary frame U), the curve fit correcting a
// frame's yaw error, the shift between poses, the rejection of arches that
// cannot face each other, and the tooth-point stand-in on the synthetic pair.
#include "occlude/planner/arch_alignment.h"

#include <gtest/gtest.h>

#include <cmath>

#include "occlude/angles.h"
#include "planner_fixture.h"

namespace occlude::planner {
namespace {

// The lower arch's design: a horseshoe w = -k u^2 (incisors at u = 0) in the plane of an
// arbitrary frame, 41 points from the right (u < 0) to the left.
constexpr double kHalfWidthMm = 25.0, kCurvature = 0.06;
constexpr double kOverjetMm = 2.0, kOverbiteMm = 2.0;
// Alignment of exact curves: only the polyline's discretization of the offset curve remains.
constexpr double kExactAlignMm = 0.02, kExactAlignDeg = 0.05;

struct Frame {
  Eigen::Vector3d origin, occlusal, anterior, lateral;
};

// An arbitrary lower frame: x left, y anterior, occlusal = anterior x lateral (the physical
// handedness, see JawArch), turned and moved.
Frame LowerFrame() {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Frame f;
  f.origin = Eigen::Vector3d(4.0, -7.0, 12.0);
  f.lateral = R * Eigen::Vector3d::UnitX();
  f.anterior = R * Eigen::Vector3d::UnitY();
  f.occlusal = f.anterior.cross(f.lateral);
  return f;
}

// Point of the horseshoe at u, `out` mm outward along its normal and `down` mm along -occlusal.
Eigen::Vector3d ArchPoint(const Frame& f, double u, double out, double down) {
  const double w = -kCurvature * u * u;
  const Eigen::Vector2d normal = Eigen::Vector2d(2.0 * kCurvature * u, 1.0).normalized();
  const Eigen::Vector2d q = Eigen::Vector2d(u, w) + out * normal;
  return f.origin + q.x() * f.lateral + q.y() * f.anterior - down * f.occlusal;
}

JawArch LowerArch() {
  const Frame f = LowerFrame();
  JawArch a;
  a.origin_J = f.origin;
  a.occlusal_J = f.occlusal;
  a.anterior_J = f.anterior;
  a.lateral_J = f.lateral;
  for (int i = -20; i <= 20; ++i) a.curve_J.push_back(ArchPoint(f, kHalfWidthMm * i / 20.0, 0, 0));
  return a;
}

// The upper arch at the target relation, in L: the offset curve, its incisal point overjet
// ahead and overbite below, axes facing.
JawArch UpperArchInL() {
  const Frame f = LowerFrame();
  JawArch a;
  a.origin_J = ArchPoint(f, 0.0, kOverjetMm, kOverbiteMm);
  a.occlusal_J = -f.occlusal;
  a.anterior_J = f.anterior;
  a.lateral_J = f.lateral;
  for (int i = -20; i <= 20; ++i)
    a.curve_J.push_back(ArchPoint(f, kHalfWidthMm * i / 20.0, kOverjetMm, kOverbiteMm));
  return a;
}

JawArch Moved(const JawArch& a, const Eigen::Isometry3d& X) {
  JawArch m = a;
  m.origin_J = X * a.origin_J;
  m.occlusal_J = X.linear() * a.occlusal_J;
  m.anterior_J = X.linear() * a.anterior_J;
  m.lateral_J = X.linear() * a.lateral_J;
  for (auto& p : m.curve_J) p = X * p;
  return m;
}

// X_LU of the target: U an arbitrary frame (the upper arch given in it).
Eigen::Isometry3d TargetPose() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(2.1, Eigen::Vector3d(-1, 0.4, 2).normalized()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(30.0, -45.0, 8.0);
  return X;
}

double LargestMove(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const JawArch& u) {
  double d = 0.0;
  for (const auto& p : u.curve_J) d = std::max(d, (a * p - b * p).norm());
  return d;
}

double AngleDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return DegreesFromRadians(
      Eigen::AngleAxisd(Eigen::Matrix3d(a.linear() * b.linear().transpose())).angle());
}

TEST(AlignArchesTest, RecoversTheKnownRelativePose) {
  const Eigen::Isometry3d X_LU = TargetPose();
  const JawArch upper_U = Moved(UpperArchInL(), X_LU.inverse());
  const ArchAlignment a = AlignArches(LowerArch(), upper_U);
  EXPECT_LE(LargestMove(a.X_LU, X_LU, upper_U), kExactAlignMm);
  EXPECT_LE(AngleDeg(a.X_LU, X_LU), kExactAlignDeg);
  EXPECT_LE(LargestMove(a.X_LU_frames, X_LU, upper_U), 1e-9);  // the frames alone are exact
  EXPECT_LE(a.fit_rms_mm, kExactAlignMm);
  EXPECT_TRUE(a.warnings.empty());
}

// The upper arch of an analysis whose anterior axis is `yaw_error_deg` off in its occlusal
// plane (the curve itself exact), in U.
JawArch UpperArchWithYawError(double yaw_error_deg) {
  JawArch upper_L = UpperArchInL();
  const Eigen::AngleAxisd yaw(RadiansFromDegrees(yaw_error_deg), upper_L.occlusal_J);
  upper_L.anterior_J = yaw * upper_L.anterior_J;
  upper_L.lateral_J = yaw * upper_L.lateral_J;
  return Moved(upper_L, TargetPose().inverse());
}

// The frames' alignment inherits a yaw error of the analysis, the curve fit takes it out: 4 deg,
// and 12 deg (c2-ios: the frames 9 deg off, the fit's -10.2 deg beyond the old 10 deg limit).
TEST(AlignArchesTest, CurveFitCorrectsAYawErrorOfTheFrames) {
  constexpr double kAfterFitDeg = 0.5, kAfterFitMm = 0.5;
  const Eigen::Isometry3d X_LU = TargetPose();
  for (const double yaw_error_deg : {4.0, 12.0}) {
    const JawArch upper_U = UpperArchWithYawError(yaw_error_deg);
    const ArchAlignment a = AlignArches(LowerArch(), upper_U);
    EXPECT_NEAR(AngleDeg(a.X_LU_frames, X_LU), yaw_error_deg, 1e-6);
    EXPECT_LE(AngleDeg(a.X_LU, X_LU), kAfterFitDeg) << yaw_error_deg;
    EXPECT_LE(LargestMove(a.X_LU, X_LU, upper_U), kAfterFitMm) << yaw_error_deg;
    EXPECT_NEAR(std::abs(a.fit_yaw_deg), yaw_error_deg, kAfterFitDeg);
    EXPECT_LT(a.fit_rms_mm, a.fit_rms_before_mm);
    EXPECT_TRUE(a.warnings.empty()) << yaw_error_deg;
    AlignmentSettings frames_only;
    frames_only.fit_curves = false;
    EXPECT_TRUE(AlignArches(LowerArch(), upper_U, frames_only).X_LU.isApprox(a.X_LU_frames));
  }
}

// A fit that would turn the upper farther than max_fit_yaw_deg is not trusted: the frames'
// alignment is kept, with a warning naming the limit.
TEST(AlignArchesTest, AFitBeyondTheYawLimitKeepsTheFramesAndWarns) {
  const JawArch upper_U = UpperArchWithYawError(12.0);
  AlignmentSettings strict;
  strict.max_fit_yaw_deg = 8.0;
  const ArchAlignment a = AlignArches(LowerArch(), upper_U, strict);
  EXPECT_TRUE(a.X_LU.isApprox(a.X_LU_frames));
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_NE(a.warnings[0].find("kept the frames' alignment"), std::string::npos) << a.warnings[0];
  EXPECT_NE(a.warnings[0].find("8.0 deg"), std::string::npos) << a.warnings[0];
}

// Overjet and overbite are what the aligned incisal points show.
TEST(AlignArchesTest, PlacesTheIncisalPointsTheSettingsApart) {
  AlignmentSettings s;
  s.overjet_mm = 3.0;
  s.overbite_mm = 1.0;
  s.fit_curves = false;
  const JawArch lower = LowerArch();
  const JawArch upper_U = Moved(UpperArchInL(), TargetPose().inverse());
  const ArchAlignment a = AlignArches(lower, upper_U, s);
  const Eigen::Vector3d d = a.X_LU * upper_U.origin_J - lower.origin_J;
  EXPECT_NEAR(d.dot(lower.anterior_J), 3.0, 1e-9);
  EXPECT_NEAR(-d.dot(lower.occlusal_J), 1.0, 1e-9);
  EXPECT_NEAR(d.dot(lower.lateral_J), 0.0, 1e-9);
  EXPECT_NEAR((a.X_LU.linear() * upper_U.occlusal_J).dot(lower.occlusal_J), -1.0, 1e-12);
}

TEST(ArchShiftTest, AnalyticShiftsAndRoundTrip) {
  const JawArch lower = LowerArch();
  const Eigen::Isometry3d X0 = TargetPose();
  const Eigen::Vector3d pivot(1.0, 2.0, 3.0);
  Eigen::Isometry3d X1 = X0;
  X1.pretranslate(5.0 * lower.anterior_J - 1.5 * lower.lateral_J);
  const ArchShift s = ShiftBetween(X0, X1, pivot, lower);
  EXPECT_NEAR(s.sagittal_mm, 5.0, 1e-9);
  EXPECT_NEAR(s.lateral_mm, -1.5, 1e-9);
  EXPECT_NEAR(s.vertical_mm, 0.0, 1e-9);
  EXPECT_NEAR(s.yaw_deg, 0.0, 1e-9);
  ArchShift turn;
  turn.yaw_deg = 7.0;
  turn.pitch_deg = -2.0;
  turn.sagittal_mm = -3.0;
  const Eigen::Isometry3d X2 = ApplyShift(X0, turn, pivot, lower);
  const ArchShift back = ShiftBetween(X0, X2, pivot, lower);
  EXPECT_NEAR(back.yaw_deg, 7.0, 1e-9);
  EXPECT_NEAR(back.pitch_deg, -2.0, 1e-9);
  EXPECT_NEAR(back.roll_deg, 0.0, 1e-9);
  EXPECT_NEAR(back.sagittal_mm, -3.0, 1e-9);
  EXPECT_NEAR((X2 * X0.inverse() * pivot - pivot).dot(lower.anterior_J), -3.0, 1e-9);
}

void ExpectRejected(const JawArch& lower, const JawArch& upper, const std::string& words) {
  try {
    AlignArches(lower, upper);
    ADD_FAILURE() << "accepted; expected an error naming '" << words << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(AlignArchesTest, RejectsArchesThatCannotFaceEachOther) {
  const JawArch lower = LowerArch();
  const JawArch upper = UpperArchInL();
  ExpectRejected(lower, lower, "cannot face each other");  // the lower given as the upper
  JawArch mirrored = upper;
  mirrored.lateral_J = -mirrored.lateral_J;
  ExpectRejected(lower, mirrored, "cannot face each other");
  JawArch reversed = upper;
  reversed.occlusal_J = -reversed.occlusal_J;  // pointing into its crowns
  ExpectRejected(lower, reversed, "cannot face each other");
  JawArch bad = upper;
  bad.anterior_J *= 2.0;
  ExpectRejected(lower, bad, "upper arch: anterior_J: must be a unit vector");
  bad = upper;
  bad.anterior_J = (bad.anterior_J + 0.3 * bad.occlusal_J).normalized();
  ExpectRejected(lower, bad, "must be orthogonal");
  bad = upper;
  bad.curve_J.resize(3);
  ExpectRejected(lower, bad, "curve_J: needs at least 4 points");
  bad = lower;
  bad.origin_J.x() = std::nan("");
  ExpectRejected(bad, upper, "lower arch: origin_J and the axes must be finite");
  AlignmentSettings s;
  s.overjet_mm = -1.0;
  EXPECT_THROW(AlignArches(lower, upper, s), std::invalid_argument);
}

// The stand-in arch analysis on the synthetic pair's tooth parts agrees with the design (L: x
// left, y occlusal, z anterior; U parallel to L at the bite), and its two arches face.
TEST(JawArchFromTeethTest, SyntheticPairMatchesItsDesign) {
  constexpr double kAxisDeg = 3.0, kMidlineMm = 0.3;
  const auto& c = test::Synthetic();
  const JawArch lower = JawArchFromTeeth(ToothTops(c.pair.lower_L, Eigen::Vector3d::UnitY()),
                                         Eigen::Vector3d::UnitY());
  const JawArch upper = JawArchFromTeeth(ToothTops(c.pair.upper_U, -Eigen::Vector3d::UnitY()),
                                         -Eigen::Vector3d::UnitY());
  auto deg = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return DegreesFromRadians(std::acos(std::clamp(a.dot(b), -1.0, 1.0)));
  };
  EXPECT_LE(deg(lower.occlusal_J, Eigen::Vector3d::UnitY()), kAxisDeg);
  EXPECT_LE(deg(lower.anterior_J, Eigen::Vector3d::UnitZ()), kAxisDeg);
  EXPECT_LE(deg(lower.lateral_J, Eigen::Vector3d::UnitX()), kAxisDeg);
  EXPECT_LE(deg(upper.occlusal_J, -Eigen::Vector3d::UnitY()), kAxisDeg);
  EXPECT_LE(deg(upper.anterior_J, Eigen::Vector3d::UnitZ()), kAxisDeg);
  EXPECT_LE(deg(upper.lateral_J, Eigen::Vector3d::UnitX()), kAxisDeg);
  EXPECT_LE(std::abs(lower.origin_J.x()), kMidlineMm);
  EXPECT_LE(std::abs(upper.origin_J.x()), kMidlineMm);
  EXPECT_EQ(lower.curve_J.size(), 14u);
  EXPECT_LT(lower.curve_J.front().x(), 0.0);  // right to left
  EXPECT_NO_THROW(ValidateJawArches(lower, upper));
  // At the designed bite the upper incisal point is ahead of the lower's (overjet).
  EXPECT_GT((c.pair.X_LU * upper.origin_J - lower.origin_J).z(), 0.5);
}

TEST(JawArchFromTeethTest, RejectsTooFewTeethOrOneSide) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  std::vector<ToothPoint> right = {{41, {-1, 0, 20}},
                                   {42, {-5, 0, 18}},
                                   {43, {-9, 0, 15}},
                                   {44, {-13, 0, 10}},
                                   {46, {-20, 0, 0}}};
  EXPECT_THROW(JawArchFromTeeth(right, up), std::invalid_argument);  // one side only
  std::vector<ToothPoint> few = {{41, {-1, 0, 20}}, {31, {1, 0, 20}}, {46, {-20, 0, 0}}};
  EXPECT_THROW(JawArchFromTeeth(few, up), std::invalid_argument);
  std::vector<ToothPoint> mixed = right;
  mixed.push_back({21, {1, 0, 20}});  // an upper tooth among lower ones
  EXPECT_THROW(JawArchFromTeeth(mixed, up), std::invalid_argument);
}

}  // namespace
}  // namespace occlude::planner
