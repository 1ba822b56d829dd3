// `occlude validate`: how well each solver finds a known bite again. The upper jaw of a case
// with a registered bite (a case folder in occlusion, or the synthetic pair at its designed
// bite) is perturbed by seeded random rigid transforms at several magnitudes, and every
// solver runs from every perturbed start. Each run is scored against the reference pose:
// translation error = the largest displacement, between the found and the reference pose, of
// the occlusal pivot and the incisor and left/right molar reference points; rotation error =
// the angle of the relative rotation. Summaries per solver and magnitude: median and 95th
// percentile errors, success rate (within success_mm and success_deg), time, and the
// consensus: the medoid of the found poses and how tightly the runs gather around it
// (repeatability, which does not assume that the reference is the optimum). The reference
// check then asks whether the reference is an optimum at all (ReferenceCheck).
//
// Perturbations: translation uniform in the ball of radius magnitude_mm, rotation vector
// uniform in the ball of radius magnitude_deg (about the pivot), seeded per (magnitude, start)
// and shared by all solvers. Magnitude 0:0 starts at the reference itself: a closing run (the
// errors are then how far the search moved, e.g. on the open-bite case).
// Each run is single-threaded and timed in thread CPU time; runs go in parallel over threads.
#pragma once

#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "config/clinical_targets.h"
#include "occlude/planner/global_search.h"
#include "occlude/planner/plan.h"
#include "session/jaw_pair.h"

namespace occlude::app {

struct Magnitude {
  double mm = 0.0;
  double deg = 0.0;
};
/// "1:2,2:3,5:10" -> magnitudes; throws UserError naming --magnitudes on bad text.
std::vector<Magnitude> ParseMagnitudes(const std::string& text);

struct ValidateOptions {
  std::vector<planner::SolverKind> solvers = {
      planner::SolverKind::kCeres, planner::SolverKind::kCoarseToFine,
      planner::SolverKind::kNloptLocal, planner::SolverKind::kNloptGlobal};
  int starts = 20;  ///< perturbed starts per magnitude
  std::vector<Magnitude> magnitudes = {{1.0, 2.0}, {2.0, 3.0}, {5.0, 10.0}};
  std::uint32_t seed = 1;
  std::vector<double> voxels_mm = {0.8, 0.4};  ///< oracle schedule, coarse first
  bool exact_last = false;                     ///< add an exact-distance last stage
  int threads = 0;          ///< runs in parallel (each single-threaded); 0 = all cores
  int solver_starts = 4;    ///< internal starts of coarse-to-fine and nlopt-global
  int global_samples = 16;  ///< their global stage's sampled poses
  planner::NloptLocalMethod nlopt_local = planner::PlanRequest{}.nlopt_local;
  double contact_band_mm = 0.1;
  double max_penetration_mm = 0.05;
  double bound_margin_mm = 1.5;  ///< search bounds: the magnitude plus these margins
  double bound_margin_deg = 3.0;
  double success_mm = 0.3, success_deg = 1.0;
  int path_steps = 20;          ///< poses on the reference check's path (ReferenceCheck)
  std::ostream* log = nullptr;  ///< progress lines
  /// `--global` only (validate_global.h): the global search's scan, the start kinds run (of
  /// GlobalStartKinds(), in that order), the cusp kind's shift and the clinical targets the
  /// seats are ranked by (the default ranking unless `--clinical FILE`).
  planner::GlobalScanSettings global_scan;
  std::vector<std::string> global_kinds = {"near", "sagittal", "apart"};
  double cusp_period_mm = 7.0;
  ClinicalTargets clinical;
};

struct ValidateRun {
  planner::SolverKind solver = planner::SolverKind::kCeres;
  Magnitude magnitude;
  int start = 0;
  planner::PoseError start_error;  ///< of the perturbed start
  planner::PoseError error;        ///< of the found pose
  planner::PoseParameters found;   ///< found pose relative to the reference, about the pivot
  double max_penetration_mm = 0.0, constrained_penetration_mm = 0.0;
  double contact_area_mm2 = 0.0;
  std::size_t contact_samples = 0, outliers = 0;
  std::string status;
  int evaluations = 0;
  double seconds = 0.0;  ///< thread CPU time of the run
  bool success = false;
  double consensus_mm = 0.0;  ///< displacement from the medoid of its solver and magnitude
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();
};

struct ValidateSummary {
  planner::SolverKind solver = planner::SolverKind::kCeres;
  Magnitude magnitude;
  int runs = 0;
  double success_rate = 0.0;
  double median_err_mm = 0.0, p95_err_mm = 0.0, median_err_deg = 0.0, p95_err_deg = 0.0;
  double median_seconds = 0.0;
  double worst_penetration_mm = 0.0;      ///< largest constrained (outlier-robust) penetration
  double worst_max_penetration_mm = 0.0;  ///< largest true maximum
  planner::PoseError medoid_error;        ///< the consensus pose against the reference
  double median_consensus_mm = 0.0;       ///< spread of the runs about the consensus
  double within_consensus = 0.0;          ///< share of runs within success_mm / success_deg of it
  double medoid_contact_mm2 = 0.0;
};

/// Is the reference pose an optimum of the objective at all? The straight path from it to
/// the consensus of every run (the medoid of all found poses), evaluated on the last stage.
/// A pose on it beyond the success bar that dominates the reference (more contact, no deeper
/// penetration: planner::Dominates) is preferred to the reference by every objective that
/// rewards contact and penalizes penetration: errors against the reference then measure the
/// reference, not the solvers. Dominating poses within the bar (a reference a few hundredths
/// of a millimetre short of its seat) do not; not dominated along this path is no proof of
/// optimality.
struct ReferenceCheck {
  Eigen::Isometry3d X_LU_consensus = Eigen::Isometry3d::Identity();
  planner::PoseError consensus_error;  ///< the consensus against the reference
  std::vector<planner::PathPoint>
      path;  ///< s = 0: the reference, s = 1: the consensus (last stage)
  int nearest_dominating =
      -1;  ///< index in `path` of the first pose dominating the reference; -1: none
  int nearest_dominating_beyond_bar = -1;  ///< the first one beyond the success bar; -1: none
  int most_contact_dominating = -1;        ///< the dominating pose with the most contact; -1: none
};

struct ValidateResult {
  std::string case_name;
  std::vector<ValidateRun> runs;
  std::vector<ValidateSummary> summary;
  planner::PoseEvaluation reference;  ///< the reference pose as given, on the last stage
  ReferenceCheck reference_check;
  double build_seconds = 0.0;
};

ValidateResult RunValidation(const JawPair& jaws, const ValidateOptions& options);

std::string ValidateCsv(const ValidateResult& result);
std::string ValidateSummaryCsv(const ValidateResult& result);
/// The reference check's path: s, distance from the reference, contact, penetration, dominates.
std::string ReferencePathCsv(const ValidateResult& result);
/// Human-readable summary with the settings, the reference pose's own contact and
/// penetration, and the machine.
std::string ValidateSummaryText(const ValidateResult& result, const ValidateOptions& options,
                                const std::string& machine);
/// Charts (file, PNG bytes): stability (success rate against magnitude, one line per solver),
/// error (median and 95th percentile against magnitude), time against error (every run).
std::vector<std::pair<std::string, std::string>> ValidateCharts(const ValidateResult& result,
                                                                const ValidateOptions& options,
                                                                const std::string& subtitle);

}  // namespace occlude::app
