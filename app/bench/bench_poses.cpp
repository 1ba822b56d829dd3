// Benchmark poses (see bench_poses_internal.h).
#include <algorithm>
#include <cmath>
#include <random>

#include "bench/bench_poses_internal.h"
#include "occlude/angles.h"
#include "occlude/collision/arch_frame.h"

namespace occlude::app {
namespace {

// A unit vector perpendicular to `axis`.
Eigen::Vector3d Perpendicular(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d other =
      std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return axis.cross(other).normalized();
}

Eigen::Isometry3d RotationAbout(const Eigen::Vector3d& pivot_L, const Eigen::AngleAxisd& rotation) {
  return Eigen::Translation3d(pivot_L) * rotation * Eigen::Translation3d(-pivot_L);
}

}  // namespace

Eigen::Vector3d SweepPivotL(const BenchCase& bc) {
  return collision::UpperOcclusalCentre(*bc.upper_U, bc.X_LU_ref, bc.axis_L);
}

std::vector<std::vector<Eigen::Isometry3d>> SweepPoses(const BenchCase& bc,
                                                       const std::vector<double>& offsets_mm,
                                                       int reps, double jitter_deg,
                                                       double jitter_mm, std::uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d pivot_L = SweepPivotL(bc);
  const Eigen::Vector3d across = Perpendicular(bc.axis_L);
  std::vector<std::vector<Eigen::Isometry3d>> poses;
  for (const double offset : offsets_mm) {
    std::vector<Eigen::Isometry3d> at;
    for (int r = 0; r < std::max(1, reps); ++r) {
      Eigen::Isometry3d jitter = Eigen::Isometry3d::Identity();
      if (r > 0) {
        const Eigen::Vector3d axis =
            Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
        const double angle = RadiansFromDegrees(unit(rng) * jitter_deg);
        const double spin = unit(rng) * 2.0 * kPi;
        const Eigen::Vector3d t =
            Eigen::AngleAxisd(spin, bc.axis_L) * across * (unit(rng) * jitter_mm);
        jitter = Eigen::Translation3d(t) * RotationAbout(pivot_L, Eigen::AngleAxisd(angle, axis));
      }
      at.push_back(Eigen::Translation3d(offset * bc.axis_L) * jitter * bc.X_LU_ref);
    }
    poses.push_back(std::move(at));
  }
  return poses;
}

HapticTrajectory::HapticTrajectory(
    const BenchCase& bc, const Eigen::Vector3d& lateral_L, const Eigen::Vector3d& anterior_L,
    double seconds, std::uint32_t seed,
    const std::function<double(const Eigen::Isometry3d&)>& contact_offset, int keyframes)
    : case_(bc), seconds_(seconds) {
  // Sliding directions orthogonal to the axis.
  lateral_L_ = (lateral_L - lateral_L.dot(bc.axis_L) * bc.axis_L).normalized();
  anterior_L_ = bc.axis_L.cross(lateral_L_).normalized();
  if (anterior_L_.dot(anterior_L) < 0) anterior_L_ = -anterior_L_;
  pivot_L_ = SweepPivotL(bc);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  amp_lat_ = 0.2 + 0.2 * u(rng);
  amp_pro_ = 0.1 + 0.2 * u(rng);
  f_lat_ = 0.5 + u(rng);
  f_pro_ = 0.5 + u(rng);
  phase_ = 2.0 * kPi * u(rng);
  wobble_deg_ = 0.3 * u(rng);
  // Contact height on a keyframe grid over the sliding phase (t >= seconds / 4).
  const int n = std::max(2, keyframes);
  for (int k = 0; k < n; ++k) {
    const double t = seconds_ * (0.25 + 0.75 * k / (n - 1));
    key_t_.push_back(t);
    key_offset_.push_back(contact_offset(Slide(t)));
  }
}

Eigen::Isometry3d HapticTrajectory::Slide(double t) const {
  const double ts = std::max(0.0, t - 0.25 * seconds_);
  const double lat = amp_lat_ * std::sin(2.0 * kPi * f_lat_ * ts);
  const double pro =
      amp_pro_ * std::sin(2.0 * kPi * f_pro_ * ts + phase_) - amp_pro_ * std::sin(phase_);
  const double wobble = wobble_deg_ * kPi / 180.0 * std::sin(2.0 * kPi * 0.7 * ts);
  return Eigen::Translation3d(lat * lateral_L_ + pro * anterior_L_) *
         RotationAbout(pivot_L_, Eigen::AngleAxisd(wobble, anterior_L_)) * case_.X_LU_ref;
}

Eigen::Isometry3d HapticTrajectory::At(double t) const {
  t = std::clamp(t, 0.0, seconds_);
  double offset = 0.0;
  if (t < key_t_.front()) {  // descent from 2 mm open to the first contact height
    const double s = t / key_t_.front();
    offset = (1.0 - s) * 2.0 + s * key_offset_.front();
  } else {
    const auto it = std::upper_bound(key_t_.begin(), key_t_.end(), t);
    const std::size_t i =
        it == key_t_.end() ? key_t_.size() - 1 : static_cast<std::size_t>(it - key_t_.begin());
    const std::size_t j = i == 0 ? 0 : i - 1;
    const double span = key_t_[i] - key_t_[j];
    const double s = span > 0 ? (t - key_t_[j]) / span : 0.0;
    offset = (1.0 - s) * key_offset_[j] + s * key_offset_[i];
  }
  return Eigen::Translation3d(offset * case_.axis_L) * Slide(t);
}

}  // namespace occlude::app
