// The synthetic dental arch curve: a squared horseshoe in the xz-plane of L, parameterised by
// arc length, round over the incisors, turning most at the canines and straight, parallel to the
// anterior axis, over the premolars and molars (see ArchCurve in synthetic_jaws_internal.h).
#include <algorithm>
#include <cmath>

#include "occlude/angles.h"
#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

/// F(u) on [0, 1]: 0 -> 1 with F'(1) = 0; the peaked part is the quintic smoothstep.
double TurnShare(const ArchCurve& arch, double u) {
  const double peaked = u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
  const double uniform = u * (2.0 - u);
  return (1.0 - arch.round_share) * peaked + arch.round_share * uniform;
}

/// F'(u).
double TurnRate(const ArchCurve& arch, double u) {
  const double peaked = 30.0 * u * u * (1.0 - u) * (1.0 - u);
  const double uniform = 2.0 - 2.0 * u;
  return (1.0 - arch.round_share) * peaked + arch.round_share * uniform;
}

/// Integral of the unit tangent over [a, b] by 5-point Gauss-Legendre, exact to ~1e-12 mm on
/// the 1 mm pieces ArchPoint uses.
Eigen::Vector2d TangentIntegral(const ArchCurve& arch, double a, double b) {
  static constexpr double kNodes[5] = {0.0, -0.5384693101056831, 0.5384693101056831,
                                       -0.9061798459386640, 0.9061798459386640};
  static constexpr double kWeights[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                         0.2369268850561891, 0.2369268850561891};
  const double half = 0.5 * (b - a);
  const double mid = 0.5 * (a + b);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (int k = 0; k < 5; ++k) sum += kWeights[k] * ArchTangent(arch, mid + half * kNodes[k]);
  return half * sum;
}

}  // namespace

double ArchAngle(const ArchCurve& arch, double s) {
  const double u = std::min(std::abs(s) / arch.bend_length, 1.0);
  return std::copysign(0.5 * kPi * TurnShare(arch, u), s);
}

Eigen::Vector2d ArchPoint(const ArchCurve& arch, double s) {
  // theta is odd in s, so x(s) is odd and z(s) even: integrate over [0, |s|] and mirror.
  const double bend = std::min(std::abs(s), arch.bend_length);
  constexpr double kPiece = 1.0;  // mm
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  for (double a = 0.0; a < bend; a += kPiece)
    p += TangentIntegral(arch, a, std::min(bend, a + kPiece));
  p.y() -= std::abs(s) - bend;  // the straight posterior segment runs along -z
  if (s < 0.0) p.x() = -p.x();
  p.y() += arch.z_offset;
  return p;
}

Eigen::Vector2d ArchTangent(const ArchCurve& arch, double s) {
  const double theta = ArchAngle(arch, s);
  return Eigen::Vector2d(std::cos(theta), -std::sin(theta));
}

Eigen::Vector2d ArchNormal(const ArchCurve& arch, double s) {
  const double theta = ArchAngle(arch, s);
  return Eigen::Vector2d(std::sin(theta), std::cos(theta));
}

double ArchCurvature(const ArchCurve& arch, double s) {
  const double u = std::abs(s) / arch.bend_length;
  return u >= 1.0 ? 0.0 : 0.5 * kPi * TurnRate(arch, u) / arch.bend_length;
}

double MaxArchCurvature(const ArchCurve& arch) {
  constexpr int kSamples = 1024;  // F' is a smooth quartic: sampled to 1e-6 relative
  double largest = 0.0;
  for (int k = 0; k <= kSamples; ++k) {
    largest = std::max(largest, ArchCurvature(arch, arch.bend_length * k / kSamples));
  }
  return largest * (1.0 + 1e-6);
}

}  // namespace occlude::io::synthetic
