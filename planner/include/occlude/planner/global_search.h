// The global occlusion search: every distinct intercuspation of two arches,
// without a start pose. The upper is aligned onto the lower from their arches
// (arch_alignment.h); a scan over the sagittal shift along the arch, the
// lateral shift, yaw and pitch about the aligned pose settles each pose along
// the occlusal axis on the coarse stage and scores it; the local optima of the
// scan (the basins) go through the local search's coarse stage, the best
// distinct ones through the finer stages (plan.h's coarse-to-fine chain), and
// the distinct seats come back best first, each with its shift from the
// aligned pose. Also the seat of a pose: where the local search goes from it.
//
// A request of its own (not a scope flag in PlanRequest): the global search needs the two
// arches and the scan's ranges, and has no start pose or bounds of its own; the local
// settings each basin is refined with are a PlanRequest inside it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

#include "occlude/planner/arch_alignment.h"
#include "occlude/planner/plan.h"
#include "occlude/planner/seat_ranking.h"

namespace occlude::planner {

/// The scan's grid about the aligned pose: per axis the values k * step with |k * step| <=
/// range (a range of 0, or a step over the range, gives the one value 0); sagittal along the
/// lower's anterior axis, lateral along its lateral axis, yaw about its occlusal axis and pitch
/// about its lateral axis, both through the pivot.
struct GlobalScanSettings {
  double sagittal_range_mm = 15.0;
  double sagittal_step_mm = 1.0;
  double lateral_range_mm = 1.5;
  double lateral_step_mm = 1.5;
  double yaw_range_deg = 4.0;
  double yaw_step_deg = 4.0;
  double pitch_range_deg = 3.0;
  double pitch_step_deg = 3.0;
  /// Each grid pose starts this far open along the occlusal axis before the settle closes it.
  double open_mm = 2.0;
  /// Sample spacing of the scan's occlusal samples on the coarse stage (coarser than the
  /// stage's own: the scan asks only which poses interdigitate).
  double sample_spacing_mm = 1.0;
  /// Local optima of the scan sent through the coarse stage, and of those the best distinct
  /// ones refined on the finer stages.
  int max_basins = 12;
  int max_refined = 6;
};

struct GlobalRequest {
  JawArch lower_L;  ///< the lower arch in L
  JawArch upper_U;  ///< the upper arch in U
  AlignmentSettings alignment;
  GlobalScanSettings scan;
  /// The local search each basin is refined with: solver (kCoarseToFine; kNloptGlobal also
  /// walks the stages; the single-stage solvers refine the best max_refined basins on the last
  /// stage only), band, penetration, seat objective, distinct thresholds, threads, seed,
  /// max_evaluations; each seat is polished (PlanRequest::polish, always on here). Its bounds widen
  /// the search's box (relative to the aligned pose, on every axis: the scan's largest range plus
  /// open_mm plus the largest bound; rotations the largest scan angle plus the largest bound, at
  /// most 90 deg). X_LU_start is the pose as given: it only sets GlobalProposal::from_given.
  /// max_proposals: the seats returned. num_starts, num_global_samples, pivot_L, locked,
  /// max_seconds and on_progress are not used.
  PlanRequest local;
  /// The clinical ranking of the distinct seats (seat_ranking.h): every distinct refined seat is
  /// judged, the inadmissible ones go to GlobalResult::excluded, the rest ranked, and the best
  /// local.max_proposals returned. Without a judge: by seat cost.
  SeatRanking ranking;
  /// Called serialized from the search's threads: phase, work done, work in the phase.
  enum class Phase { kScan, kBasins, kRefine };
  std::function<void(Phase phase, int done, int total)> on_progress;
};
const char* ToString(GlobalRequest::Phase phase);

/// Throws std::invalid_argument naming the first invalid field ("GlobalRequest.scan....",
/// the arches, the alignment, or the local request's) and how to fix it.
void ValidateGlobalRequest(const GlobalRequest& request);

/// A local optimum of the scan.
struct ScanBasin {
  ArchShift shift;                ///< grid pose relative to the aligned pose (settled: vertical)
  double seat_cost = 0.0;         ///< on the scan's samples, settled (lower is better)
  double contact_area_mm2 = 0.0;  ///< on the scan's samples (within the contact band)
};

struct GlobalResult {
  ArchAlignment alignment;
  Eigen::Vector3d pivot_L = Eigen::Vector3d::Zero();  ///< the pivot (L, at the aligned pose)
  std::vector<ScanBasin> basins;                      ///< best first (scan seat cost)
  std::vector<GlobalProposal> proposals;  ///< distinct seats as request.ranking ranks them
  std::vector<GlobalProposal> excluded;   ///< distinct seats the judge found inadmissible
  std::vector<std::string> warnings;      ///< e.g. the curve fit rejected, no feasible seat found
  int scan_poses = 0;
  int total_evaluations = 0;
  /// Thread CPU seconds (all threads): the whole search and its phases (the alignment and
  /// the sample sets are in the total only).
  double cpu_seconds = 0.0, scan_cpu_seconds = 0.0, basins_cpu_seconds = 0.0,
         refine_cpu_seconds = 0.0;
  double wall_seconds = 0.0;
};

/// Runs the global search on a schedule (coarse first; at least one stage; the oracles built
/// on the whole jaws, the upper in its frame U; give the oracles' OracleOptions::arch as
/// FrameOf(lower_L) so that their left/right shares agree). Throws std::invalid_argument for
/// an invalid request or schedule. Never returns a non-finite pose; infeasible seats keep
/// status kInfeasible. The result depends on the request and schedule only, not on the
/// thread count, and not on local.X_LU_start.
GlobalResult GlobalSearch(const OracleSchedule& schedule, const GlobalRequest& request);

/// The seat of a pose: the proposal the local search (`settings`: its solver and stages, one
/// start, no global samples, bounds relative to X_LU) reaches from X_LU. Throws like Plan.
Proposal SeatOf(const OracleSchedule& schedule, const Eigen::Isometry3d& X_LU,
                const PlanRequest& settings = {});

}  // namespace occlude::planner
