// Poses the benchmark replays: the jittered occlusal-axis sweep and the haptic
// trajectory (descent into the bite, then sliding in contact). Seeded and
// deterministic, so every method sees exactly the same poses.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <vector>

#include "bench/bench.h"

namespace occlude::app {

/// For each offset (mm along bench_case.axis_L from the bite), `reps` poses
/// X_LU: the first exactly on the axis, the others with a seeded rigid jitter
/// (rotation up to jitter_deg about the upper jaw's centroid, translation up to
/// jitter_mm across the axis).
std::vector<std::vector<Eigen::Isometry3d>> SweepPoses(const BenchCase& bench_case,
                                                       const std::vector<double>& offsets_mm,
                                                       int reps, double jitter_deg,
                                                       double jitter_mm, std::uint32_t seed);

/// The haptic trajectory as a function of time t in [0, seconds]: the first
/// quarter descends along the axis from 2 mm open to the contact height, the
/// rest slides laterally and protrusively (seeded amplitudes up to 0.4 mm and
/// frequencies 0.5-1.5 Hz, a small rotation wobble) while staying at the
/// contact height, which `contact_offset` gives for a lateral/protrusive
/// displacement (mm in L; evaluated on a keyframe grid before the replay and
/// interpolated, so the replay itself costs nothing).
class HapticTrajectory {
 public:
  HapticTrajectory(const BenchCase& bench_case, const Eigen::Vector3d& lateral_L,
                   const Eigen::Vector3d& anterior_L, double seconds, std::uint32_t seed,
                   const std::function<double(const Eigen::Isometry3d& X_LU_slid)>& contact_offset,
                   int keyframes = 48);
  Eigen::Isometry3d At(double t) const;
  double seconds() const { return seconds_; }

 private:
  Eigen::Isometry3d Slide(double t) const;  // lateral/protrusive/wobble part, no vertical offset

  BenchCase case_;
  Eigen::Vector3d lateral_L_, anterior_L_, pivot_L_;
  double seconds_;
  double amp_lat_, amp_pro_, f_lat_, f_pro_, phase_, wobble_deg_;
  std::vector<double> key_t_, key_offset_;
};

/// The pivot of the sweep jitter and the haptic wobble: the centre of the upper occlusal surface
/// (collision::UpperOcclusalCentre) in L at the bite.
Eigen::Vector3d SweepPivotL(const BenchCase& bench_case);

}  // namespace occlude::app
