// A case as `propose`, `refine` and `report` work on it: the meshes, the arch frame, the
// rotation pivot, the planner's oracle schedule, and the report's map fields, each built once
// on first use and kept (so `refine --watch` pays for the trees only once). Building steps
// that take over a second are reported on stderr.
//
// Frames: the session works on its jaw pair at the reference (session/jaw_pair.h: AtReference):
// lower in L, upper in U as the files give it, the synthetic pair's upper moved to L at its
// designed bite (like `occlude synth` case folders), so X_LU = identity is the pose as scanned;
// the arch frame and the pivot are taken at that pose. Poses in the config and in
// the outputs are about pivot_L (planner::ComposePose with the reference = identity).
#pragma once

#include <Eigen/Geometry>
#include <atomic>
#include <future>
#include <memory>
#include <optional>
#include <vector>

#include "base/progress.h"
#include "config/case_config.h"
#include "occlude/collision/memory_estimate.h"
#include "occlude/collision/signed_distance.h"
#include "occlude/planner/request.h"
#include "session/case_analysis.h"
#include "session/jaw_pair.h"
#include "session/near_cells.h"
#include "session/oracle_cache.h"
#include "session/session_region.h"

namespace occlude::app {

/// Arch frame for shares and views: EstimateArchFrame on the jaws at X_LU; with an up-axis
/// hint the occlusal axis is the hint and the anterior direction the estimate's, made
/// perpendicular.
collision::ArchFrame CaseArchFrame(const CaseConfig& config, const io::TriangleMesh& lower_L,
                                   const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU);

/// The voxel sizes of the planner's schedule for a config: coarse to fine, ending at the
/// config's voxel size ({0.8, 0.4, v} for v < 0.4, else {max(0.8, 2 v), v}).
std::vector<double> ScheduleVoxels(const CaseConfig& config);
/// The same schedule ending at `finest_mm`.
std::vector<double> ScheduleVoxels(double finest_mm);

/// Estimated peak memory of what a session of `config` builds when its finest voxel size
/// is `voxel_mm`: the oracles of the schedule ending there and the map fields.
collision::MemoryEstimate EstimateSessionMemory(const CaseConfig& config, const JawPair& jaws,
                                                double voxel_mm);

/// Exact distance fields of both meshes for the report's vertex maps. Exact distances do not
/// depend on a field's voxel size, so the lower's is the finest oracle's field when that oracle
/// models the whole lower jaw (the session owns it), else one of its own, as is the upper's.
/// With each, the cells near its mesh at the maps' reach (MapReachMm), which cull the vertices
/// searched.
struct MapFields {
  const collision::NarrowBandSdf& lower() const { return shared_lower ? *shared_lower : own_lower; }
  const collision::NarrowBandSdf& upper() const { return own_upper; }

  const collision::NarrowBandSdf* shared_lower = nullptr;
  collision::NarrowBandSdf own_lower, own_upper;
  NearCells lower_near, upper_near;  ///< of lower_L and upper_U, at lower_near.reach_mm()
};

class CaseSession {
 public:
  /// Loads the meshes of `config` (throws UserError naming the file), warns on stderr about
  /// odd jaw pairs (far apart, identical, in metres), and checks the memory of everything
  /// the session may build against the budget (memory_guard.h: `memory_budget_mb` > 0 is
  /// the command's --memory-budget-mb, else the config's limits, else the default).
  explicit CaseSession(const CaseConfig& config, double memory_budget_mb = 0);

  const CaseConfig& config() const { return config_; }
  const JawPair& jaws() const { return jaws_; }
  const collision::ArchFrame& arch() const { return arch_; }
  /// Replaces the arch frame the oracles are built with (e.g. the global search's, from the
  /// arch analysis); only before the first oracle is built (throws std::logic_error after).
  void UseArchFrame(const collision::ArchFrame& arch);
  /// The rotation pivot in L (at identity U = L): the config's pivot_mm or the centre of the
  /// upper arch's occlusal surface.
  const Eigen::Vector3d& pivot_L() const { return pivot_L_; }
  /// The start pose of the config about pivot_L().
  Eigen::Isometry3d ConfigStartPose() const;

  /// The planner's schedule (built on first use): ScheduleVoxels sub-voxel stages. With
  /// [accuracy] region_of_interest (the default) each oracle models only the region of
  /// interest of a search from ConfigStartPose() within the config's bounds, which answers as
  /// the whole jaws do at every pose of that search (collision/region_of_interest.h).
  const planner::OracleSchedule& Schedule();
  /// Frees the schedule and its oracles but the finest (which reports and evaluations read):
  /// for a command that searches once, then reports. A later Schedule() builds or loads them
  /// again. (a-bite-3shape: 137 of its 292 MB of oracles.)
  void ReleaseCoarseOracles();
  /// The finest oracle on the whole jaws, valid at any pose (the schedule's finest without
  /// region_of_interest, or when its region kept the whole jaws).
  const collision::JawOracle& FinestOracle();
  /// The finest oracle valid at X_LU: the whole-jaw one when already built, else the
  /// schedule's finest when its region covers X_LU (every upper vertex within the region's
  /// displacement of its place at the start pose), else FinestOracle().
  const collision::JawOracle& FinestOracleAt(const Eigen::Isometry3d& X_LU);
  /// The oracles built so far, in build order (for the report's settings).
  const std::vector<OracleModel>& Models() const { return models_; }
  /// True once the session has built an oracle rather than read it from the cache.
  bool BuiltOracles() const { return *built_oracles_; }
  /// The map fields (built on first use) with their near cells at the config's MapReachMm
  /// (built again when UpdateSettings changed it).
  const MapFields& Maps();

  /// True when `other` can reuse this session's models (same meshes, units, up axis, voxel
  /// sizes, sample spacing and pivot); otherwise a new session is needed.
  bool Reusable(const CaseConfig& other) const;
  /// Takes the non-model settings of `other` (band, limits, solver, bounds, start, adjust,
  /// output, report, landmarks: the given landmarks are read again) after Reusable(other).
  void UpdateSettings(const CaseConfig& other);

  /// The cache of the session's oracles and arch analyses (off: its folder is empty), for
  /// other products of the meshes alone (the 3D view's decimation).
  const std::shared_ptr<OracleCache>& cache() const { return cache_; }

  /// The arch analysis of both jaws (built on first use, the detection kept across
  /// UpdateSettings) with the config's given landmarks (landmarks_file, read when the session
  /// is made: a bad file throws UserError there), upper ones moved with the upper jaw.
  const CaseAnalysis& Analysis();
  /// Starts what needs the meshes alone, the detection of Analysis() and the upper jaw's field
  /// of Maps(), on threads of their own, so that they run while the caller loads oracles and
  /// settles a pose; Analysis() and Maps() then wait for them. Does nothing for what is done or
  /// under way.
  void Prefetch();

 private:
  CaseConfig config_;
  JawPair jaws_;
  collision::ArchFrame arch_;
  Eigen::Vector3d pivot_L_ = Eigen::Vector3d::Zero();
  /// One oracle per schedule stage, built on demand (the report needs only the finest).
  std::vector<std::unique_ptr<collision::JawOracle>> oracles_;
  planner::OracleSchedule stages_;
  const collision::JawOracle& Oracle(std::size_t index);
  /// What stage `index`'s oracle is made of: its options, the meshes it models (the whole jaws
  /// or the region's), its record so far and its step's label; prints the region's line.
  struct StageInputs {
    collision::OracleOptions options;
    std::shared_ptr<const io::TriangleMesh> lower, upper;
    OracleModel model;
    std::string what;
  };
  StageInputs PrepareStage(std::size_t index);
  /// The region of interest of the session's search for an oracle reading `band_mm`: read from
  /// the cache, else selected (the selector made on first use: its seconds into
  /// *selector_seconds) and saved.
  collision::RegionOfInterest SelectRegion(double band_mm, double* selector_seconds);
  /// The stage's oracle, read from the cache or built (thread-safe for different stages).
  std::unique_ptr<collision::JawOracle> BuildStage(const StageInputs& in);
  /// Keeps `oracle` as stage `index`'s and records what it models.
  void KeepStage(std::size_t index, StageInputs in, std::unique_ptr<collision::JawOracle> oracle);
  /// The schedule's finest oracle when built (never released), else null.
  const collision::JawOracle* BuiltScheduledFinest() const;
  std::unique_ptr<MapFields> maps_;  ///< may point into the finest oracle (never released)
  std::future<collision::NarrowBandSdf> upper_map_;  ///< Prefetch's, until Maps() takes it
  /// The lower field of a built oracle of the whole lower jaw at the finest voxel size, or null.
  const collision::NarrowBandSdf* WholeLowerField() const;
  // Region of interest (session_region.h): the whole-jaw finest oracle when asked for, and
  // what every oracle built holds.
  std::unique_ptr<collision::JawOracle> whole_finest_;
  std::vector<OracleModel> models_;
  /// Set by a build (reads, which may build a bad entry again, run on two threads); held by
  /// pointer so that the session stays movable.
  std::unique_ptr<std::atomic<bool>> built_oracles_ = std::make_unique<std::atomic<bool>>(false);
  /// The cache of oracles and arch analyses (config_'s cache settings); shared with the
  /// analysis's thread of Prefetch.
  std::shared_ptr<OracleCache> cache_;
  std::unique_ptr<collision::JawOracle> BuildOracle(std::shared_ptr<const io::TriangleMesh> lower_L,
                                                    std::shared_ptr<const io::TriangleMesh> upper_U,
                                                    const collision::OracleOptions& options,
                                                    const std::string& what);
  collision::RegionOfInterestRequest RegionRequest(double band_mm) const;
  /// The regions of every stage from one selection's bounds (made on the first region).
  std::unique_ptr<collision::RegionSelector> region_;
  // The arch analysis: given landmarks in the session's frames, detection, and both combined.
  std::vector<io::Landmark> given_;
  Eigen::Isometry3d X_LU_ref_loaded_ = Eigen::Isometry3d::Identity();
  std::unique_ptr<CaseAnalysis> detected_, analysis_;
  std::future<CaseAnalysis> detecting_;  ///< Prefetch's, until Analysis() takes it
  void ReadGiven();
};

}  // namespace occlude::app
