// The occlusal-axis sweep shared by `occlude demo` and `occlude collide --sweep`:
// the upper jaw moved along an axis through a reference pose (offset > 0 opens
// the bite), and at each offset the boolean, all-pairs and exact queries timed
// for each sphere mode (median and maximum of repeated runs, one thread).
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "base/timing.h"
#include "occlude/collision/collide.h"

namespace occlude::app {

struct SweepOptions {
  std::vector<double> offsets_mm = {5.0, 2.0,  1.0, 0.5,   0.3,  0.2,
                                    0.1, 0.05, 0.0, -0.05, -0.1, -0.2};
  Eigen::Vector3d axis_L = Eigen::Vector3d::UnitY();  ///< unit, lower -> upper
  double delta_mm = 0.1;
  int reps = 30;
  std::vector<collision::SphereMode> modes = {collision::SphereMode::kExplicit};
  bool exact = true;  ///< also time the exact refinement (explicit mode only)
};

struct SweepRow {
  double offset_mm = 0.0;
  collision::SphereMode mode = collision::SphereMode::kExplicit;
  bool overlap = false;
  Summary boolean_us, pairs_us, exact_us;
  std::size_t boolean_tests = 0, pairs_tests = 0, pairs = 0, contacts = 0;
  double min_distance_mm = 0.0;
  bool intersect = false;
  bool has_exact = false;
};

/// Runs the sweep; A = lower (frame L), B = upper (frame U); X_LU_ref is the bite.
std::vector<SweepRow> RunSweep(const collision::CollisionPair& pair,
                               const Eigen::Isometry3d& X_LU_ref, const SweepOptions& options);
/// A fixed-width table (header included), one line per row.
std::string SweepTable(const std::vector<SweepRow>& rows);
/// A JSON array, one object per row.
std::string SweepJson(const std::vector<SweepRow>& rows);

}  // namespace occlude::app
