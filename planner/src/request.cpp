// Names of the solver settings, request validation and the schedule of
// oracles the planner can build for itself.
#include "occlude/planner/request.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace occlude::planner {

const char* ToString(SolverKind kind) {
  switch (kind) {
    case SolverKind::kNloptLocal:
      return "nlopt-local";
    case SolverKind::kNloptGlobal:
      return "nlopt-global";
    case SolverKind::kCeres:
      return "ceres";
    case SolverKind::kCoarseToFine:
      return "coarse-to-fine";
  }
  return "?";
}

SolverKind SolverKindFromName(const std::string& name) {
  for (SolverKind k : {SolverKind::kNloptLocal, SolverKind::kNloptGlobal, SolverKind::kCeres,
                       SolverKind::kCoarseToFine}) {
    if (name == ToString(k)) return k;
  }
  throw std::invalid_argument("solver: unknown name '" + name +
                              "'; use nlopt-local, nlopt-global, ceres or coarse-to-fine");
}

const char* ToString(NloptLocalMethod method) {
  switch (method) {
    case NloptLocalMethod::kCobyla:
      return "cobyla";
    case NloptLocalMethod::kAuglagBobyqa:
      return "auglag-bobyqa";
    case NloptLocalMethod::kAuglagSbplx:
      return "auglag-sbplx";
  }
  return "?";
}

NloptLocalMethod NloptLocalMethodFromName(const std::string& name) {
  for (NloptLocalMethod m : {NloptLocalMethod::kCobyla, NloptLocalMethod::kAuglagBobyqa,
                             NloptLocalMethod::kAuglagSbplx}) {
    if (name == ToString(m)) return m;
  }
  throw std::invalid_argument("nlopt_local: unknown method '" + name +
                              "'; use cobyla, auglag-bobyqa or auglag-sbplx");
}

const char* ToString(PenetrationMeasure measure) {
  switch (measure) {
    case PenetrationMeasure::kMax:
      return "max";
    case PenetrationMeasure::kOutlierArea:
      return "outlier-area";
    case PenetrationMeasure::kPercentile:
      return "percentile";
  }
  return "?";
}

void ValidateRequest(const PlanRequest& r) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("PlanRequest." + what); };
  auto finite_pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!r.X_LU_start.matrix().allFinite()) fail("X_LU_start: must be finite");
  if (!(std::isfinite(r.contact_band_mm) && r.contact_band_mm >= 0.0 && r.contact_band_mm <= 5.0)) {
    fail("contact_band_mm: must be in [0, 5] mm (default 0.1)");
  }
  if (!(std::isfinite(r.max_penetration_mm) && r.max_penetration_mm >= 0.0)) {
    fail("max_penetration_mm: must be finite and >= 0 (default 0.05)");
  }
  if (!(std::isfinite(r.outlier_area_mm2) && r.outlier_area_mm2 >= 0.0)) {
    fail("outlier_area_mm2: must be finite and >= 0 (0 disables outliers)");
  }
  if (!(r.penetration_percentile > 0.0 && r.penetration_percentile <= 100.0)) {
    fail("penetration_percentile: must be in (0, 100]");
  }
  if (!finite_pos(r.attraction_range_mm) || r.attraction_range_mm <= r.contact_band_mm) {
    fail("attraction_range_mm: must be finite and above contact_band_mm (default 0.6)");
  }
  if (!(std::isfinite(r.spike_patch_max_mm2) && r.spike_patch_max_mm2 >= 0.0)) {
    fail("spike_patch_max_mm2: must be finite and >= 0 (0 turns spike patches off; default 5)");
  }
  if (!(std::isfinite(r.max_seconds) && r.max_seconds >= 0.0))
    fail("max_seconds: must be finite and >= 0 (0 = no budget)");
  if (!finite_pos(r.seat_window_mm)) fail("seat_window_mm: must be finite and > 0 (default 1.0)");
  if (!finite_pos(r.seat_scale_mm)) fail("seat_scale_mm: must be finite and > 0 (default 0.3)");
  if (!(std::isfinite(r.seat_penetration_allowance_mm) && r.seat_penetration_allowance_mm >= 0.0)) {
    fail("seat_penetration_allowance_mm: must be finite and >= 0 (default 0.02)");
  }
  if (!(r.seat_min_facing >= -1.0 && r.seat_min_facing <= 1.0))
    fail("seat_min_facing: must be in [-1, 1] (default 0.6)");
  if (!(r.bilateral_posterior_weight >= 0.0 && r.bilateral_posterior_weight <= 1.0)) {
    fail("bilateral_posterior_weight: must be in [0, 1]");
  }
  for (int i = 0; i < 3; ++i) {
    if (!(r.lower_bound.translation_mm[i] <= 0.0 && r.upper_bound.translation_mm[i] >= 0.0 &&
          std::isfinite(r.lower_bound.translation_mm[i]) &&
          std::isfinite(r.upper_bound.translation_mm[i]))) {
      fail("lower_bound/upper_bound translation " + std::to_string(i) +
           ": need finite lower <= 0 <= upper (mm, relative to the start pose)");
    }
    if (!(r.lower_bound.rotation_deg[i] <= 0.0 && r.upper_bound.rotation_deg[i] >= 0.0 &&
          r.lower_bound.rotation_deg[i] >= -90.0 && r.upper_bound.rotation_deg[i] <= 90.0)) {
      fail("lower_bound/upper_bound rotation " + std::to_string(i) +
           ": need -90 <= lower <= 0 <= upper <= 90 (deg, relative to the start pose)");
    }
  }
  if (r.pivot_L && !r.pivot_L->allFinite()) fail("pivot_L: must be finite");
  if (r.num_starts < 1 || r.num_starts > 1000) fail("num_starts: must be in [1, 1000]");
  if (r.num_global_samples < 0 || r.num_global_samples > 100000) {
    fail("num_global_samples: must be in [0, 100000]");
  }
  if (r.num_threads < 1 || r.num_threads > 256) fail("num_threads: must be in [1, 256]");
  if (r.max_proposals < 1) fail("max_proposals: must be >= 1");
  if (!(r.distinct_translation_mm >= 0.0) || !(r.distinct_rotation_deg >= 0.0)) {
    fail("distinct_translation_mm / distinct_rotation_deg: must be >= 0");
  }
  if (r.max_evaluations < 10) fail("max_evaluations: must be >= 10");
}

collision::OracleOptions StageOracleOptions(const collision::OracleOptions& base,
                                            const std::vector<double>& voxel_sizes_mm,
                                            std::size_t index) {
  collision::OracleOptions o = base;
  o.voxel_size_mm = voxel_sizes_mm.at(index);
  // The first of several stages is the wide one: its field reaches kCoarseBandMm so that the
  // seat objective pulls far starts in (the finer stages only refine).
  if (index == 0 && voxel_sizes_mm.size() > 1) {
    o.sdf_dilation_voxels = std::max(o.sdf_dilation_voxels,
                                     static_cast<int>(std::ceil(kCoarseBandMm / o.voxel_size_mm)));
  }
  return o;
}

OwnedSchedule BuildSchedule(const std::shared_ptr<const io::TriangleMesh>& lower_L,
                            const std::shared_ptr<const io::TriangleMesh>& upper_U,
                            const std::vector<double>& voxel_sizes_mm, bool exact_last,
                            const collision::OracleOptions& base_options) {
  if (voxel_sizes_mm.empty()) {
    throw std::invalid_argument("BuildSchedule: voxel_sizes_mm is empty; give e.g. {0.8, 0.4}");
  }
  OwnedSchedule s;
  for (const double v : voxel_sizes_mm) {
    if (!(std::isfinite(v) && v > 0.0)) {
      throw std::invalid_argument("BuildSchedule: voxel size " + std::to_string(v) +
                                  " must be > 0 mm");
    }
    const collision::OracleOptions o =
        StageOracleOptions(base_options, voxel_sizes_mm, s.oracles.size());
    s.oracles.push_back(std::make_unique<collision::JawOracle>(lower_L, upper_U, o));
    s.stages.push_back({s.oracles.back().get(), collision::AccuracyLevel::kSubVoxel});
  }
  if (exact_last) s.stages.push_back({s.oracles.back().get(), collision::AccuracyLevel::kExact});
  return s;
}

}  // namespace occlude::planner
