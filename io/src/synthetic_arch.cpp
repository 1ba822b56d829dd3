// The synthetic dental arch curve: a smooth horseshoe in the xz-plane of L, parameterised by
// arc length (see ArchCurve in synthetic_jaws_internal.h).
#include <algorithm>
#include <cmath>

#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

double TangentAngle(const ArchCurve& arch, double s) {
  return arch.theta_max * std::tanh(s / arch.s_scale);
}

/// Integral of the unit tangent (cos theta, -sin theta) over [a, b] by 5-point Gauss-Legendre,
/// exact to ~1e-12 mm on the 1 mm pieces ArchPoint uses.
Eigen::Vector2d TangentIntegral(const ArchCurve& arch, double a, double b) {
  static constexpr double kNodes[5] = {0.0, -0.5384693101056831, 0.5384693101056831,
                                       -0.9061798459386640, 0.9061798459386640};
  static constexpr double kWeights[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                         0.2369268850561891, 0.2369268850561891};
  const double half = 0.5 * (b - a);
  const double mid = 0.5 * (a + b);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (int k = 0; k < 5; ++k) {
    const double theta = TangentAngle(arch, mid + half * kNodes[k]);
    sum += kWeights[k] * Eigen::Vector2d(std::cos(theta), -std::sin(theta));
  }
  return half * sum;
}

}  // namespace

Eigen::Vector2d ArchPoint(const ArchCurve& arch, double s) {
  // theta is odd in s, so x(s) is odd and z(s) even: integrate over [0, |s|] and mirror.
  const double length = std::abs(s);
  constexpr double kPiece = 1.0;  // mm
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  double a = 0.0;
  while (a < length) {
    const double b = std::min(length, a + kPiece);
    p += TangentIntegral(arch, a, b);
    a = b;
  }
  if (s < 0.0) p.x() = -p.x();
  p.y() += arch.z_offset;
  return p;
}

Eigen::Vector2d ArchNormal(const ArchCurve& arch, double s) {
  const double theta = TangentAngle(arch, s);
  return Eigen::Vector2d(std::sin(theta), std::cos(theta));
}

double ArchCurvature(const ArchCurve& arch, double s) {
  const double c = std::cosh(s / arch.s_scale);
  return arch.theta_max / (arch.s_scale * c * c);
}

}  // namespace occlude::io::synthetic
