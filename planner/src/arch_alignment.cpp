// The coarse alignment of two arches: the frames matched (occlusal planes
// facing, anterior and lateral directions matched, the incisal points a
// typical overjet and overbite apart), then a 2-D point-to-curve fit of the
// upper curve onto the lower curve offset outward by the overjet (lateral,
// anterior, yaw), held to the incisal relationship by a soft prior; and the
// shift between two poses in the lower's arch frame.
#include "occlude/planner/arch_alignment.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "occlude/angles.h"
#include "occlude/planner/pose.h"

namespace occlude::planner {
namespace {

constexpr double kAxisTolerance = 0.05;  // unit length and orthogonality of an arch's axes
constexpr std::size_t kMinCurvePoints = 4;
constexpr int kFitIterations = 12;
constexpr double kRadPerDeg = RadiansFromDegrees(1.0);

// The arch's axes made exactly orthonormal: occlusal kept, anterior projected into its plane,
// lateral = side * occlusal x anterior with side the sign the given lateral has.
struct Axes {
  Eigen::Vector3d occlusal, anterior, lateral;
  double side = 1.0;
};

Axes Orthonormal(const JawArch& a) {
  Axes x;
  x.occlusal = a.occlusal_J.normalized();
  x.anterior = (a.anterior_J - a.anterior_J.dot(x.occlusal) * x.occlusal).normalized();
  const Eigen::Vector3d left = x.occlusal.cross(x.anterior);
  x.side = left.dot(a.lateral_J) >= 0.0 ? 1.0 : -1.0;
  x.lateral = x.side * left;
  return x;
}

void CheckArch(const JawArch& a, const std::string& name) {
  auto fail = [&](const std::string& what) {
    throw std::invalid_argument(name + " arch: " + what);
  };
  const bool finite = a.origin_J.allFinite() && a.occlusal_J.allFinite() &&
                      a.anterior_J.allFinite() && a.lateral_J.allFinite();
  if (!finite) fail("origin_J and the axes must be finite");
  for (const auto& p : a.curve_J) {
    if (!p.allFinite()) fail("curve_J: every point must be finite");
  }
  const Eigen::Vector3d* axes[3] = {&a.occlusal_J, &a.anterior_J, &a.lateral_J};
  const char* names[3] = {"occlusal_J", "anterior_J", "lateral_J"};
  for (int i = 0; i < 3; ++i) {
    if (std::abs(axes[i]->norm() - 1.0) > kAxisTolerance) {
      fail(std::string(names[i]) + ": must be a unit vector (length " +
           std::to_string(axes[i]->norm()) + ")");
    }
    for (int j = i + 1; j < 3; ++j) {
      if (std::abs(axes[i]->dot(*axes[j])) > kAxisTolerance) {
        fail(std::string(names[i]) + " and " + names[j] + ": must be orthogonal (cosine " +
             std::to_string(axes[i]->dot(*axes[j])) + ")");
      }
    }
  }
  if (a.curve_J.size() < kMinCurvePoints) {
    fail("curve_J: needs at least " + std::to_string(kMinCurvePoints) + " points (has " +
         std::to_string(a.curve_J.size()) + "); no teeth found?");
  }
}

}  // namespace

void ValidateJawArches(const JawArch& lower_L, const JawArch& upper_U) {
  CheckArch(lower_L, "lower");
  CheckArch(upper_U, "upper");
  // The lower's (lateral, anterior, occlusal) and the upper's (lateral, anterior, -occlusal)
  // must have the same handedness, or no rotation makes both occlusal planes face each other
  // with both midlines and both left sides matched.
  const double lower_hand = lower_L.lateral_J.cross(lower_L.anterior_J).dot(lower_L.occlusal_J);
  const double upper_hand = upper_U.lateral_J.cross(upper_U.anterior_J).dot(-upper_U.occlusal_J);
  if (lower_hand * upper_hand <= 0.0) {
    throw std::invalid_argument(
        "upper arch: its (lateral, anterior, occlusal) has the handedness of the lower's, so the "
        "arches cannot face each other with matched sides: the same jaw given twice (an upper as "
        "a lower), one jaw mirrored, or its occlusal_J pointing into its crowns; check which mesh "
        "is which and that occlusal_J points out of each jaw's crowns");
  }
}

namespace {

// Rotation taking the upper's arch axes (lateral, anterior, -occlusal) in U onto the lower's
// (lateral, anterior, occlusal) in L.
Eigen::Matrix3d FacingRotation(const Axes& lower, const Axes& upper) {
  Eigen::Matrix3d B_L, B_U;
  B_L << lower.lateral, lower.anterior, lower.occlusal;
  B_U << upper.lateral, upper.anterior, -upper.occlusal;
  return B_L * B_U.transpose();
}

// A curve in the lower's occlusal plane (u lateral, w anterior, about the lower origin).
std::vector<Eigen::Vector2d> PlaneCurve(const std::vector<Eigen::Vector3d>& curve_L,
                                        const Axes& lower, const Eigen::Vector3d& origin_L) {
  std::vector<Eigen::Vector2d> c;
  c.reserve(curve_L.size());
  for (const auto& p : curve_L)
    c.emplace_back((p - origin_L).dot(lower.lateral), (p - origin_L).dot(lower.anterior));
  return c;
}

// The lower curve moved outward (away from the arch's inside) by `offset` per vertex: the
// outward normal is the tangent (right to left) turned towards +w at the incisors.
std::vector<Eigen::Vector2d> OffsetCurve(const std::vector<Eigen::Vector2d>& c, double offset) {
  std::vector<Eigen::Vector2d> out(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) {
    const Eigen::Vector2d t = c[std::min(i + 1, c.size() - 1)] - c[i == 0 ? 0 : i - 1];
    const Eigen::Vector2d n = Eigen::Vector2d(-t.y(), t.x()).normalized();
    out[i] = c[i] + offset * (n.allFinite() ? n : Eigen::Vector2d::Zero());
  }
  return out;
}

// Closest point of the polyline to q, and the unit normal of its segment there (zero when the
// closest point is an end of the polyline: such points do not constrain the fit).
void ClosestOnPolyline(const std::vector<Eigen::Vector2d>& c, const Eigen::Vector2d& q,
                       Eigen::Vector2d* closest, Eigen::Vector2d* normal) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < c.size(); ++i) {
    const Eigen::Vector2d d = c[i + 1] - c[i];
    const double len2 = d.squaredNorm();
    const double s = len2 > 0.0 ? std::clamp((q - c[i]).dot(d) / len2, 0.0, 1.0) : 0.0;
    const Eigen::Vector2d p = c[i] + s * d;
    if ((q - p).squaredNorm() >= best) continue;
    best = (q - p).squaredNorm();
    *closest = p;
    const bool end = (i == 0 && s == 0.0) || (i + 2 == c.size() && s == 1.0);
    *normal = end || len2 == 0.0
                  ? Eigen::Vector2d::Zero()
                  : Eigen::Vector2d(Eigen::Vector2d(-d.y(), d.x()) / std::sqrt(len2));
  }
}

// 2-D rigid motion (u, w, yaw rad) applied about the incisal target `centre`.
Eigen::Vector2d Move(const Eigen::Vector3d& m, const Eigen::Vector2d& centre,
                     const Eigen::Vector2d& p) {
  const double c = std::cos(m.z()), s = std::sin(m.z());
  const Eigen::Vector2d r = p - centre;
  return centre + Eigen::Vector2d(c * r.x() - s * r.y(), s * r.x() + c * r.y()) + m.head<2>();
}

double RmsToCurve(const std::vector<Eigen::Vector2d>& target,
                  const std::vector<Eigen::Vector2d>& moving) {
  double sum = 0.0;
  for (const auto& q : moving) {
    Eigen::Vector2d p, n;
    ClosestOnPolyline(target, q, &p, &n);
    sum += (q - p).squaredNorm();
  }
  return moving.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(moving.size()));
}

// Gauss-Newton on point-to-line distances of the upper curve to the offset lower curve, with
// the incisal point held near its target by a prior worth a quarter of the curve points.
Eigen::Vector3d FitCurves(const std::vector<Eigen::Vector2d>& target,
                          const std::vector<Eigen::Vector2d>& upper,
                          const Eigen::Vector2d& incisal) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  const double prior = std::sqrt(0.25 * static_cast<double>(upper.size()));
  for (int it = 0; it < kFitIterations; ++it) {
    Eigen::Matrix3d H = prior * prior * Eigen::Matrix3d::Identity();
    H(2, 2) = 0.0;
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    g.head<2>() = prior * prior * m.head<2>();
    for (const auto& p : upper) {
      const Eigen::Vector2d q = Move(m, incisal, p);
      Eigen::Vector2d c, n;
      ClosestOnPolyline(target, q, &c, &n);
      if (n.squaredNorm() == 0.0) continue;
      const Eigen::Vector2d r = q - incisal - m.head<2>();  // rotated arm about the centre
      const Eigen::Vector3d J(n.x(), n.y(), n.dot(Eigen::Vector2d(-r.y(), r.x())));
      H += J * J.transpose();
      g += J * n.dot(q - c);
    }
    H(2, 2) += 1e-6;
    const Eigen::Vector3d step = -H.ldlt().solve(g);
    if (!step.allFinite()) break;
    m += step;
    if (step.head<2>().norm() < 1e-4 && std::abs(step.z()) < 1e-6) break;
  }
  return m;
}

void CheckSettings(const AlignmentSettings& s) {
  auto check = [](double v, const char* name) {
    if (!(std::isfinite(v) && v >= 0.0)) {
      throw std::invalid_argument(std::string("AlignmentSettings.") + name +
                                  ": must be finite and >= 0");
    }
  };
  check(s.overjet_mm, "overjet_mm (default 2)");
  check(s.overbite_mm, "overbite_mm (default 2)");
  check(s.max_fit_shift_mm, "max_fit_shift_mm (default 6)");
  check(s.max_fit_yaw_deg, "max_fit_yaw_deg (default 15)");
}

}  // namespace

ArchAlignment AlignArches(const JawArch& lower_L, const JawArch& upper_U,
                          const AlignmentSettings& settings) {
  ValidateJawArches(lower_L, upper_U);
  CheckSettings(settings);
  const Axes lower = Orthonormal(lower_L), upper = Orthonormal(upper_U);
  ArchAlignment a;
  const Eigen::Matrix3d R = FacingRotation(lower, upper);
  const Eigen::Vector3d target_L = lower_L.origin_J + settings.overjet_mm * lower.anterior -
                                   settings.overbite_mm * lower.occlusal;
  a.X_LU_frames.linear() = R;
  a.X_LU_frames.translation() = target_L - R * upper_U.origin_J;
  a.X_LU = a.X_LU_frames;
  std::vector<Eigen::Vector3d> upper_L;
  for (const auto& p : upper_U.curve_J) upper_L.push_back(a.X_LU_frames * p);
  const std::vector<Eigen::Vector2d> target =
      OffsetCurve(PlaneCurve(lower_L.curve_J, lower, lower_L.origin_J), settings.overjet_mm);
  const std::vector<Eigen::Vector2d> moving = PlaneCurve(upper_L, lower, lower_L.origin_J);
  const Eigen::Vector2d incisal(0.0, settings.overjet_mm);
  a.fit_rms_before_mm = a.fit_rms_mm = RmsToCurve(target, moving);
  if (!settings.fit_curves) return a;
  const Eigen::Vector3d m = FitCurves(target, moving, incisal);
  std::vector<Eigen::Vector2d> moved;
  moved.reserve(moving.size());
  for (const auto& p : moving) moved.push_back(Move(m, incisal, p));
  // The fit turns (u, w) from lateral towards anterior: about lateral x anterior, which is
  // +-occlusal; yaw_deg is the same turn about occlusal (ArchShift's sign).
  const Eigen::Vector3d turn_axis = lower.lateral.cross(lower.anterior);
  const double yaw_deg = m.z() * turn_axis.dot(lower.occlusal) / kRadPerDeg;
  if (m.head<2>().norm() > settings.max_fit_shift_mm ||
      std::abs(yaw_deg) > settings.max_fit_yaw_deg) {
    char w[200];
    std::snprintf(w, sizeof w,
                  "the arch curve fit moved the upper %.1f mm and %.1f deg from the frames' "
                  "alignment (limits %.1f mm, %.1f deg); kept the frames' alignment",
                  m.head<2>().norm(), yaw_deg, settings.max_fit_shift_mm, settings.max_fit_yaw_deg);
    a.warnings.push_back(w);
    return a;
  }
  a.fit_lateral_mm = m.x();
  a.fit_anterior_mm = m.y();
  a.fit_yaw_deg = yaw_deg;
  a.fit_rms_mm = RmsToCurve(target, moved);
  const Eigen::Vector3d centre_L =
      lower_L.origin_J + incisal.x() * lower.lateral + incisal.y() * lower.anterior;
  const Eigen::Isometry3d fit =
      Eigen::Translation3d(m.x() * lower.lateral + m.y() * lower.anterior) *
      Eigen::Translation3d(centre_L) * Eigen::AngleAxisd(m.z(), turn_axis) *
      Eigen::Translation3d(-centre_L);
  a.X_LU = fit * a.X_LU_frames;
  return a;
}

ArchShift ShiftBetween(const Eigen::Isometry3d& X_LU_from, const Eigen::Isometry3d& X_LU_to,
                       const Eigen::Vector3d& p_LPivot, const JawArch& lower_L) {
  const Axes lower = Orthonormal(lower_L);
  const PoseParameters d = DecomposePose(X_LU_to, p_LPivot, X_LU_from);
  ArchShift s;
  s.lateral_mm = d.translation_mm.dot(lower.lateral);
  s.sagittal_mm = d.translation_mm.dot(lower.anterior);
  s.vertical_mm = d.translation_mm.dot(lower.occlusal);
  s.yaw_deg = d.rotation_deg.dot(lower.occlusal);
  s.pitch_deg = d.rotation_deg.dot(lower.lateral);
  s.roll_deg = d.rotation_deg.dot(lower.anterior);
  return s;
}

Eigen::Isometry3d ApplyShift(const Eigen::Isometry3d& X_LU_from, const ArchShift& shift,
                             const Eigen::Vector3d& p_LPivot, const JawArch& lower_L) {
  const Axes lower = Orthonormal(lower_L);
  PoseParameters d;
  d.translation_mm = shift.lateral_mm * lower.lateral + shift.sagittal_mm * lower.anterior +
                     shift.vertical_mm * lower.occlusal;
  d.rotation_deg = shift.yaw_deg * lower.occlusal + shift.pitch_deg * lower.lateral +
                   shift.roll_deg * lower.anterior;
  return ComposePose(d, p_LPivot, X_LU_from);
}

collision::ArchFrame FrameOf(const JawArch& lower_L) {
  const Axes lower = Orthonormal(lower_L);
  collision::ArchFrame f;
  f.origin_L = lower_L.origin_J;
  f.occlusal_L = lower.occlusal;
  f.anterior_L = lower.anterior;
  f.lateral_L = lower.lateral;
  double lo = 0.0, hi = 0.0;
  for (const auto& p : lower_L.curve_J) {
    lo = std::min(lo, (p - f.origin_L).dot(f.anterior_L));
    hi = std::max(hi, (p - f.origin_L).dot(f.anterior_L));
  }
  f.anterior_split_mm = hi - 0.35 * (hi - lo);
  return f;
}

}  // namespace occlude::planner
